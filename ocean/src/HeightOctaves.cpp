// HeightOctaves: procedural generation of tileable, looping height-map octaves and their CPU sampling
// (GPU Gems 2 §18.2.1; dispersion and looping from Tessendorf 2001 §3.2), with every vertex filter of
// §18.2.4 (listings 18-2, 18-3) and the combined two-pass path of §18.2.5 in double, mirroring
// ocean/shaders/octaves.glsl line by line. See the header for the model and the modes.
#include "ocean/HeightOctaves.h"

#include "engine/Time.h"
#include "ocean/OceanConstants.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace pacifica::ocean {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

void require(bool ok, const std::string& message) {
    if (!ok)
        throw std::invalid_argument(message);
}

int wrapIndex(long long i, int n) {
    const long long r = i % n;
    return static_cast<int>(r < 0 ? r + n : r);
}

struct Wave {
    int n = 0, m = 0;     // cycles per tile along u and v (lattice vector: tiles exactly)
    double amplitude = 0; // before normalisation
    double omega = 0;     // rad/s, quantised to multiples of 2*pi/T
    double phase = 0;
};

/// Chooses `count` distinct lattice waves around the wind direction. Directional spreading ~ cos^2 of the
/// angle to the wind and amplitude ~ k^-1.25, a softened Phillips-like falloff (Tessendorf 2001 eq. 40).
std::vector<Wave> makeWaves(const OctaveDesc& o, const HeightOctavesDesc& d, std::mt19937_64& rng) {
    const int maxCycles = std::max(2, d.mapSize / 16); // >= 16 texels per wavelength
    const double wind = d.windDirectionDeg * std::numbers::pi / 180.0;
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::set<std::pair<int, int>> used;
    std::vector<Wave> waves;
    int guard = 0;
    while (static_cast<int>(waves.size()) < d.wavesPerOctave && guard++ < 100000) {
        // Direction: wind +- spread; compass angle (clockwise from north) to (east, north) components.
        const double spread = (uni(rng) - 0.5) * std::numbers::pi * 0.9;
        const double dir = wind + spread;
        const double cycles = 1.0 + uni(rng) * (maxCycles - 1);
        const int n = static_cast<int>(std::lround(cycles * std::sin(dir)));
        const int m = static_cast<int>(std::lround(cycles * std::cos(dir)));
        if ((n == 0 && m == 0) || used.count({n, m}) || used.count({-n, -m}))
            continue;
        used.insert({n, m});
        Wave w;
        w.n = n;
        w.m = m;
        const double c = std::sqrt(double(n * n + m * m));
        const double spreadWeight = std::cos(spread) * std::cos(spread);
        w.amplitude = spreadWeight / std::pow(c, 1.25);
        // Deep-water dispersion w = sqrt(g k), k = 2 pi c / L, quantised to the loop (Tessendorf §3.2).
        const double k = kTwoPi * c / o.tileSize;
        const double omega0 = kTwoPi / o.loopPeriod;
        w.omega = omega0 * std::max(1.0, std::round(std::sqrt(GRAVITY * k) / omega0));
        w.phase = uni(rng) * kTwoPi;
        waves.push_back(w);
    }
    return waves;
}

/// One wave's row of a map added in place: v = (a + b i) (cr + ci i) per texel; h += Re v, dh/du -= su Im v,
/// dh/dv -= sv Im v.
void addWaveToRow(double a, double b, double su, double sv, const double* cr, const double* ci, double* rh,
                  double* ru, double* rv, size_t n) {
    for (size_t x = 0; x < n; ++x) {
        const double vr = a * cr[x] - b * ci[x], vi = a * ci[x] + b * cr[x];
        rh[x] += vr;
        ru[x] -= su * vi;
        rv[x] -= sv * vi;
    }
}

