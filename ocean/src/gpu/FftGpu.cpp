// FftGpu: uploads FftOcean's spectrum once and runs the spectrum / inverse-FFT / finalize compute passes
// (see the header for the pass list, the time encoding and the GL state it touches).
#include <epoxy/gl.h>

#include "gpu/FftGpu.h"

#include "gpu/GpuInterface.h"

#include "engine/Time.h"
#include "engine/gl/Shader.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanShaders.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pacifica::ocean {
namespace {

/// Complex planes transformed per update (two real fields each; see fft_spectrum.comp).
constexpr int FFT_PLANES = 4;
/// Layers (draws) one group of cascades may hold: every cascade's two draws.
constexpr int FFT_MAX_LAYERS = 2 * FFT_MAX_CASCADES;
/// Local size of the 2D passes (spectrum, finalize); N >= 16 is a multiple.
constexpr int TILE_GROUP = 8;
/// Floor on the Jacobian used when the slope map divides by it (fft_finalize.comp): where the surface
/// folds (J <= 0) the gradient of the displaced surface is infinite or flips; the map then holds the
/// gradient at J = 0.05, a steep but finite face.
constexpr double JACOBIAN_FLOOR = 0.05;

int log2Int(int n) {
    int l = 0;
    while ((1 << l) < n)
        ++l;
    return l;
}

gl::Program buildCompute(const char* file, const std::string& defines) {
    std::vector<gl::ShaderSource> sources;
    sources.push_back({"<ocean constants>", shaderConstantDefines()});
    sources.push_back({"<fft defines>", defines});
    sources.push_back({file, std::string(shaderText(file))});
    return gl::buildProgram({{gl::ShaderStage::Compute, sources}}, file);
}

int location(unsigned program, const char* name) {
    return glGetUniformLocation(program, name);
}

} // namespace

uint32_t FftGpu::timeWord(double time, double loopPeriod) {
    const double s = wrapPhase(time, loopPeriod) / loopPeriod; // [0, 1), in double
    // s * 2^32 < 2^32 is exact (power-of-two scale); rounding to the nearest integer may give 2^32 -> 0.
    const double scaled = std::nearbyint(std::ldexp(s, 32));
    return static_cast<uint32_t>(static_cast<uint64_t>(scaled) & 0xffffffffu);
}

FftGpu::FftGpu(std::shared_ptr<const FftOcean> ocean) {
    if (!ocean)
        throw std::invalid_argument("FftGpu::FftGpu(): ocean is null");
    init({{std::move(ocean)}});
}

FftGpu::FftGpu(std::shared_ptr<const FftCascades> cascades) : mSea(std::move(cascades)) {
    if (!mSea)
        throw std::invalid_argument("FftGpu::FftGpu(): cascades is null");
    std::vector<std::vector<std::shared_ptr<const FftOcean>>> draws;
    for (size_t c = 0; c < mSea->cascades().size(); ++c) {
        draws.push_back({mSea->cascades()[c]});
        if (!mSea->secondDraws().empty())
            draws.back().push_back(mSea->secondDraws()[c]);
    }
    init(std::move(draws));
}

