// FftGpu (internal): the GPU side of FftOcean — each update() evolves the spectrum to the wrapped time and
// inverse-FFTs it in GL compute shaders into two tiling textures that ocean/shaders/fft.glsl samples:
//   displacement map, RGBA32F, 1 level:  (lambda Dx, lambda Dy, h, J) at grid point (i, j) L / N
//   slope map, RGBA32F, full mip chain:   (dH/dx, dH/dy, (dH/dx)^2, (dH/dy)^2) of the displaced surface
// (J is the Jacobian determinant of eq. 30's horizontal map, for foam.) Per update, four compute passes:
//   1. fft_spectrum.comp  htilde(k, t) (eq. 26) and its derived spectra (eq. 29, slopes, dD/dx), packed as
//                         four complex N x N planes (two real fields per complex FFT: all are Hermitian)
//   2. fft_pass.comp      inverse FFT along x: one workgroup per row and plane, radix-2 in shared memory
//   3. fft_pass.comp      inverse FFT along y: one workgroup per column and plane
//   4. fft_finalize.comp  unpack, apply lambda, the displaced-surface gradient, write both maps
// then the slope map's mip chain, one fft_mip.comp dispatch per level (part of pass 4 in the counts).
// Living whitecaps (FftDesc::foamMemory; FftOcean::foamHeightAt): for every lattice time t_j =
// j FOAM_MEMORY_STEP that passed since the last update, passes 1-3 on the height plane alone and
// fft_foam.comp store max(h(t_j), 0) into a ring of FOAM_MEMORY_WINDOW R32F layers; one more pass takes the
// decayed maximum over the ring into the memory map (R32F, N x N) that fft.glsl reads. Normally 0 or 1 sample
// a frame (5 per simulated second); a seek or the first frame samples the whole window (30).
//
// Time: only w = q w0 (integer q) reaches the GPU, and the time as the 32-bit fixed-point fraction
// word = round(wrap(t, T) / T * 2^32), formed in double here. The shader's phase q * word (mod 2^32, exact
// uint arithmetic) / 2^32 turns is then exact up to the final float conversion, for any t.
//
// Cascades (FftCascades): the draws of every cascade (A, and B when aperiodic) are layers of the maps, and
// the draws of one grid size N (a group: cascade 0's N, the detail cascades' N) are transformed together —
// one dispatch per pass for the whole group, the layer in the dispatch's z (or workgroup y) — so the cost
// in passes and barriers does not grow with the cascades: 4 passes per group. fft.glsl sums the cascades.
// The living whitecaps follow cascade 0 (its draws are the first layers of its group).
//
// GL state: update() restores the current program (gl::StateGuard) but leaves shader-storage buffer
// bindings 0..3 and image units 0..3 pointing at this object's resources; bind() binds texture units
// [firstUnit, firstUnit + unitsUsed()). Needs a current GL 4.5 context for construction, update(), bind() and
// the destructor.
#pragma once

#include "gpu/SurfaceGpu.h"
#include "ocean/FftOcean.h"

#include "engine/gl/GlObjects.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pacifica::ocean {

class FftGpu final : public SurfaceGpu {
public:
    /// Compiles the compute programs and allocates the buffers and maps (no upload yet: the first update()
    /// uploads h0 and q once and reports it).
    explicit FftGpu(std::shared_ptr<const FftOcean> ocean);
    /// The same for every cascade of `cascades` (FftDesc::cascades of them, summed by fft.glsl).
    explicit FftGpu(std::shared_ptr<const FftCascades> cascades);