OctaveMap generate(const OctaveDesc& o, const HeightOctavesDesc& d, std::mt19937_64& rng) {
    const int size = d.mapSize, frames = d.frames;
    const std::vector<Wave> waves = makeWaves(o, d, rng);
    double sumSq = 0.0;
    for (const Wave& w : waves)
        sumSq += 0.5 * w.amplitude * w.amplitude; // distinct lattice cosines are orthogonal over a tile
    const double norm = 1.0 / std::sqrt(sumSq);   // unit RMS height

    // Spatial phasors e^{i 2 pi (n x + m y) / size} factor into per-axis tables, one pair per wave (the x
    // table as real and imaginary rows), and each wave's complex amplitude into one value per frame.
    const size_t texels = static_cast<size_t>(size) * size, n = static_cast<size_t>(size);
    const size_t nf = static_cast<size_t>(frames);
    std::vector<double> exRe(waves.size() * n), exIm(waves.size() * n);
    std::vector<std::complex<double>> ey(waves.size() * n), c0(waves.size() * nf);
    for (size_t k = 0; k < waves.size(); ++k) {
        const Wave& w = waves[k];
        for (int x = 0; x < size; ++x) {
            const std::complex<double> e = std::polar(1.0, kTwoPi * w.n * x / size);
            exRe[k * n + static_cast<size_t>(x)] = e.real();
            exIm[k * n + static_cast<size_t>(x)] = e.imag();
        }
        for (int y = 0; y < size; ++y)
            ey[k * n + static_cast<size_t>(y)] = std::polar(1.0, kTwoPi * w.m * y / size);
        for (int f = 0; f < frames; ++f) {
            const double t = o.loopPeriod * f / frames;
            // h = a cos(theta - w t + phi); dh/du = -a 2 pi n sin(...); dh/dv = -a 2 pi m sin(...)
            c0[k * nf + static_cast<size_t>(f)] = w.amplitude * norm * std::polar(1.0, w.phase - w.omega * t);
        }
    }
    // Row by row, every wave added to the row while it sits in the cache, in planes of h, dh/du and dh/dv.
    // Each texel sums the waves in their order with the same operations as one pass per wave with
    // std::complex (whose product of finite values is (ac - bd) + (ad + bc) i), so the maps are the same to
    // the bit; written out, the product vectorises.
    std::vector<double> planes(nf * texels * 3, 0.0);
    double* const hPlane = planes.data();
    double* const uPlane = hPlane + nf * texels;
    double* const vPlane = uPlane + nf * texels;
    for (size_t f = 0; f < nf; ++f)
        for (size_t y = 0; y < n; ++y) {
            const size_t row = f * texels + y * n;
            double* const rh = hPlane + row;
            double* const ru = uPlane + row;
            double* const rv = vPlane + row;
            for (size_t k = 0; k < waves.size(); ++k) {
                const std::complex<double> cy = c0[k * nf + f] * ey[k * n + y];
                const double a = cy.real(), b = cy.imag();
                const double su = kTwoPi * waves[k].n, sv = kTwoPi * waves[k].m;
                addWaveToRow(a, b, su, sv, &exRe[k * n], &exIm[k * n], rh, ru, rv, n);
            }
        }
    OctaveMap map;
    map.size = size;
    map.frames = frames;
    map.texels.resize(static_cast<size_t>(frames) * texels * 4);
    for (size_t i = 0; i < static_cast<size_t>(frames) * texels; ++i) {
        // Stored as half floats on the GPU (RGBA16F): round here so the CPU samples the identical values.
        const double h = hPlane[i], sx = uPlane[i], sy = vPlane[i];
        map.texels[i * 4 + 0] = glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(h)));
        map.texels[i * 4 + 1] = glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(sx)));
        map.texels[i * 4 + 2] = glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(sy)));
        // Squared slope: after mip filtering E[s^2] - |E[s]|^2 is the slope variance the pixel no longer
        // resolves, which the shader turns into specular roughness (LEAN mapping, Olano & Baker 2010).
        map.texels[i * 4 + 3] = glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(sx * sx + sy * sy)));
    }
    return map;
}

/// In-place iterative radix-2 FFT (Cooley & Tukey 1965; bit reversal, then log2(n) butterfly passes):
/// a[k] = sum_x a[x] e^(sign 2 pi i k x / n), unnormalised. n is a power of two.
void fft(std::vector<std::complex<double>>& a, int sign) {
    const size_t n = a.size();
    for (size_t i = 1, j = 0; i < n; ++i) {
        size_t bit = n >> 1;
        for (; j & bit; bit >>= 1)
            j ^= bit;
        j ^= bit;
        if (i < j)
            std::swap(a[i], a[j]);
    }
    for (size_t len = 2; len <= n; len <<= 1) {
        const std::complex<double> w = std::polar(1.0, sign * kTwoPi / static_cast<double>(len));
        for (size_t i = 0; i < n; i += len) {
            std::complex<double> wk(1.0, 0.0);
            for (size_t k = 0; k < len / 2; ++k) {
                const std::complex<double> even = a[i + k], odd = a[i + k + len / 2] * wk;
                a[i + k] = even + odd;
                a[i + k + len / 2] = even - odd;
                wk *= w;
            }
        }
    }
}

/// Spectral derivative of one periodic line of n samples over one tile (u in [0, 1)): forward FFT, mode k
/// (signed, |k| < n/2) times i 2 pi k, the Nyquist mode k = n/2 zeroed, inverse FFT / n (Johnson 2011,
/// algorithm 1, for the first derivative).
void spectralDerivative(std::vector<std::complex<double>>& line) {
    const int n = static_cast<int>(line.size());
    fft(line, -1);
    for (int k = 0; k < n; ++k) {
        const int signedK = k < n / 2 ? k : k - n;
        line[static_cast<size_t>(k)] *= k == n / 2 ? 0.0 : std::complex<double>(0.0, kTwoPi * signedK);
    }
    fft(line, +1);
    for (auto& v : line)
        v /= static_cast<double>(n);
}

float toHalfChecked(double v, const std::string& field, const char* what, int frame, int x, int y) {
    const float h = glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(v)));
    require(std::isfinite(h), field + ": " + what + " " + std::to_string(v) + " at frame " +
                                  std::to_string(frame) + ", texel (" + std::to_string(x) + ", " +
                                  std::to_string(y) + ") exceeds half-float range (65504) of the GPU maps");
    return h;
}

} // namespace

