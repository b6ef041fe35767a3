// GpuQueries (internal): the asynchronous GPU height queries of OceanRenderer (Ocean.h queueHeights /
// takeHeights). A ring of GPU_QUERY_RING batches; each batch is queued (points copied), evaluated by the
// next render() that draws its ocean (sea_query.comp, a compute pass writing the batch's buffer, then a
// fence), and taken once the fence has signalled (glClientWaitSync with a zero timeout: no stall).
// Buffers grow to the largest batch and are reused: steady state allocates nothing.
#pragma once

#include "engine/gl/GlObjects.h"
#include "ocean/Ocean.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace pacifica::ocean {

class GpuQueries {
public:
    static constexpr size_t RING = GPU_QUERY_RING;

    GpuQueries() = default;
    ~GpuQueries();
    GpuQueries(const GpuQueries&) = delete;
    GpuQueries& operator=(const GpuQueries&) = delete;

    /// Copies the points (finite; std::invalid_argument naming the first that is not) into a free slot, or
    /// the oldest slot not taken (its points counted as dropped). Returns the batch's ticket.
    std::uint64_t queue(std::uint64_t oceanId, std::span<const glm::dvec2> points);
    /// Batches of this ocean waiting for a render().
    bool waiting(std::uint64_t oceanId) const;
    /// Evaluates this ocean's waiting batches with the compute `program` (in use, the model's uniforms set)
    /// relative to the camera at cameraOrigin: uploads each, dispatches, fences. Returns the batches
    /// evaluated. The caller restores the GL state.
    int evaluate(std::uint64_t oceanId, const glm::dvec3& cameraOrigin, unsigned program);
    /// Copies the answers of `ticket` into heights (as long as its points; std::invalid_argument otherwise,
    /// or for a ticket not pending) if the GPU has finished them; false (nothing copied) if not yet.
    bool take(std::uint64_t ticket, std::span<double> heights);
    const GpuQueryCounters& counters() const { return mCounters; }

private:
    enum class State { Free, Queued, InFlight };
    struct Slot {
        State state = State::Free;
        std::uint64_t ticket = 0, oceanId = 0;
        std::vector<glm::dvec2> points; // queued, world metres
        std::vector<glm::vec2> rel;     // uploaded, camera-relative
        std::vector<float> heights;     // read back
        size_t capacity = 0;            // points the buffers hold
        gl::Buffer input, output;
        void* fence = nullptr; // GLsync
    };
    void release(Slot& slot);

    std::array<Slot, RING> mSlots;
    std::uint64_t mNextTicket = 1;
    GpuQueryCounters mCounters;
};

} // namespace pacifica::ocean
