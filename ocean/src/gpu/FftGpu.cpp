// FftGpu: uploads FftOcean's spectrum once and runs the spectrum / inverse-FFT / finalize compute passes
// (see the header for the pass list, the time encoding and the GL state it touches).
#include <epoxy/gl.h>

#include "gpu/FftGpu.h"

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

FftGpu::FftGpu(std::shared_ptr<const FftOcean> ocean) : mOcean(std::move(ocean)) {
    if (!mOcean)
        throw std::invalid_argument("FftGpu::FftGpu(): ocean is null");
    mSize = mOcean->desc().size;
    const int n = mSize;
    // Threads per FFT line: each does N / (2 threads) butterflies per stage. 64 keeps whole warps/wavefronts
    // busy on GPUs (N * 4 workgroups per pass); on llvmpipe fewer threads per group run faster (fewer
    // coroutine switches at barriers): 256 -> 64 took N = 256 from ~85 to ~63 ms there.
    const int threads = std::min(n / 2, 64);
    const std::string defines =
        "#define FFT_N " + std::to_string(n) + "u\n#define FFT_LOG2N " + std::to_string(log2Int(n)) +
        "u\n#define FFT_THREADS " + std::to_string(threads) + "\n#define FFT_PLANES " +
        std::to_string(FFT_PLANES) + "u\n#define TILE_GROUP " + std::to_string(TILE_GROUP) +
        "\n#define JACOBIAN_FLOOR " + std::to_string(JACOBIAN_FLOOR) + "\n";
    mSpectrumProgram = buildCompute("fft_spectrum.comp", defines);
    mPassProgram = buildCompute("fft_pass.comp", defines);
    mFinalizeProgram = buildCompute("fft_finalize.comp", defines);
    if (mOcean->desc().foamMemory) {
        mFoamSampleProgram = buildCompute("fft_foam.comp", defines + "#define FFT_FOAM_SAMPLE\n");
        mFoamMemoryProgram =
            buildCompute("fft_foam.comp", defines); // FOAM_MEMORY_WINDOW: shaderConstantDefines
        mFoamSamples = gl::Texture::createArray2D(GL_R32F, n, n, FOAM_MEMORY_WINDOW, 1);
        mFoamMemory = gl::Texture::create2D(GL_R32F, n, n, 1);
        mFoamMemory.setSampling(GL_NEAREST, GL_NEAREST, GL_REPEAT);
    }

    const size_t cells = static_cast<size_t>(n) * n;
    mData = gl::Buffer::create(cells * FFT_PLANES * 2 * sizeof(float), nullptr);
    mDisplacement = gl::Texture::create2D(GL_RGBA32F, n, n, 1);
    mDisplacement.setSampling(GL_NEAREST, GL_NEAREST, GL_REPEAT);
    mSlope = gl::Texture::create2D(GL_RGBA32F, n, n, log2Int(n) + 1);
    mSlope.setSampling(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
}

void FftGpu::upload() {
    // Spectrum in FFT storage order: storage index p holds wave number n' = p (p < N/2) or p - N, i.e.
    // lattice index (p + N/2) mod N, so the inverse DFT's e^{2 pi i p x / N} = e^{i k x} needs no sign
    // correction afterwards. Per cell: (h0(k), conj(h0(-k))) and the integer q(k).
    const int n = mSize;
    const auto& h0 = mOcean->h0();
    const auto& q = mOcean->omegaMultiple();
    const size_t cells = static_cast<size_t>(n) * n;
    std::vector<float> pairs(cells * 4);
    std::vector<uint32_t> mult(cells);
    auto lattice = [n](int p) { return (p + n / 2) % n; };
    for (int py = 0; py < n; ++py) {
        for (int px = 0; px < n; ++px) {
            const int i = lattice(px), m = lattice(py);
            // -k: wave number -n' -> lattice N - i (mod N); the Nyquist index 0 maps to itself (h0 = 0).
            const int ni = (n - i) % n, nm = (n - m) % n;
            const std::complex<double> a = h0[static_cast<size_t>(m) * n + i];
            const std::complex<double> b = std::conj(h0[static_cast<size_t>(nm) * n + ni]);
            const size_t s = static_cast<size_t>(py) * n + px;
            pairs[s * 4 + 0] = static_cast<float>(a.real());
            pairs[s * 4 + 1] = static_cast<float>(a.imag());
            pairs[s * 4 + 2] = static_cast<float>(b.real());
            pairs[s * 4 + 3] = static_cast<float>(b.imag());
            mult[s] = q[static_cast<size_t>(m) * n + i];
        }
    }
    // Twiddles e^{+2 pi i j / N}, j < N/2, in double then rounded once (more accurate than GLSL sin/cos).
    std::vector<float> tw(static_cast<size_t>(n));
    for (int j = 0; j < n / 2; ++j) {
        const double a = 2.0 * std::numbers::pi * j / n;
        tw[static_cast<size_t>(2 * j)] = static_cast<float>(std::cos(a));
        tw[static_cast<size_t>(2 * j + 1)] = static_cast<float>(std::sin(a));
    }
    mH0Pairs = gl::Buffer::create(pairs.size() * sizeof(float), pairs.data());
    mOmegaMultiples = gl::Buffer::create(mult.size() * sizeof(uint32_t), mult.data());
    mTwiddles = gl::Buffer::create(tw.size() * sizeof(float), tw.data());
    mUploaded = true;
}

void FftGpu::transform(uint32_t word, unsigned firstPlane, unsigned planes) {
    const GLuint n = static_cast<GLuint>(mSize);
    const GLuint groups2d = n / TILE_GROUP;
    // 1. htilde(k, t) and the derived spectra.
    glUseProgram(mSpectrumProgram.id());
    glUniform1ui(location(mSpectrumProgram.id(), "uTimeWord"), word);
    glUniform1f(location(mSpectrumProgram.id(), "uDeltaK"),
                static_cast<float>(2.0 * std::numbers::pi / mOcean->desc().tileSize));
    glDispatchCompute(groups2d, groups2d, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    // 2-3. Inverse FFT along x (rows), then along y (columns), of planes [firstPlane, firstPlane + planes).
    glUseProgram(mPassProgram.id());
    const int dirLoc = location(mPassProgram.id(), "uDirection");
    glUniform1ui(location(mPassProgram.id(), "uPlaneBase"), firstPlane);
    for (int dir = 0; dir < 2; ++dir) {
        glUniform1i(dirLoc, dir);
        glDispatchCompute(n, planes, 1);
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
    const GLuint groups2d = static_cast<GLuint>(mSize) / TILE_GROUP;
    auto layerOf = [](int64_t step) {
        return static_cast<int>(((step % FOAM_MEMORY_WINDOW) + FOAM_MEMORY_WINDOW) % FOAM_MEMORY_WINDOW);
    };
    int passes = 0;
    glBindImageTexture(2, mFoamSamples.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32F);
    for (int64_t step = first; step <= j; ++step) {
        transform(timeWord(foamStepTime(step), mOcean->desc().loopPeriod), 1, 1); // h: plane 1
        glUseProgram(mFoamSampleProgram.id());
        glUniform1i(location(mFoamSampleProgram.id(), "uLayer"), layerOf(step));
        glDispatchCompute(groups2d, groups2d, 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        passes += 4;
    }
    glUseProgram(mFoamMemoryProgram.id());
    float weights[FOAM_MEMORY_WINDOW];
    for (int k = 0; k < FOAM_MEMORY_WINDOW; ++k)
        weights[k] = static_cast<float>(std::exp(-k * FOAM_MEMORY_STEP / FOAM_DECAY_TIME));
    glUniform1fv(location(mFoamMemoryProgram.id(), "uWeight"), FOAM_MEMORY_WINDOW, weights);
    glUniform1i(location(mFoamMemoryProgram.id(), "uNewest"), layerOf(j));
    glBindImageTexture(3, mFoamMemory.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute(groups2d, groups2d, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    mHaveFoam = true;
    mFoamStep = j;
    return passes + 1;
}

SurfaceGpuStats FftGpu::update(double time, const glm::dvec3& /*cameraWorld*/) {
    SurfaceGpuStats stats;
    const uint32_t word = timeWord(time, mOcean->desc().loopPeriod);
    const bool foamDue = mOcean->desc().foamMemory && !(mHaveFoam && foamStepIndex(time) == mFoamStep);
    if (mHaveMaps && word == mLastWord && !foamDue)
        return stats;     // same wrapped time: the maps are already exactly these
    gl::StateGuard guard; // restores the host's program
    if (!mUploaded) {
        upload();
        stats.uploads = 1;
    }
    const GLuint n = static_cast<GLuint>(mSize);
    const GLuint groups2d = n / TILE_GROUP;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, mData.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, mH0Pairs.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, mOmegaMultiples.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, mTwiddles.id());
    if (foamDue)
        stats.computePasses += updateFoamMemory(time);
    if (mHaveMaps && word == mLastWord) { // only the memory moved on (its samples leave the maps alone)
        mTotals.computePasses += stats.computePasses;
        mTotals.uploads += stats.uploads;
        return stats;
    }
    transform(word, 0, FFT_PLANES);

    // 4. Unpack into the maps.
    glUseProgram(mFinalizeProgram.id());
    glUniform1f(location(mFinalizeProgram.id(), "uChoppiness"),
                static_cast<float>(mOcean->desc().choppiness));
    glBindImageTexture(0, mDisplacement.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, mSlope.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groups2d, groups2d, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    // Mip chain of the slope map for filtered lighting (LEAN-style variance, fft.glsl).
    glGenerateTextureMipmap(mSlope.id());

    stats.computePasses += 4;
    mHaveMaps = true;
    mLastWord = word;
    mTotals.computePasses += stats.computePasses;
    mTotals.uploads += stats.uploads;
    return stats;
}

void FftGpu::bind(unsigned program, int firstUnit, double time, const glm::dvec3& cameraWorld) {
    const double tile = mOcean->desc().tileSize;
    // fract(camera.xy / L) in double (exact fmod), so the GPU's float sees only [0, 1].
    const glm::vec2 offset(static_cast<float>(wrapPhase(cameraWorld.x, tile) / tile),
                           static_cast<float>(wrapPhase(cameraWorld.y, tile) / tile));
    glProgramUniform2f(program, location(program, "uFftUvOffset"), offset.x, offset.y);
    glProgramUniform1f(program, location(program, "uFftInvTile"), static_cast<float>(1.0 / tile));
    glProgramUniform1i(program, location(program, "uFftSize"), mSize);
    glProgramUniform1i(program, location(program, "uFftDisplacement"), firstUnit);
    glProgramUniform1i(program, location(program, "uFftSlope"), firstUnit + 1);
    glBindTextureUnit(static_cast<GLuint>(firstUnit), mDisplacement.id());
    glBindTextureUnit(static_cast<GLuint>(firstUnit + 1), mSlope.id());
    // Foam memory on firstUnit + 2 (the sampler always names its unit); the decay since the last lattice
    // time, formed in double: e^(-(t - t_j) / tau).
    const bool memory = mOcean->desc().foamMemory;
    glProgramUniform1i(program, location(program, "uFftFoam"), firstUnit + 2);
    glProgramUniform1i(program, location(program, "uFftFoamMemory"), memory ? 1 : 0);
    const double decay =
        memory ? std::exp(-(time - foamStepTime(foamStepIndex(time))) / FOAM_DECAY_TIME) : 0.0;
    glProgramUniform1f(program, location(program, "uFftFoamDecay"), static_cast<float>(decay));
    glBindTextureUnit(static_cast<GLuint>(firstUnit + 2), memory ? mFoamMemory.id() : 0);
}

std::vector<float> FftGpu::readFoamMemory() const {
    std::vector<float> out(static_cast<size_t>(mSize) * mSize);
    if (!mFoamMemory)
        return {};
    glGetTextureImage(mFoamMemory.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(float)),
                      out.data());
    return out;
}

std::vector<float> FftGpu::readDisplacementMap() const {
    std::vector<float> out(static_cast<size_t>(mSize) * mSize * 4);
    glGetTextureImage(mDisplacement.id(), 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
    return out;
}

std::vector<float> FftGpu::readSlopeMap(int level) const {
    const int s = std::max(1, mSize >> level);
    std::vector<float> out(static_cast<size_t>(s) * s * 4);
    glGetTextureImage(mSlope.id(), level, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(float)),
                      out.data());
    return out;
}

} // namespace pacifica::ocean