OctaveMap makeOctaveMap(const OctaveImage& image, int frames, const std::string& field) {
    const int s = image.size;
    require(s >= 16 && s <= 1024 && (s & (s - 1)) == 0,
            field + ".size must be a power of two in [16, 1024], got " + std::to_string(s));
    require(image.frames == 1 || image.frames == frames,
            field + ".frames must be 1 or " + std::to_string(frames) + " (HeightOctavesDesc.frames), got " +
                std::to_string(image.frames));
    const size_t texels = static_cast<size_t>(s) * static_cast<size_t>(s);
    require(image.heights.size() == texels * static_cast<size_t>(image.frames),
            field + ".heights must hold frames * size * size = " +
                std::to_string(texels * static_cast<size_t>(image.frames)) + " values, got " +
                std::to_string(image.heights.size()));
    for (size_t i = 0; i < image.heights.size(); ++i)
        require(std::isfinite(image.heights[i]), field + ".heights[" + std::to_string(i) +
                                                     "] is not finite (frame " + std::to_string(i / texels) +
                                                     ", texel (" + std::to_string(i % texels % s) + ", " +
                                                     std::to_string(i % texels / s) + "))");
    OctaveMap map;
    map.size = s;
    map.frames = frames;
    map.texels.resize(static_cast<size_t>(frames) * texels * 4);
    std::vector<std::complex<double>> line(static_cast<size_t>(s));
    for (int f = 0; f < image.frames; ++f) {
        const float* h = &image.heights[static_cast<size_t>(f) * texels];
        std::vector<double> du(texels), dv(texels);
        for (int y = 0; y < s; ++y) { // d/du along each row
            for (int x = 0; x < s; ++x)
                line[static_cast<size_t>(x)] = h[static_cast<size_t>(y) * s + x];
            spectralDerivative(line);
            for (int x = 0; x < s; ++x)
                du[static_cast<size_t>(y) * s + x] = line[static_cast<size_t>(x)].real();
        }
        for (int x = 0; x < s; ++x) { // d/dv along each column
            for (int y = 0; y < s; ++y)
                line[static_cast<size_t>(y)] = h[static_cast<size_t>(y) * s + x];
            spectralDerivative(line);
            for (int y = 0; y < s; ++y)
                dv[static_cast<size_t>(y) * s + x] = line[static_cast<size_t>(y)].real();
        }
        float* out = &map.texels[static_cast<size_t>(f) * texels * 4];
        for (int y = 0; y < s; ++y)
            for (int x = 0; x < s; ++x) {
                const size_t i = static_cast<size_t>(y) * s + x;
                // Rounded to half like a generated map: the CPU samples exactly what RGBA16F holds.
                out[i * 4 + 0] = toHalfChecked(h[i], field, "height", f, x, y);
                out[i * 4 + 1] = toHalfChecked(du[i], field, "slope dh/du", f, x, y);
                out[i * 4 + 2] = toHalfChecked(dv[i], field, "slope dh/dv", f, x, y);
                out[i * 4 + 3] =
                    toHalfChecked(du[i] * du[i] + dv[i] * dv[i], field, "squared slope", f, x, y);
            }
    }
    // A still image: every slice is the same.
    for (int f = image.frames; f < frames; ++f)
        std::copy_n(map.texels.begin(), texels * 4,
                    map.texels.begin() + static_cast<std::ptrdiff_t>(f * texels * 4));
    return map;
}