    std::vector<std::string> glslFiles() const override { return {"fft.glsl"}; }
    /// Recomputes the maps for time t: 4 compute passes per group of cascades of one grid size (+ 1 upload
    /// the first time), plus 4 per foam sample and 1 for the memory when t entered a new foam lattice step.
    /// Skipped entirely — no pass, returns zeros — when the time word equals the last update's (same wrapped
    /// time, e.g. t and t + T, or a paused game) and the foam step is the last one, since the maps are then
    /// bitwise what they would be. The FFT tile does not depend on the camera; cameraWorld is unused here
    /// (bind() uses it). Throws std::invalid_argument for a non-finite time (wrapPhase).
    SurfaceGpuStats update(double time, const glm::dvec3& cameraWorld) override;
    /// Sets fft.glsl's uniforms (per cascade the tile offset fract(camera.xy / L) formed in double, its
    /// layers, fade and mix terms; the foam memory's decay since its lattice time) and binds the maps of the
    /// last update(): the foam memory to firstUnit, then per group g its displacement and slope arrays to
    /// firstUnit + 1 + 2g and + 2 + 2g. Does no GPU work (call update(time) first).
    void bind(unsigned program, int firstUnit, double time, const glm::dvec3& cameraWorld) override;
    int unitsUsed() const override { return 1 + 2 * static_cast<int>(mGroups.size()); }

    /// Cascade 0's (the only one for a single FftOcean).
    const FftOcean& ocean() const { return *mCascades.front().draws.front(); }
    int cascadeCount() const { return static_cast<int>(mCascades.size()); }
    /// Sums of every update()'s stats since construction.
    SurfaceGpuStats totals() const { return mTotals; }
    /// round(wrap(t, T) / T * 2^32) mod 2^32: the only form in which time reaches the GPU.
    static uint32_t timeWord(double time, double loopPeriod);

    /// Read-backs for tests and tools: RGBA floats, row-major (j * N + i) * 4; level of the slope map; of
    /// draw `draw` of cascade `cascade`.
    std::vector<float> readDisplacementMap(int cascade = 0, int draw = 0) const;
    std::vector<float> readSlopeMap(int level = 0, int cascade = 0, int draw = 0) const;
    /// The living whitecaps' memory M_j of the last update() (FftOcean::foamHeightAt) of cascade 0's draw A,
    /// N x N floats, row-major; empty without FftDesc::foamMemory.
    std::vector<float> readFoamMemory() const;

private:
    /// The cascades of one grid size N: their programs, spectra (a layer per draw, in cascade order), scratch
    /// planes and maps.
    struct Group {
        int size = 0;
        int layers = 0;
        gl::Program spectrum, pass, finalize, mip;
        gl::Buffer twiddles, h0Pairs, omegaMultiples;
        gl::Texture displacement, slope; // 2D arrays, a layer per draw
        std::vector<float> deltaK;       // 2 pi / L per layer
    };
    /// One cascade: its draws and where they are.
    struct Cascade {
        std::vector<std::shared_ptr<const FftOcean>> draws;
        int group = 0;
        int firstLayer = 0;
    };
    void init(std::vector<std::vector<std::shared_ptr<const FftOcean>>> cascades);
    void upload(Group& g, int groupIndex);
    /// Passes 1-3 (spectrum, inverse FFT along x then y) of layers [0, layers) of group g for the time
    /// word, transforming planes firstPlane + 4 l (each layer's 4 planes when planes == 4, else its plane
    /// firstPlane alone).
    void transform(const Group& g, int layers, uint32_t word, unsigned firstPlane, unsigned planes);
    /// Samples the lattice times the window lacks and rebuilds the memory map; returns the passes run.
    int updateFoamMemory(double time);

    std::shared_ptr<const FftCascades> mSea; // null for a single FftOcean
    std::vector<Group> mGroups;
    std::vector<Cascade> mCascades;
    gl::Buffer mData; // scratch planes, sized for the largest group
    gl::Program mFoamSampleProgram, mFoamMemoryProgram;
    gl::Texture mFoamSamples, mFoamMemory; // the ring of FOAM_MEMORY_WINDOW crest samples; the memory map
    bool mHaveFoam = false;
    int64_t mFoamStep = 0; // lattice index of the memory map
    bool mUploaded = false;
    bool mHaveMaps = false;
    uint32_t mLastWord = 0;
    SurfaceGpuStats mTotals;
};

} // namespace pacifica::ocean
