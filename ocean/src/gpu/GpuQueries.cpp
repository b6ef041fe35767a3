// GpuQueries: the asynchronous GPU height queries (GpuQueries.h).
#include "gpu/GpuQueries.h"

#include "gpu/GpuInterface.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pacifica::ocean {

namespace {
constexpr size_t SEA_QUERY_GROUP = 64; ///< sea_query.comp's local_size_x
} // namespace

GpuQueries::~GpuQueries() {
    for (Slot& s : mSlots)
        release(s);
}

void GpuQueries::release(Slot& slot) {
    if (slot.fence) {
        glDeleteSync(static_cast<GLsync>(slot.fence));
        gl::noteDeleted(gl::ObjectKind::Sync);
    }
    slot.fence = nullptr;
    slot.state = State::Free;
    slot.ticket = 0;
}

std::uint64_t GpuQueries::queue(std::uint64_t oceanId, std::span<const glm::dvec2> points) {
    for (size_t i = 0; i < points.size(); ++i)
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y))
            throw std::invalid_argument("queueHeights(): points[" + std::to_string(i) + "] is not finite");
    auto free =
        std::find_if(mSlots.begin(), mSlots.end(), [](const Slot& s) { return s.state == State::Free; });
    if (free == mSlots.end()) { // the ring is full: the oldest batch not taken makes room
        free = std::min_element(mSlots.begin(), mSlots.end(),
                                [](const Slot& a, const Slot& b) { return a.ticket < b.ticket; });
        mCounters.dropped += free->points.size();
        release(*free);
    }
    free->state = State::Queued;
    free->ticket = mNextTicket++;
    free->oceanId = oceanId;
    free->points.assign(points.begin(), points.end());
    mCounters.queued += points.size();
    return free->ticket;
}

bool GpuQueries::waiting(std::uint64_t oceanId) const {
    return std::any_of(mSlots.begin(), mSlots.end(),
                       [&](const Slot& s) { return s.state == State::Queued && s.oceanId == oceanId; });
}

int GpuQueries::evaluate(std::uint64_t oceanId, const glm::dvec3& cameraOrigin, unsigned program) {
    const GLint count = glGetUniformLocation(program, "uQueryCount");
    int batches = 0;
    for (Slot& s : mSlots) {
        if (s.state != State::Queued || s.oceanId != oceanId)
            continue;
        const size_t n = s.points.size();
        // Camera-relative in double first, then float (the surface's GLSL takes camera-relative points).
        s.rel.resize(n);
        for (size_t i = 0; i < n; ++i)
            s.rel[i] = glm::vec2(s.points[i] - glm::dvec2(cameraOrigin));
        if (n > s.capacity) {
            s.capacity = std::max<size_t>(n, 2 * s.capacity);
            s.input = gl::Buffer::create(s.capacity * sizeof(glm::vec2), nullptr, GL_DYNAMIC_STORAGE_BIT);
            s.output = gl::Buffer::create(s.capacity * sizeof(float), nullptr, 0);
        }
        if (n > 0) {
            glNamedBufferSubData(s.input.id(), 0, static_cast<GLsizeiptr>(n * sizeof(glm::vec2)),
                                 s.rel.data());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SEA_QUERY_POINTS_BINDING, s.input.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SEA_QUERY_HEIGHTS_BINDING, s.output.id());
            glProgramUniform1ui(program, count, static_cast<GLuint>(n));
            glDispatchCompute(static_cast<GLuint>((n + SEA_QUERY_GROUP - 1) / SEA_QUERY_GROUP), 1, 1);
        }
        // The readback (glGetNamedBufferSubData in take()) sees the shader's writes after this barrier.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        s.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        gl::noteCreated(gl::ObjectKind::Sync);
        s.state = State::InFlight;
        mCounters.evaluated += n;
        ++batches;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SEA_QUERY_POINTS_BINDING, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SEA_QUERY_HEIGHTS_BINDING, 0);
    return batches;
}

bool GpuQueries::take(std::uint64_t ticket, std::span<double> heights) {
    auto slot = std::find_if(mSlots.begin(), mSlots.end(),
                             [&](const Slot& s) { return s.state != State::Free && s.ticket == ticket; });
    if (slot == mSlots.end())
        throw std::invalid_argument("takeHeights(): ticket " + std::to_string(ticket) +
                                    " is not pending (taken, dropped from a full ring, or never queued)");
    if (heights.size() != slot->points.size())
        throw std::invalid_argument("takeHeights(): ticket " + std::to_string(ticket) + " has " +
                                    std::to_string(slot->points.size()) + " points but heights holds " +
                                    std::to_string(heights.size()));
    if (slot->state == State::Queued) { // no render() has drawn its ocean yet
        ++mCounters.notReady;
        return false;
    }
    // Flush: an unflushed fence need never signal (a headless host that never swaps would wait forever).
    const GLenum wait = glClientWaitSync(static_cast<GLsync>(slot->fence), GL_SYNC_FLUSH_COMMANDS_BIT, 0);
    if (wait == GL_TIMEOUT_EXPIRED) {
        ++mCounters.notReady;
        return false;
    }
    if (wait == GL_WAIT_FAILED)
        throw std::runtime_error("takeHeights(): glClientWaitSync failed");
    const size_t n = slot->points.size();
    slot->heights.resize(n);
    if (n > 0)
        glGetNamedBufferSubData(slot->output.id(), 0, static_cast<GLsizeiptr>(n * sizeof(float)),
                                slot->heights.data());
    std::copy(slot->heights.begin(), slot->heights.end(), heights.begin());
    mCounters.answered += n;
    release(*slot);
    return true;
}

} // namespace pacifica::ocean