void FftGpu::init(std::vector<std::vector<std::shared_ptr<const FftOcean>>> cascades) {
    if (cascades.empty() || static_cast<int>(cascades.size()) > FFT_MAX_CASCADES)
        throw std::invalid_argument("FftGpu::FftGpu(): 1 to " + std::to_string(FFT_MAX_CASCADES) +
                                    " cascades, got " + std::to_string(cascades.size()));
    // Group the cascades by grid size, in cascade order (cascade 0 first in its group).
    for (auto& draws : cascades) {
        if (draws.empty() || draws.size() > 2)
            throw std::invalid_argument("FftGpu::FftGpu(): a cascade has 1 or 2 draws");
        const int n = draws.front() ? draws.front()->desc().size : 0;
        for (const auto& d : draws)
            if (!d || d->desc().size != n)
                throw std::invalid_argument("FftGpu::FftGpu(): a cascade's draw is null or of another size");
        Cascade c;
        c.draws = std::move(draws);
        c.group = -1;
        for (size_t g = 0; g < mGroups.size(); ++g)
            if (mGroups[g].size == n)
                c.group = static_cast<int>(g);
        if (c.group < 0) {
            mGroups.emplace_back();
            mGroups.back().size = n;
            c.group = static_cast<int>(mGroups.size()) - 1;
        }
        Group& g = mGroups[static_cast<size_t>(c.group)];
        c.firstLayer = g.layers;
        g.layers += static_cast<int>(c.draws.size());
        for (const auto& d : c.draws)
            g.deltaK.push_back(static_cast<float>(2.0 * std::numbers::pi / d->desc().tileSize));
        mCascades.push_back(std::move(c));
    }
    size_t largest = 0;
    for (Group& g : mGroups) {
        const int n = g.size;
        if (g.layers > FFT_MAX_LAYERS)
            throw std::invalid_argument("FftGpu::FftGpu(): more than " + std::to_string(FFT_MAX_LAYERS) +
                                        " draws of one grid size");
        // Threads per FFT line: each does N / (2 threads) butterflies per stage. 64 keeps whole
        // warps/wavefronts busy on GPUs (N * 4 workgroups per pass); on llvmpipe fewer threads per group run
        // faster (fewer coroutine switches at barriers): 256 -> 64 took N = 256 from ~85 to ~63 ms there.
        const int threads = std::min(n / 2, 64);
        const std::string defines =
            "#define FFT_N " + std::to_string(n) + "u\n#define FFT_LOG2N " + std::to_string(log2Int(n)) +
            "u\n#define FFT_THREADS " + std::to_string(threads) + "\n#define FFT_PLANES " +
            std::to_string(FFT_PLANES) + "u\n#define TILE_GROUP " + std::to_string(TILE_GROUP) +
            "\n#define JACOBIAN_FLOOR " + std::to_string(JACOBIAN_FLOOR) + "\n#define FFT_MAX_LAYERS " +
            std::to_string(FFT_MAX_LAYERS) + "\n";
        g.spectrum = buildCompute("fft_spectrum.comp", defines);
        g.pass = buildCompute("fft_pass.comp", defines);
        g.finalize = buildCompute("fft_finalize.comp", defines);
        g.mip = buildCompute("fft_mip.comp", defines);
        // Twiddles e^{+2 pi i j / N}, j < N/2, in double then rounded once (more accurate than GLSL sin/cos).
        std::vector<float> tw(static_cast<size_t>(n));
        for (int j = 0; j < n / 2; ++j) {
            const double a = 2.0 * std::numbers::pi * j / n;
            tw[static_cast<size_t>(2 * j)] = static_cast<float>(std::cos(a));
            tw[static_cast<size_t>(2 * j + 1)] = static_cast<float>(std::sin(a));
        }
        g.twiddles = gl::Buffer::create(tw.size() * sizeof(float), tw.data());
        g.displacement = gl::Texture::createArray2D(GL_RGBA32F, n, n, g.layers, 1);
        g.displacement.setSampling(GL_NEAREST, GL_NEAREST, GL_REPEAT);
        g.slope = gl::Texture::createArray2D(GL_RGBA32F, n, n, g.layers, log2Int(n) + 1);
        g.slope.setSampling(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
        largest = std::max(largest, static_cast<size_t>(n) * n * g.layers);
    }
    mData = gl::Buffer::create(largest * FFT_PLANES * 2 * sizeof(float), nullptr);
    const Cascade& first = mCascades.front();
    if (first.draws.front()->desc().foamMemory) {
        const int n = first.draws.front()->desc().size, draws = static_cast<int>(first.draws.size());
        const std::string defines = "#define FFT_N " + std::to_string(n) + "u\n#define FFT_PLANES " +
                                    std::to_string(FFT_PLANES) + "u\n#define TILE_GROUP " +
                                    std::to_string(TILE_GROUP) + "\n";
        mFoamSampleProgram = buildCompute("fft_foam.comp", defines + "#define FFT_FOAM_SAMPLE\n");
        mFoamMemoryProgram =
            buildCompute("fft_foam.comp", defines); // FOAM_MEMORY_WINDOW: shaderConstantDefines
        // Per draw: a ring of FOAM_MEMORY_WINDOW samples and a memory layer, (crests of +h, crests of -h).
        mFoamSamples = gl::Texture::createArray2D(GL_RG32F, n, n, FOAM_MEMORY_WINDOW * draws, 1);
        mFoamMemory = gl::Texture::createArray2D(GL_RG32F, n, n, draws, 1);
        mFoamMemory.setSampling(GL_NEAREST, GL_NEAREST, GL_REPEAT);
    }
}

void FftGpu::upload(Group& g, int groupIndex) {
    // Spectrum in FFT storage order: storage index p holds wave number n' = p (p < N/2) or p - N, i.e.
    // lattice index (p + N/2) mod N, so the inverse DFT's e^{2 pi i p x / N} = e^{i k x} needs no sign
    // correction afterwards. Per cell: (h0(k), conj(h0(-k))) and the integer q(k); a layer per draw.
    const int n = g.size;
    const size_t cells = static_cast<size_t>(n) * n;
    std::vector<float> pairs(cells * 4 * g.layers);
    std::vector<uint32_t> mult(cells * g.layers);
    auto lattice = [n](int p) { return (p + n / 2) % n; };
    for (const Cascade& c : mCascades) {
        if (c.group != groupIndex)
            continue;
        for (size_t d = 0; d < c.draws.size(); ++d) {
            const auto& h0 = c.draws[d]->h0();
            const auto& q = c.draws[d]->omegaMultiple();
            const size_t base = (static_cast<size_t>(c.firstLayer) + d) * cells;
            for (int py = 0; py < n; ++py) {
                for (int px = 0; px < n; ++px) {
                    const int i = lattice(px), m = lattice(py);
                    // -k: wave number -n' -> lattice N - i (mod N); the Nyquist index 0 maps to itself.
                    const int ni = (n - i) % n, nm = (n - m) % n;
                    const std::complex<double> a = h0[static_cast<size_t>(m) * n + i];
                    const std::complex<double> b = std::conj(h0[static_cast<size_t>(nm) * n + ni]);
                    const size_t s = base + static_cast<size_t>(py) * n + px;
                    pairs[s * 4 + 0] = static_cast<float>(a.real());
                    pairs[s * 4 + 1] = static_cast<float>(a.imag());
                    pairs[s * 4 + 2] = static_cast<float>(b.real());
                    pairs[s * 4 + 3] = static_cast<float>(b.imag());
                    mult[s] = q[static_cast<size_t>(m) * n + i];
                }
            }
        }
    }
    g.h0Pairs = gl::Buffer::create(pairs.size() * sizeof(float), pairs.data());
    g.omegaMultiples = gl::Buffer::create(mult.size() * sizeof(uint32_t), mult.data());
}

void FftGpu::transform(const Group& g, int layers, uint32_t word, unsigned firstPlane, unsigned planes) {
    const GLuint n = static_cast<GLuint>(g.size);
    const GLuint groups2d = n / TILE_GROUP;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, FFT_PLANES_BINDING, mData.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, FFT_H0_PAIRS_BINDING, g.h0Pairs.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, FFT_OMEGA_MULTIPLES_BINDING, g.omegaMultiples.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, FFT_TWIDDLES_BINDING, g.twiddles.id());
    // 1. htilde(k, t) and the derived spectra, every layer (dispatch z).
    glUseProgram(g.spectrum.id());
    glUniform1ui(location(g.spectrum.id(), "uTimeWord"), word);
    glUniform1fv(location(g.spectrum.id(), "uDeltaK"), static_cast<GLsizei>(g.deltaK.size()),
                 g.deltaK.data());
    glDispatchCompute(groups2d, groups2d, static_cast<GLuint>(layers));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    // 2-3. Inverse FFT along x (rows), then along y (columns): workgroup y = the line's plane among the
    // `planes` transformed per layer, times the layers.
    glUseProgram(g.pass.id());
    const int dirLoc = location(g.pass.id(), "uDirection");
    glUniform1ui(location(g.pass.id(), "uPlaneBase"), firstPlane);
    glUniform1ui(location(g.pass.id(), "uPlanesPerLayer"), planes);
    for (int dir = 0; dir < 2; ++dir) {
        glUniform1i(dirLoc, dir);
        glDispatchCompute(n, planes * static_cast<GLuint>(layers), 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

int FftGpu::updateFoamMemory(double time) {
    // The samples the window [j - W + 1, j] needs and the ring lacks: normally the one or two lattice times
    // since the last frame; all W after a seek, a step back in time or the first frame. The ring then holds
    // exactly the samples of the window whatever the frame times were, so the memory is a function of t.
    const int64_t j = foamStepIndex(time);
    if (mHaveFoam && j == mFoamStep)
        return 0;
    const int64_t first = mHaveFoam && j > mFoamStep && j - mFoamStep < FOAM_MEMORY_WINDOW
                              ? mFoamStep + 1
                              : j - FOAM_MEMORY_WINDOW + 1;
    const Cascade& c0 = mCascades.front(); // layers [0, draws) of its group
    const Group& g0 = mGroups[static_cast<size_t>(c0.group)];
    const GLuint groups2d = static_cast<GLuint>(g0.size) / TILE_GROUP;
    const int draws = static_cast<int>(c0.draws.size());
    auto slotOf = [](int64_t step) {
        return static_cast<int>(((step % FOAM_MEMORY_WINDOW) + FOAM_MEMORY_WINDOW) % FOAM_MEMORY_WINDOW);
    };
    int passes = 0;
    glBindImageTexture(FFT_FOAM_SAMPLES_IMAGE_UNIT, mFoamSamples.id(), 0, GL_TRUE, 0, GL_READ_WRITE,
                       GL_RG32F);
    for (int64_t step = first; step <= j; ++step) {
        transform(g0, draws, timeWord(foamStepTime(step), c0.draws.front()->desc().loopPeriod), 1,
                  1); // h: plane 1 of each draw
        glUseProgram(mFoamSampleProgram.id());
        glUniform1i(location(mFoamSampleProgram.id(), "uSlot"), slotOf(step));
        glDispatchCompute(groups2d, groups2d, static_cast<GLuint>(draws));
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        passes += 4;
    }
    glUseProgram(mFoamMemoryProgram.id());
    float weights[FOAM_MEMORY_WINDOW];
    for (int k = 0; k < FOAM_MEMORY_WINDOW; ++k)
        weights[k] = static_cast<float>(std::exp(-k * FOAM_MEMORY_STEP / FOAM_DECAY_TIME));
    glUniform1fv(location(mFoamMemoryProgram.id(), "uWeight"), FOAM_MEMORY_WINDOW, weights);
    glUniform1i(location(mFoamMemoryProgram.id(), "uNewest"), slotOf(j));
    glBindImageTexture(FFT_FOAM_MEMORY_IMAGE_UNIT, mFoamMemory.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
    glDispatchCompute(groups2d, groups2d, static_cast<GLuint>(draws));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    mHaveFoam = true;
    mFoamStep = j;
    return passes + 1;
}

SurfaceGpuStats FftGpu::update(double time, const glm::dvec3& /*cameraWorld*/) {
    SurfaceGpuStats stats;
    // One loop period for every cascade (cascadeDesc keeps it), so one time word.
    const FftDesc& desc = mCascades.front().draws.front()->desc();
    const uint32_t word = timeWord(time, desc.loopPeriod);
    const bool foamDue = desc.foamMemory && !(mHaveFoam && foamStepIndex(time) == mFoamStep);
    if (mHaveMaps && word == mLastWord && !foamDue)
        return stats;     // same wrapped time: the maps are already exactly these
    gl::StateGuard guard; // restores the host's program
    if (!mUploaded) {
        for (size_t g = 0; g < mGroups.size(); ++g)
            upload(mGroups[g], static_cast<int>(g));
        mUploaded = true;
        stats.uploads = 1;
    }
    if (foamDue)
        stats.computePasses += updateFoamMemory(time);
    if (mHaveMaps && word == mLastWord) { // only the memory moved on (its samples leave the maps alone)
        mTotals.computePasses += stats.computePasses;
        mTotals.uploads += stats.uploads;
        return stats;
    }
    for (const Group& g : mGroups) {
        transform(g, g.layers, word, 0, FFT_PLANES);
        // 4. Unpack every layer into its layer of the maps (dispatch z).
        glUseProgram(g.finalize.id());
        glUniform1f(location(g.finalize.id(), "uChoppiness"), static_cast<float>(desc.choppiness));
        glBindImageTexture(FFT_DISPLACEMENT_IMAGE_UNIT, g.displacement.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY,
                           GL_RGBA32F);
        glBindImageTexture(FFT_SLOPE_IMAGE_UNIT, g.slope.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        const GLuint groups2d = static_cast<GLuint>(g.size) / TILE_GROUP;
        glDispatchCompute(groups2d, groups2d, static_cast<GLuint>(g.layers));
        // The scratch planes are rewritten by the next group's spectrum pass.
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                        GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                        GL_SHADER_STORAGE_BARRIER_BIT);
        // Mip chains of the slope maps for filtered lighting (LEAN-style variance, fft.glsl): every layer
        // at once, a dispatch per level.
        glUseProgram(g.mip.id());
        const int sizeLoc = location(g.mip.id(), "uSize");
        for (int level = 1, size = g.size / 2; size >= 1; ++level, size /= 2) {
            glBindImageTexture(FFT_MIP_SOURCE_IMAGE_UNIT, g.slope.id(), level - 1, GL_TRUE, 0, GL_READ_ONLY,
                               GL_RGBA32F);
            glBindImageTexture(FFT_MIP_DESTINATION_IMAGE_UNIT, g.slope.id(), level, GL_TRUE, 0, GL_WRITE_ONLY,
                               GL_RGBA32F);
            glUniform1i(sizeLoc, size);
            const GLuint groups = static_cast<GLuint>((size + TILE_GROUP - 1) / TILE_GROUP);
            glDispatchCompute(groups, groups, static_cast<GLuint>(g.layers));
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        stats.computePasses += 4;
    }
    mHaveMaps = true;
    mLastWord = word;
    mTotals.computePasses += stats.computePasses;
    mTotals.uploads += stats.uploads;
    return stats;
}

void FftGpu::bind(unsigned program, int firstUnit, double time, const glm::dvec3& cameraWorld) {
    // Foam memory on firstUnit (the sampler always names its unit); the decay since the last lattice time,
    // formed in double: e^(-(t - t_j) / tau).
    const bool memory = mCascades.front().draws.front()->desc().foamMemory;
    glProgramUniform1i(program, location(program, "uFftFoam"), firstUnit);
    glProgramUniform1i(program, location(program, "uFftFoamMemory"), memory ? 1 : 0);
    const double decay =
        memory ? std::exp(-(time - foamStepTime(foamStepIndex(time))) / FOAM_DECAY_TIME) : 0.0;
    glProgramUniform1f(program, location(program, "uFftFoamDecay"), static_cast<float>(decay));
    glBindTextureUnit(static_cast<GLuint>(firstUnit), memory ? mFoamMemory.id() : 0);
    for (size_t g = 0; g < mGroups.size(); ++g) {
        glBindTextureUnit(static_cast<GLuint>(firstUnit + 1 + 2 * static_cast<int>(g)),
                          mGroups[g].displacement.id());
        glBindTextureUnit(static_cast<GLuint>(firstUnit + 2 + 2 * static_cast<int>(g)),
                          mGroups[g].slope.id());
    }
    const int count = static_cast<int>(mCascades.size());
    glProgramUniform1i(program, location(program, "uFftCascades"), count);
    glProgramUniform1i(program, location(program, "uFftDraws"),
                       static_cast<int>(mCascades.front().draws.size()));
    // Every element of the sampler arrays names a unit of its type; those past the cascade count repeat
    // cascade 0's (never read: fft.glsl stops at uFftCascades).
    for (int i = 0; i < FFT_MAX_CASCADES; ++i) {
        const int ci = i < count ? i : 0;
        const Cascade& c = mCascades[static_cast<size_t>(ci)];
        const std::string idx = "[" + std::to_string(i) + "]";
        const FftDesc& d = c.draws.front()->desc();
        const double tile = d.tileSize;
        // fract(camera.xy / L) in double (exact fmod), so the GPU's float sees only [0, 1].
        const glm::vec2 offset(static_cast<float>(wrapPhase(cameraWorld.x, tile) / tile),
                               static_cast<float>(wrapPhase(cameraWorld.y, tile) / tile));
        glProgramUniform2f(program, location(program, ("uFftUvOffset" + idx).c_str()), offset.x, offset.y);
        glProgramUniform1f(program, location(program, ("uFftInvTile" + idx).c_str()),
                           static_cast<float>(1.0 / tile));
        glProgramUniform1i(program, location(program, ("uFftSize" + idx).c_str()), d.size);
        glProgramUniform1i(program, location(program, ("uFftLayer" + idx).c_str()), c.firstLayer);
        glProgramUniform1f(program, location(program, ("uFftFadeEnd" + idx).c_str()),
                           mSea ? static_cast<float>(mSea->displacementFadeEnd(ci)) : 1.0e30f);
        glProgramUniform1i(program, location(program, ("uFftDisplacement" + idx).c_str()),
                           firstUnit + 1 + 2 * c.group);
        glProgramUniform1i(program, location(program, ("uFftSlope" + idx).c_str()),
                           firstUnit + 2 + 2 * c.group);
        // The mix angle's terms about the camera: sin(k.(camera + rel) + phase) = sin(psi + k.rel) with
        // psi = wrap(k.camera + phase, 2 pi) formed in double, so the float sees only k.rel.
        for (int j = 0; j < FFT_MIX_TERMS && mSea && i < count; ++j) {
            const glm::dvec3 m = mSea->mixTerm(i, j);
            const double psi =
                wrapPhase(m.x * cameraWorld.x + m.y * cameraWorld.y + m.z, 2.0 * std::numbers::pi);
            const std::string name = "uFftMix[" + std::to_string(i * FFT_MIX_TERMS + j) + "]";
            glProgramUniform3f(program, location(program, name.c_str()), static_cast<float>(m.x),
                               static_cast<float>(m.y), static_cast<float>(psi));
        }
    }
}

std::vector<float> FftGpu::readFoamMemory() const {
    if (!mFoamMemory)
        return {};
    const Cascade& c0 = mCascades.front();
    const int n = c0.draws.front()->desc().size, draws = static_cast<int>(c0.draws.size());
    std::vector<float> all(static_cast<size_t>(n) * n * draws);
    glGetTextureImage(mFoamMemory.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(all.size() * sizeof(float)),
                      all.data());
    all.resize(static_cast<size_t>(n) * n); // draw A's layer
    return all;
}

namespace {
/// Layer `layer` of level `level` of a 2D array texture of `layers` layers, RGBA floats.
std::vector<float> readLayer(unsigned texture, int level, int size, int layers, int layer) {
    std::vector<float> all(static_cast<size_t>(size) * size * 4 * layers);
    glGetTextureImage(texture, level, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(all.size() * sizeof(float)),
                      all.data());
    const auto first =
        all.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(size) * size * 4 * layer);
    return {first, first + static_cast<std::ptrdiff_t>(static_cast<size_t>(size) * size * 4)};
}
} // namespace

std::vector<float> FftGpu::readDisplacementMap(int cascade, int draw) const {
    const Cascade& c = mCascades.at(static_cast<size_t>(cascade));
    const Group& g = mGroups[static_cast<size_t>(c.group)];
    return readLayer(g.displacement.id(), 0, g.size, g.layers, c.firstLayer + draw);
}

std::vector<float> FftGpu::readSlopeMap(int level, int cascade, int draw) const {
    const Cascade& c = mCascades.at(static_cast<size_t>(cascade));
    const Group& g = mGroups[static_cast<size_t>(c.group)];
    return readLayer(g.slope.id(), level, std::max(1, g.size >> level), g.layers, c.firstLayer + draw);
}

} // namespace pacifica::ocean