namespace {

/// Every field of the description in range (std::invalid_argument naming the field otherwise); the
/// combined levels are checked by the constructor, which counts them.
void validate(const HeightOctavesDesc& desc) {
    const auto& oct = desc.octaves;
    require(!oct.empty() && oct.size() <= 8,
            "HeightOctavesDesc.octaves must hold 1..8 octaves, got " + std::to_string(oct.size()));
    require(desc.displacedOctaves >= 0 && desc.displacedOctaves <= static_cast<int>(oct.size()),
            "HeightOctavesDesc.displacedOctaves must be in [0, " + std::to_string(oct.size()) + "], got " +
                std::to_string(desc.displacedOctaves));
    require(desc.mapSize >= 16 && desc.mapSize <= 1024 && (desc.mapSize & (desc.mapSize - 1)) == 0,
            "HeightOctavesDesc.mapSize must be a power of two in [16, 1024], got " +
                std::to_string(desc.mapSize));
    require(desc.frames >= 2 && desc.frames <= 256,
            "HeightOctavesDesc.frames must be in [2, 256], got " + std::to_string(desc.frames));
    require(desc.wavesPerOctave >= 1 && desc.wavesPerOctave <= 512,
            "HeightOctavesDesc.wavesPerOctave must be in [1, 512], got " +
                std::to_string(desc.wavesPerOctave));
    require(std::isfinite(desc.windDirectionDeg), "HeightOctavesDesc.windDirectionDeg must be finite");
    for (size_t i = 0; i < oct.size(); ++i) {
        const std::string f = "HeightOctavesDesc.octaves[" + std::to_string(i) + "].";
        require(std::isfinite(oct[i].tileSize) && oct[i].tileSize > 0.0,
                f + "tileSize must be finite and > 0");
        require(std::isfinite(oct[i].amplitude) && oct[i].amplitude >= 0.0,
                f + "amplitude must be finite and >= 0");
        require(std::isfinite(oct[i].loopPeriod) && oct[i].loopPeriod > 0.0,
                f + "loopPeriod must be finite and > 0");
    }
    require(desc.vertexFilter >= VertexFilter::Nearest && desc.vertexFilter <= VertexFilter::Trilinear,
            "HeightOctavesDesc.vertexFilter is not a VertexFilter value: " +
                std::to_string(static_cast<int>(desc.vertexFilter)));
    require(std::isfinite(desc.trilinearLodTexels) && desc.trilinearLodTexels > 0.0,
            "HeightOctavesDesc.trilinearLodTexels must be finite and > 0, got " +
                std::to_string(desc.trilinearLodTexels));
    require(desc.combinedSize >= 16 && desc.combinedSize <= 4096 &&
                (desc.combinedSize & (desc.combinedSize - 1)) == 0,
            "HeightOctavesDesc.combinedSize must be a power of two in [16, 4096], got " +
                std::to_string(desc.combinedSize));
    require(std::isfinite(desc.combinedTexel) && desc.combinedTexel > 0.0,
            "HeightOctavesDesc.combinedTexel must be finite and > 0, got " +
                std::to_string(desc.combinedTexel));
    require(std::isfinite(desc.combinedRadius) && desc.combinedRadius > 0.0,
            "HeightOctavesDesc.combinedRadius must be finite and > 0, got " +
                std::to_string(desc.combinedRadius));
    require(desc.images.empty() || desc.images.size() == oct.size(),
            "HeightOctavesDesc.images must be empty or hold one entry per octave (" +
                std::to_string(oct.size()) + "), got " + std::to_string(desc.images.size()));
    for (size_t i = 0; i < desc.images.size(); ++i)
        require(desc.images[i].heights.empty() || desc.images[i].size == desc.mapSize,
                "HeightOctavesDesc.images[" + std::to_string(i) +
                    "].size must equal HeightOctavesDesc.mapSize (" + std::to_string(desc.mapSize) +
                    "), got " + std::to_string(desc.images[i].size));
}

/// The height's mip chain of one map (listing 18-3 needs the packed maps of two levels): 2x2 box average,
/// rounded to half like the RGBA16F texture the GPU samples.
std::vector<std::vector<float>> heightMips(const OctaveMap& m) {
    std::vector<std::vector<float>> levels;
    for (int fine = m.size; fine > 1; fine /= 2) {
        const int c = fine / 2;
        std::vector<float> next(static_cast<size_t>(m.frames) * c * c);
        for (int f = 0; f < m.frames; ++f) {
            for (int y = 0; y < c; ++y) {
                for (int x = 0; x < c; ++x) {
                    double sum = 0.0;
                    for (int k = 0; k < 4; ++k) {
                        const int fx = 2 * x + (k & 1), fy = 2 * y + (k >> 1);
                        sum += levels.empty()
                                   ? m.texel(f, fx, fy)[0]
                                   : levels.back()[(static_cast<size_t>(f) * fine + fy) * fine + fx];
                    }
                    next[(static_cast<size_t>(f) * c + y) * c + x] =
                        glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(0.25 * sum)));
                }
            }
        }
        levels.push_back(std::move(next));
    }
    return levels;
}

/// The largest height step between neighbouring texels of a map (wrapping).
double maxStep(const OctaveMap& m) {
    double step = 0.0;
    for (int f = 0; f < m.frames; ++f)
        for (int y = 0; y < m.size; ++y)
            for (int x = 0; x < m.size; ++x) {
                const double h = m.texel(f, x, y)[0];
                step = std::max(step, std::abs(m.texel(f, (x + 1) % m.size, y)[0] - h));
                step = std::max(step, std::abs(m.texel(f, x, (y + 1) % m.size)[0] - h));
            }
    return step;
}

} // namespace

HeightOctaves::HeightOctaves(const HeightOctavesDesc& desc) : mDesc(desc) {
    validate(desc);
    const auto& oct = desc.octaves;
    mCombinedLevels = 1;
    while (combinedReach(mCombinedLevels - 1) < desc.combinedRadius && mCombinedLevels <= MAX_COMBINED_LEVELS)
        ++mCombinedLevels;
    require(mCombinedLevels <= MAX_COMBINED_LEVELS,
            "HeightOctavesDesc.combinedRadius " + std::to_string(desc.combinedRadius) + " needs more than " +
                std::to_string(MAX_COMBINED_LEVELS) + " combined levels of combinedSize " +
                std::to_string(desc.combinedSize) + " from combinedTexel " +
                std::to_string(desc.combinedTexel));

    std::mt19937_64 rng(desc.seed);
    for (size_t i = 0; i < oct.size(); ++i) {
        if (i < desc.images.size() && !desc.images[i].heights.empty()) {
            (void)makeWaves(oct[i], desc, rng); // keeps the generated octaves the same as without images
            const OctaveImage& image = desc.images[i];
            mMaps.push_back(
                makeOctaveMap(image, desc.frames, "HeightOctavesDesc.images[" + std::to_string(i) + "]"));
            double sum = 0.0, sumSq = 0.0;
            for (float h : image.heights) {
                sum += h;
                sumSq += double(h) * h;
            }
            const double n = static_cast<double>(image.heights.size());
            mRms.push_back(std::sqrt(std::max(0.0, sumSq / n - (sum / n) * (sum / n)))); // about the mean
        } else {
            mMaps.push_back(generate(oct[i], desc, rng));
            mRms.push_back(1.0);
        }
    }
    for (const OctaveMap& m : mMaps) {
        mHeightMips.push_back(heightMips(m));
        mMaxStep.push_back(maxStep(m));
    }
    for (int i = 0; desc.foamMemory && i < desc.displacedOctaves; ++i) {
        const OctaveDesc& o = oct[static_cast<size_t>(i)];
        mMaps[static_cast<size_t>(i)].foam =
            foamMemory(mMaps[static_cast<size_t>(i)], o.tileSize / desc.mapSize, o.loopPeriod / desc.frames);
    }
    for (int i = 0; i < desc.displacedOctaves; ++i) {
        float peak = 0.0f;
        for (size_t t = 0; t < mMaps[i].texels.size(); t += 4)
            peak = std::max(peak, std::abs(mMaps[i].texels[t]));
        mMaxDisplacement += oct[i].amplitude * peak;
    }
}

std::vector<float> foamMemory(const OctaveMap& map, double texelMetres, double sliceSeconds) {
    if (!(texelMetres > 0.0) || !(sliceSeconds > 0.0))
        throw std::invalid_argument("foamMemory(): texelMetres and sliceSeconds must be > 0");
    const int s = map.size, frames = map.frames;
    const size_t area = static_cast<size_t>(s) * s;
    const double decay = std::exp(-sliceSeconds / FOAM_DECAY_TIME);
    const double variance = 2.0 * FOAM_SPREAD_DIFFUSIVITY * sliceSeconds / (texelMetres * texelMetres);
    const int passes = std::max(1, static_cast<int>(std::ceil(variance / 0.5))); // w = variance / 2 <= 1/4
    const double w = 0.5 * variance / passes;
    std::vector<double> m(area, 0.0), tmp(area);
    auto spread = [&]() {
        for (int p = 0; p < passes; ++p) {
            for (int y = 0; y < s; ++y)
                for (int x = 0; x < s; ++x) {
                    const size_t r = static_cast<size_t>(y) * s;
                    tmp[r + x] =
                        (1.0 - 2.0 * w) * m[r + x] + w * (m[r + (x + s - 1) % s] + m[r + (x + 1) % s]);
                }
            for (int y = 0; y < s; ++y)
                for (int x = 0; x < s; ++x)
                    m[static_cast<size_t>(y) * s + x] =
                        (1.0 - 2.0 * w) * tmp[static_cast<size_t>(y) * s + x] +
                        w * (tmp[static_cast<size_t>((y + s - 1) % s) * s + x] +
                             tmp[static_cast<size_t>((y + 1) % s) * s + x]);
        }
    };
    std::vector<float> out(area * frames);
    for (int lap = 0; lap < 2; ++lap)
        for (int f = 0; f < frames; ++f) {
            spread();
            for (int y = 0; y < s; ++y)
                for (int x = 0; x < s; ++x) {
                    double& v = m[static_cast<size_t>(y) * s + x];
                    v = std::max(std::max(static_cast<double>(map.texel(f, x, y)[0]), 0.0), decay * v);
                    if (lap == 1)
                        out[static_cast<size_t>(f) * area + static_cast<size_t>(y) * s + x] =
                            glm::unpackHalf1x16(glm::packHalf1x16(static_cast<float>(v)));
                }
        }
    return out;
}

std::vector<OctaveFrameParams> HeightOctaves::frameParams(const glm::dvec2& cameraXY, double time) const {
    std::vector<OctaveFrameParams> out;
    for (const OctaveDesc& o : mDesc.octaves) {
        OctaveFrameParams p{};
        const double b = 1.0 / o.tileSize;
        // Wrap in double: the GPU only ever sees [0,1) offsets and [0, frames) positions.
        p.uvOffset = glm::vec2(static_cast<float>(wrapPhase(cameraXY.x * b, 1.0)),
                               static_cast<float>(wrapPhase(cameraXY.y * b, 1.0)));
        p.invTileSize = static_cast<float>(b);
        p.amplitude = static_cast<float>(o.amplitude);
        p.framePosition = static_cast<float>(wrapPhase(time, o.loopPeriod) / o.loopPeriod * mDesc.frames);
        if (p.framePosition >= static_cast<float>(mDesc.frames)) // float rounding up to `frames`
            p.framePosition = 0.0f;
        out.push_back(p);
    }
    return out;
}

namespace {

/// A looped map (size^2 texels, `frames` slices) at tile coordinate u and frame position: bilinear in space
/// with texel centres at (i + 0.5) / size (ocean_common.glsl sampleOctave()), then linear in time.
/// value(frame, x, y) gives a texel (double or glm::dvec3).
template <typename F>
auto loopedBilinear(int size, int frames, const glm::dvec2& u, double framePosition, const F& value) {
    const double px = wrapPhase(u.x, 1.0) * size - 0.5, py = wrapPhase(u.y, 1.0) * size - 0.5;
    const double fx0 = std::floor(px), fy0 = std::floor(py);
    const double ax = px - fx0, ay = py - fy0;
    const int x0 = wrapIndex(static_cast<long long>(fx0), size),
              x1 = wrapIndex(static_cast<long long>(fx0) + 1, size);
    const int y0 = wrapIndex(static_cast<long long>(fy0), size),
              y1 = wrapIndex(static_cast<long long>(fy0) + 1, size);
    const double ff = std::floor(framePosition);
    const double at = framePosition - ff;
    auto bilinear = [&](int f) {
        const auto bottom = value(f, x0, y0) + (value(f, x1, y0) - value(f, x0, y0)) * ax;
        const auto top = value(f, x0, y1) + (value(f, x1, y1) - value(f, x0, y1)) * ax;
        return bottom + (top - bottom) * ay;
    };
    const auto a = bilinear(wrapIndex(static_cast<long long>(ff), frames));
    const auto b = bilinear(wrapIndex(static_cast<long long>(ff) + 1, frames));
    return a + (b - a) * at;
}

} // namespace

glm::dvec3 HeightOctaves::sampleMap(int octave, const glm::dvec2& u, double framePosition) const {
    const OctaveMap& map = mMaps[static_cast<size_t>(octave)];
    return loopedBilinear(map.size, map.frames, u, framePosition, [&](int f, int x, int y) {
        const float* t = map.texel(f, x, y);
        return glm::dvec3(t[0], t[1], t[2]);
    });
}

glm::dvec3 HeightOctaves::heightAndGradient(const glm::dvec2& worldXY, double time, int octaveCount) const {
    glm::dvec3 sum(0.0);
    const int n = std::min(octaveCount, static_cast<int>(mMaps.size()));
    for (int i = 0; i < n; ++i) {
        const OctaveDesc& o = mDesc.octaves[static_cast<size_t>(i)];
        const double b = 1.0 / o.tileSize;
        const double fpos = wrapPhase(time, o.loopPeriod) / o.loopPeriod * mDesc.frames;
        const glm::dvec3 h = sampleMap(i, worldXY * b, fpos);
        // H = sum A_i h_i(B_i x): dH/dx = A_i B_i dh/du.
        sum += glm::dvec3(o.amplitude * h.x, o.amplitude * b * h.y, o.amplitude * b * h.z);
    }
    return sum;
}

double HeightOctaves::octaveSlopeVariance(int octave) const {
    const OctaveMap& map = mMaps[static_cast<size_t>(octave)];
    const OctaveDesc& o = mDesc.octaves[static_cast<size_t>(octave)];
    double sx = 0.0, sy = 0.0, ss = 0.0;
    const size_t n = map.texels.size() / 4;
    for (size_t k = 0; k < n; ++k) {
        const double gx = map.texels[k * 4 + 1], gy = map.texels[k * 4 + 2];
        sx += gx;
        sy += gy;
        ss += gx * gx + gy * gy;
    }
    const double count = static_cast<double>(std::max<size_t>(n, 1));
    const double scale = o.amplitude / o.tileSize;
    return scale * scale * std::max(ss / count - (sx * sx + sy * sy) / (count * count), 0.0);
}

double HeightOctaves::foamHeightAt(const glm::dvec2& worldXY, double time) const {
    double sum = 0.0;
    for (int i = 0; i < mDesc.displacedOctaves; ++i) {
        const OctaveDesc& o = mDesc.octaves[static_cast<size_t>(i)];
        const OctaveMap& map = mMaps[static_cast<size_t>(i)];
        const size_t area = static_cast<size_t>(map.size) * map.size;
        const double fpos = wrapPhase(time, o.loopPeriod) / o.loopPeriod * mDesc.frames;
        sum += o.amplitude *
               loopedBilinear(map.size, map.frames, worldXY / o.tileSize, fpos, [&](int f, int x, int y) {
                   const size_t k = static_cast<size_t>(f) * area + static_cast<size_t>(y) * map.size + x;
                   return double(map.foam.empty() ? map.texels[k * 4] : map.foam[k]);
               });
    }
    return sum;
}

double HeightOctaves::heightAt(const glm::dvec2& worldXY, double time) const {
    return heightSeenFrom(worldXY, time, worldXY);
}

float HeightOctaves::heightMip(int octave, int level, int frame, int x, int y) const {
    const OctaveMap& map = mMaps[static_cast<size_t>(octave)];
    const int s = map.size >> level;
    x = wrapIndex(x, s);
    y = wrapIndex(y, s);
    if (level == 0)
        return map.texel(frame, x, y)[0];
    const std::vector<float>& l = mHeightMips[static_cast<size_t>(octave)][static_cast<size_t>(level - 1)];
    return l[(static_cast<size_t>(frame) * s + y) * s + x];
}

glm::vec4 HeightOctaves::packedTexel(int octave, int level, int frame, int x, int y) const {
    // GPU Gems 2 §18.2.4: "we can pack four height values into a single texel of a four-component texture".
    return {heightMip(octave, level, frame, x, y), heightMip(octave, level, frame, x + 1, y),
            heightMip(octave, level, frame, x, y + 1), heightMip(octave, level, frame, x + 1, y + 1)};
}

double HeightOctaves::packedBilinear(int octave, int level, int frame, const glm::dvec2& u) const {
    // Listing 18-2 (tex2D_bilinear4x) with the footprint's lower-left texel fetched by index: same texel
    // centre convention as Bilinear, so level 0 gives the identical value.
    const int s = mDesc.mapSize >> level;
    const double px = wrapPhase(u.x, 1.0) * s - 0.5, py = wrapPhase(u.y, 1.0) * s - 0.5;
    const double fx0 = std::floor(px), fy0 = std::floor(py);
    const double ax = px - fx0, ay = py - fy0;
    const glm::dvec4 t(packedTexel(octave, level, frame, static_cast<int>(fx0), static_cast<int>(fy0)));
    const double ab0 = t.x + (t.y - t.x) * ax; // lerp(tAB0.xz, tAB0.yw, f.x)
    const double ab1 = t.z + (t.w - t.z) * ax;
    return ab0 + (ab1 - ab0) * ay; // lerp(tAB.x, tAB.y, f.y)
}

double HeightOctaves::sliceHeight(int octave, VertexFilter filter, int level, int frame,
                                  const glm::dvec2& u) const {
    switch (filter) {
    case VertexFilter::Nearest:
    case VertexFilter::Bilinear:
    case VertexFilter::HardwareBilinear:
        return frameHeight(octave, frame, footprint(octave, filter, u));
    case VertexFilter::Packed4Tap:
    case VertexFilter::Trilinear:
        break;
    }
    return packedBilinear(octave, level, frame, u);
}

double HeightOctaves::sampleHeight(int octave, VertexFilter filter, const glm::dvec2& u, double framePosition,
                                   double lod) const {
    const double ff = std::floor(framePosition);
    const double at = framePosition - ff;
    const int f0 = wrapIndex(static_cast<long long>(ff), mDesc.frames);
    const int f1 = wrapIndex(static_cast<long long>(ff) + 1, mDesc.frames);
    auto slice = [&](int frame) {
        if (filter != VertexFilter::Trilinear)
            return sliceHeight(octave, filter, 0, frame, u);
        // Listing 18-3 (tex2D_trilinear): snap to the nearer level outside the 0.3..0.7 band of the LOD
        // fraction (one packed fetch), blend the two levels inside it (two fetches).
        const double l = std::clamp(lod, 0.0, static_cast<double>(mipLevels() - 1));
        const double base = std::floor(l);
        const double fr = l - base;
        const int level = static_cast<int>(base);
        if (fr < TRILINEAR_BAND_LOW)
            return packedBilinear(octave, level, frame, u);
        if (fr > TRILINEAR_BAND_HIGH)
            return packedBilinear(octave, level + 1, frame, u);
        const double r0 = packedBilinear(octave, level, frame, u);
        const double r1 = packedBilinear(octave, level + 1, frame, u);
        const double w = (fr - TRILINEAR_BAND_LOW) / (TRILINEAR_BAND_HIGH - TRILINEAR_BAND_LOW);
        return r0 + (r1 - r0) * w;
    };
    if (filter == VertexFilter::Trilinear || filter == VertexFilter::Packed4Tap) {
        const double a = slice(f0), b = slice(f1);
        return a + (b - a) * at;
    }
    // Nearest and bilinear: both frames share the footprint, worked out once (the same operations as
    // sliceHeight(), so the same bits: a query reads each frame's four texels and wraps the point once).
    const Footprint f = footprint(octave, filter, u);
    const double a = frameHeight(octave, f0, f), b = frameHeight(octave, f1, f);
    return a + (b - a) * at;
}

HeightOctaves::Footprint HeightOctaves::footprint(int octave, VertexFilter filter,
                                                  const glm::dvec2& u) const {
    const int s = mDesc.mapSize;
    const double wx = wrapPhase(u.x, 1.0), wy = wrapPhase(u.y, 1.0);
    Footprint f;
    const int n = mMaps[static_cast<size_t>(octave)].size; // heightMip's wrap at level 0
    if (filter == VertexFilter::Nearest) {
        // The texel whose square [i, i + 1) / size holds u (GL's NEAREST rule).
        f.nearest = true;
        f.x0 = f.x1 = wrapIndex(static_cast<int>(std::floor(wx * s)), n);
        f.y0 = f.y1 = wrapIndex(static_cast<int>(std::floor(wy * s)), n);
        return f;
    }
    double px = wx * s - 0.5, py = wy * s - 0.5;
    if (filter == VertexFilter::HardwareBilinear) {
        // Fixed-point sub-texel position with HARDWARE_WEIGHT_BITS fractional bits, rounded to nearest.
        const double q = std::ldexp(1.0, HARDWARE_WEIGHT_BITS);
        px = std::floor(px * q + 0.5) / q;
        py = std::floor(py * q + 0.5) / q;
    }
    const double fx0 = std::floor(px), fy0 = std::floor(py);
    f.ax = px - fx0;
    f.ay = py - fy0;
    const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
    f.x0 = wrapIndex(x0, n);
    f.x1 = wrapIndex(x0 + 1, n);
    f.y0 = wrapIndex(y0, n);
    f.y1 = wrapIndex(y0 + 1, n);
    return f;
}

double HeightOctaves::frameHeight(int octave, int frame, const Footprint& f) const {
    const OctaveMap& map = mMaps[static_cast<size_t>(octave)];
    auto at = [&](int x, int y) { return static_cast<double>(map.texel(frame, x, y)[0]); }; // wrapped already
    if (f.nearest)
        return at(f.x0, f.y0);
    const double h00 = at(f.x0, f.y0), h10 = at(f.x1, f.y0), h01 = at(f.x0, f.y1), h11 = at(f.x1, f.y1);
    const double bottom = h00 + (h10 - h00) * f.ax;
    const double top = h01 + (h11 - h01) * f.ax;
    return bottom + (top - bottom) * f.ay;
}

double HeightOctaves::trilinearLod(int octave, double distance) const {
    const double texels = distance / mDesc.octaves[static_cast<size_t>(octave)].tileSize * mDesc.mapSize;
    const double rho = texels / mDesc.trilinearLodTexels;
    return std::clamp(std::log2(std::max(rho, 1.0)), 0.0, static_cast<double>(mipLevels() - 1));
}

double HeightOctaves::filteredHeight(const glm::dvec2& worldXY, double time, const glm::dvec2& cameraXY,
                                     VertexFilter filter) const {
    const double distance = glm::length(worldXY - cameraXY);
    double sum = 0.0;
    for (int i = 0; i < mDesc.displacedOctaves; ++i) {
        const OctaveDesc& o = mDesc.octaves[static_cast<size_t>(i)];
        const double b = 1.0 / o.tileSize;
        const double fpos = wrapPhase(time, o.loopPeriod) / o.loopPeriod * mDesc.frames;
        const double lod = filter == VertexFilter::Trilinear ? trilinearLod(i, distance) : 0.0;
        sum += o.amplitude * sampleHeight(i, filter, worldXY * b, fpos, lod);
    }
    return sum;
}

double HeightOctaves::combinedTexel(int level) const {
    return std::ldexp(mDesc.combinedTexel, level);
}

double HeightOctaves::combinedReach(int level) const {
    return (mDesc.combinedSize / 2 - 2) * combinedTexel(level);
}

int HeightOctaves::combinedLevelFor(const glm::dvec2& rel) const {
    const double r = std::max(std::abs(rel.x), std::abs(rel.y));
    int k = 0;
    while (k < mCombinedLevels - 1 && r > combinedReach(k))
        ++k;
    return k;
}

glm::dvec2 HeightOctaves::combinedOrigin(int level, const glm::dvec2& cameraXY) const {
    const double texel = combinedTexel(level);
    return glm::floor(cameraXY / texel) * texel;
}

double HeightOctaves::combinedHeight(const glm::dvec2& worldXY, double time, const glm::dvec2& cameraXY,
                                     VertexFilter filter) const {
    const int k = combinedLevelFor(worldXY - cameraXY);
    const double texel = combinedTexel(k);
    const glm::dvec2 origin = combinedOrigin(k, cameraXY);
    const int n = mDesc.combinedSize;
    // Texel-centre convention: node (i, j) at origin + ((i, j) + 0.5 - n / 2) * texel. Points beyond the
    // last level's reach clamp to its border.
    const glm::dvec2 p =
        glm::clamp((worldXY - origin) / texel + (n / 2 - 0.5), glm::dvec2(0.0), glm::dvec2(n - 1));
    const glm::dvec2 p0 = glm::min(glm::floor(p), glm::dvec2(n - 2));
    const glm::dvec2 a = p - p0;
    auto node = [&](double i, double j) {
        const glm::dvec2 world = origin + (glm::dvec2(i, j) + (0.5 - n / 2)) * texel;
        return filteredHeight(world, time, cameraXY, filter);
    };
    const double g00 = node(p0.x, p0.y), g10 = node(p0.x + 1, p0.y);
    const double g01 = node(p0.x, p0.y + 1), g11 = node(p0.x + 1, p0.y + 1);
    const double bottom = g00 + (g10 - g00) * a.x;
    const double top = g01 + (g11 - g01) * a.x;
    return bottom + (top - bottom) * a.y;
}

double HeightOctaves::heightSeenFrom(const glm::dvec2& worldXY, double time,
                                     const glm::dvec2& cameraXY) const {
    return mDesc.combinedDisplacement ? combinedHeight(worldXY, time, cameraXY, mDesc.vertexFilter)
                                      : filteredHeight(worldXY, time, cameraXY, mDesc.vertexFilter);
}

glm::dvec3 HeightOctaves::displacementSeenFrom(const glm::dvec2& worldXY, double time,
                                               const glm::dvec2& cameraXY) const {
    return {0.0, 0.0, heightSeenFrom(worldXY, time, cameraXY)};
}

double HeightOctaves::hardwareBilinearBound() const {
    double sum = 0.0;
    for (int i = 0; i < mDesc.displacedOctaves; ++i)
        sum += mDesc.octaves[static_cast<size_t>(i)].amplitude * 2.0 *
               std::ldexp(1.0, -HARDWARE_WEIGHT_BITS) * mMaxStep[static_cast<size_t>(i)];
    return sum;
}

const char* toString(VertexFilter filter) {
    switch (filter) {
    case VertexFilter::Nearest:
        return "nearest";
    case VertexFilter::Bilinear:
        return "bilinear";
    case VertexFilter::HardwareBilinear:
        return "hardware-bilinear";
    case VertexFilter::Packed4Tap:
        return "packed-4tap";
    case VertexFilter::Trilinear:
        return "trilinear";
    }
    return "?";
}

glm::dvec3 HeightOctaves::normalAt(const glm::dvec2& worldXY, double time) const {
    const glm::dvec3 hg = heightAndGradient(worldXY, time, static_cast<int>(mMaps.size()));
    return glm::normalize(glm::dvec3(-hg.y, -hg.z, 1.0));
}

glm::dvec3 HeightOctaves::displacementAt(const glm::dvec2& worldXY, double time) const {
    return {0.0, 0.0, heightAt(worldXY, time)};
}

double HeightOctaves::significantWaveHeight() const {
    double sumSq = 0.0;
    for (int i = 0; i < mDesc.displacedOctaves; ++i) {
        const double a = mDesc.octaves[static_cast<size_t>(i)].amplitude * mRms[static_cast<size_t>(i)];
        sumSq += a * a;
    }
    return 4.0 * std::sqrt(sumSq);
}

} // namespace pacifica::ocean
