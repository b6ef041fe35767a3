// FftSampled: the FFT sea's tiles inverse-transformed on the CPU (KissFFT) and interpolated (FftSampled.h).
#include "ocean/FftSampled.h"

#include "engine/Time.h"

#include <kiss_fftnd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <exception>
#include <iterator>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>

namespace pacifica::ocean {

namespace {

constexpr double TWO_PI = 2.0 * std::numbers::pi;

/// kiss_fftnd's configuration for inverse N x N transforms: out(b, a) = sum_{m, i} in(m, i) e^{+2 pi i (m b +
/// i a) / N} (inverse = 1 is unnormalised, as the sum needs).
using FftConfig = std::unique_ptr<void, void (*)(void*)>;

FftConfig inverseConfig(int n) {
    const int dims[2] = {n, n};
    FftConfig config(kiss_fftnd_alloc(dims, 2, 1, nullptr, nullptr), [](void* p) { kiss_fft_free(p); });
    if (!config)
        throw std::bad_alloc();
    return config;
}

/// Keys' cubic convolution weights (a = -0.5, the Catmull-Rom spline) of the samples at -1, 0, 1, 2 for a
/// point f in [0, 1) past sample 0 (Keys 1981, eq. 15).
glm::dvec4 cubicWeights(double f) {
    const double f2 = f * f, f3 = f2 * f;
    return {-0.5 * f3 + f2 - 0.5 * f, 1.5 * f3 - 2.5 * f2 + 1.0, -1.5 * f3 + 2.0 * f2 + 0.5 * f,
            0.5 * f3 - 0.5 * f2};
}

/// d/df of cubicWeights(f).
glm::dvec4 cubicSlopes(double f) {
    const double f2 = f * f;
    return {-1.5 * f2 + 2.0 * f - 0.5, 4.5 * f2 - 5.0 * f, -4.5 * f2 + 4.0 * f + 0.5, 1.5 * f2 - f};
}

} // namespace

struct FftSampledSea::Tile {
    int n = 0;
    double size = 0.0;
    std::vector<glm::vec3> values;   // (lambda Dx, lambda Dy, h) at x = (a, b) L / N, row b, column a
    std::vector<glm::vec3> velocity; // d/dt of the same (empty unless asked for)
    std::vector<glm::vec3> sampled;  // values at the sampled time, with velocity (extrapolateTo's start)
    // The transform's planes: h, Dx + i Dy (both fields are real), their time derivatives, and the output.
    std::vector<kiss_fft_cpx> heights, sideways, heightRates, sidewaysRates, out;
    FftConfig config{nullptr, [](void*) {}};

    Tile(int size_, double metres, bool withVelocity) : n(size_), size(metres), config(inverseConfig(size_)) {
        const size_t count = static_cast<size_t>(n) * static_cast<size_t>(n);
        values.resize(count);
        heights.resize(count);
        sideways.resize(count);
        out.resize(count);
        if (withVelocity) {
            velocity.resize(count);
            sampled.resize(count);
            heightRates.resize(count);
            sidewaysRates.resize(count);
        }
    }
    /// Inverse-transforms `plane` and stores it in place.
    void inverse(std::vector<kiss_fft_cpx>& plane) {
        kiss_fftnd(static_cast<kiss_fftnd_cfg>(config.get()), plane.data(), out.data());
        plane.swap(out);
    }
};

void FftSampledSea::sampleTile(const FftOcean& sea, double t, Tile& tile) {
    const FftDesc& d = sea.desc();
    const int n = d.size;
    const bool rates = !tile.velocity.empty();
    // The time phase of every component as FftOcean::sumAt takes it: e^{i w t} = e^{i 2 pi q s}, s = wrap(t,
    // T) / T (Tessendorf 2001, "looping in time"), turns reduced mod 1 in double.
    const double s = wrapPhase(t, d.loopPeriod) / d.loopPeriod;
    const double dk = TWO_PI / d.tileSize, w0 = TWO_PI / d.loopPeriod;
    const std::vector<std::complex<double>>& h0 = sea.h0();
    const std::vector<uint32_t>& q = sea.omegaMultiple();
    const kiss_fft_cpx zero{0.0f, 0.0f};
    auto store = [](const std::complex<double>& c) {
        return kiss_fft_cpx{static_cast<float>(c.real()), static_cast<float>(c.imag())};
    };
    for (int m = 0; m < n; ++m) {
        for (int i = 0; i < n; ++i) {
            const size_t idx = static_cast<size_t>(m) * n + i;
            // The Nyquist row and column (index 0) hold nothing (FftOcean.h), nor does k = 0.
            if (m == 0 || i == 0 || q[idx] == 0) {
                tile.heights[idx] = tile.sideways[idx] = zero;
                if (rates)
                    tile.heightRates[idx] = tile.sidewaysRates[idx] = zero;
                continue;
            }
            const size_t neg = static_cast<size_t>(n - m) * n + (n - i); // the lattice index of -k
            const double turns = q[idx] * s;
            const double r = turns - std::round(turns);
            const std::complex<double> e(std::cos(TWO_PI * r), std::sin(TWO_PI * r));
            // Tessendorf 2001 eq. 26: htilde = h0(k) e^{i w t} + conj(h0(-k)) e^{-i w t}.
            const std::complex<double> up = h0[idx] * e, down = std::conj(h0[neg]) * std::conj(e);
            const std::complex<double> ht = up + down;
            const double kx = dk * (i - n / 2), ky = dk * (m - n / 2);
            const double k = std::sqrt(kx * kx + ky * ky);
            // Eq. 29: D = -i (k / |k|) htilde per axis; Dx + i Dy carries both real fields in one transform:
            // -i (kx + i ky) / |k| htilde.
            const std::complex<double> chop(ky / k, -kx / k);
            tile.heights[idx] = store(ht);
            tile.sideways[idx] = store(chop * ht);
            if (rates) { // d/dt htilde = i w (h0 e^{i w t} - conj(h0(-k)) e^{-i w t})
                const std::complex<double> rate = std::complex<double>(0.0, q[idx] * w0) * (up - down);
                tile.heightRates[idx] = store(rate);
                tile.sidewaysRates[idx] = store(chop * rate);
            }
        }
    }
    tile.inverse(tile.heights);
    tile.inverse(tile.sideways);
    if (rates) {
        tile.inverse(tile.heightRates);
        tile.inverse(tile.sidewaysRates);
    }
    // Lattice index i stands for the wave number i - N/2: at x = a L / N its e^{i k x} is the transform's
    // e^{2 pi i i a / N} times e^{-i pi a} = (-1)^a (and (-1)^b along y).
    const float l = static_cast<float>(d.choppiness);
    for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
            const size_t j = static_cast<size_t>(b) * n + a;
            const float sign = (a + b) % 2 == 0 ? 1.0f : -1.0f;
            tile.values[j] =
                sign * glm::vec3(l * tile.sideways[j].r, l * tile.sideways[j].i, tile.heights[j].r);
            if (rates) {
                tile.velocity[j] = sign * glm::vec3(l * tile.sidewaysRates[j].r, l * tile.sidewaysRates[j].i,
                                                    tile.heightRates[j].r);
                tile.sampled[j] = tile.values[j];
            }
        }
}

FftSampledSea::FftSampledSea(const FftCascades& sea, Interpolation interpolation, bool velocity)
    : mSea(sea), mVelocity(velocity), mInterpolation(interpolation), mCascades(sea.cascades().size()) {
    for (const auto& tile : sea.cascades())
        mSources.push_back(tile.get());
    for (const auto& tile : sea.secondDraws())
        mSources.push_back(tile.get());
    for (const FftOcean* source : mSources)
        mTiles.push_back(std::make_unique<Tile>(source->desc().size, source->desc().tileSize, velocity));
}

FftSampledSea::FftSampledSea(const FftCascades& sea, double t, Interpolation interpolation, unsigned threads)
    : FftSampledSea(sea, interpolation, false) {
    ThreadPool pool(threads == 0 ? 0 : std::min<unsigned>(threads, static_cast<unsigned>(mTiles.size())));
    resample(t, pool.jobs());
}

FftSampledSea::~FftSampledSea() = default;
FftSampledSea::FftSampledSea(FftSampledSea&&) noexcept = default;

void FftSampledSea::resample(double t, const JobSystem& jobs) {
    if (!std::isfinite(t))
        throw std::invalid_argument("FftSampledSea: time must be finite, got " + std::to_string(t));
    struct Work {
        FftSampledSea* self;
        double t;
        std::atomic<bool> failed{false};
    } work{this, t};
    jobs.run(
        mTiles.size(),
        [](void* context, size_t i) {
            auto* w = static_cast<Work*>(context);
            try { // a job must not throw (Jobs.h): sampling allocates nothing, so nothing is expected here
                sampleTile(*w->self->mSources[i], w->t, *w->self->mTiles[i]);
            } catch (...) {
                w->failed = true;
            }
        },
        &work);
    if (work.failed) {
        mSampled = false;
        throw std::runtime_error("FftSampledSea::resample(): sampling a tile failed");
    }
    mTime = mSampledTime = t;
    mSampled = true;
}

void FftSampledSea::extrapolateTo(double t, const JobSystem& jobs) {
    requireSampled("extrapolateTo");
    if (!mVelocity)
        throw std::logic_error("FftSampledSea::extrapolateTo(): made without velocity");
    if (!std::isfinite(t))
        throw std::invalid_argument("FftSampledSea::extrapolateTo(): time must be finite, got " +
                                    std::to_string(t));
    struct Work {
        FftSampledSea* self;
        float dt;
    } work{this, static_cast<float>(t - mSampledTime)}; // the offset in double first
    jobs.run(
        mTiles.size(),
        [](void* context, size_t i) {
            auto* w = static_cast<Work*>(context);
            Tile& tile = *w->self->mTiles[i];
            for (size_t j = 0; j < tile.values.size(); ++j)
                tile.values[j] = tile.sampled[j] + w->dt * tile.velocity[j];
        },
        &work);
    mTime = t;
}

void FftSampledSea::requireSampled(const char* what) const {
    if (!mSampled)
        throw std::logic_error(std::string("FftSampledSea::") + what + "(): resample() first");
}

glm::dvec3 FftSampledSea::sample(const Tile& tile, const std::vector<glm::vec3>& values, const glm::dvec2& xy,
                                 glm::dvec3* ddx, glm::dvec3* ddy) const {
    const int n = tile.n;
    const double perMetre = n / tile.size;
    // The grid coordinate of xy, wrapped to the tile in double first (the tile repeats with period L).
    const glm::dvec2 u = glm::dvec2(wrapPhase(xy.x, tile.size), wrapPhase(xy.y, tile.size)) * perMetre;
    const int a0 = static_cast<int>(std::floor(u.x)), b0 = static_cast<int>(std::floor(u.y));
    const glm::dvec2 f = u - glm::dvec2(a0, b0);
    auto wrap = [n](int i) { return ((i % n) + n) % n; };
    auto at = [&](int a, int b) { return glm::dvec3(values[static_cast<size_t>(b) * n + a]); };
    if (mInterpolation == Interpolation::Bilinear) {
        const int a00 = wrap(a0), b00 = wrap(b0), a1 = wrap(a0 + 1), b1 = wrap(b0 + 1);
        const glm::dvec3 v00 = at(a00, b00), v10 = at(a1, b00), v01 = at(a00, b1), v11 = at(a1, b1);
        if (ddx) {
            *ddx = perMetre * glm::mix(v10 - v00, v11 - v01, f.y);
            *ddy = perMetre * glm::mix(v01 - v00, v11 - v10, f.x);
        }
        return glm::mix(glm::mix(v00, v10, f.x), glm::mix(v01, v11, f.x), f.y);
    }
    // The 4 x 4 neighbourhood's wrapped columns and rows, once each.
    const int cols[4] = {wrap(a0 - 1), wrap(a0), wrap(a0 + 1), wrap(a0 + 2)};
    const int rows[4] = {wrap(b0 - 1), wrap(b0), wrap(b0 + 1), wrap(b0 + 2)};
    const glm::dvec4 wx = cubicWeights(f.x), wy = cubicWeights(f.y);
    const glm::dvec4 sx = ddx ? cubicSlopes(f.x) : glm::dvec4(0.0),
                     sy = ddx ? cubicSlopes(f.y) : glm::dvec4(0.0);
    glm::dvec3 v(0.0), gx(0.0), gy(0.0);
    for (int j = 0; j < 4; ++j) {
        glm::dvec3 row(0.0), rowSlope(0.0);
        for (int i = 0; i < 4; ++i) {
            const glm::dvec3 p = at(cols[i], rows[j]);
            row += wx[i] * p;
            rowSlope += sx[i] * p;
        }
        v += wy[j] * row;
        gx += wy[j] * rowSlope;
        gy += sy[j] * row;
    }
    if (ddx) {
        *ddx = perMetre * gx;
        *ddy = perMetre * gy;
    }
    return v;
}

glm::dvec3 FftSampledSea::displacementAndSlopes(const glm::dvec2& xy, glm::dvec3* ddx,
                                                glm::dvec3* ddy) const {
    // As FftCascades::displacementAt: each cascade's two draws mixed by (cos theta_c, sin theta_c). The
    // slopes hold the weights (theta's own gradient, ~6 / L_c rad/m, left out, as FftCascades::normalAt
    // does).
    glm::dvec3 d(0.0), gx(0.0), gy(0.0), tx, ty;
    const bool second = mTiles.size() > mCascades;
    for (size_t c = 0; c < mCascades; ++c) {
        const glm::dvec2 w = mSea.mixWeights(static_cast<int>(c), xy);
        const Tile& first = *mTiles[c];
        d += w.x * sample(first, first.values, xy, ddx ? &tx : nullptr, &ty);
        if (ddx) {
            gx += w.x * tx;
            gy += w.x * ty;
        }
        if (second) {
            const Tile& other = *mTiles[mCascades + c];
            d += w.y * sample(other, other.values, xy, ddx ? &tx : nullptr, &ty);
            if (ddx) {
                gx += w.y * tx;
                gy += w.y * ty;
            }
        }
    }
    if (ddx) {
        *ddx = gx;
        *ddy = gy;
    }
    return d;
}

glm::dvec3 FftSampledSea::displacementAt(const glm::dvec2& xy) const {
    requireSampled("displacementAt");
    return displacementAndSlopes(xy, nullptr, nullptr);
}

glm::dvec2 FftSampledSea::lagrangianPointAt(const glm::dvec2& xy, glm::dvec3* displacement) const {
    // SurfaceModel::lagrangianPointAt's solve of F(x0) = x0 + d_xy(x0) - xy = 0 (Newton, step halving, |F| <
    // 1e-9 m), with the Jacobian I + grad d_xy from the interpolant's own slopes instead of central
    // differences: one evaluation per step instead of five (the same root; the Jacobian only steers).
    requireSampled("lagrangianPointAt");
    glm::dvec3 gx, gy;
    glm::dvec2 x0 = xy;
    glm::dvec3 d = displacementAndSlopes(x0, &gx, &gy);
    glm::dvec2 f = x0 + glm::dvec2(d) - xy;
    for (int i = 0; i < 32 && glm::length(f) > 1e-9; ++i) {
        const glm::dvec2 fx(1.0 + gx.x, gx.y), fy(gy.x, 1.0 + gy.y); // dF/dx, dF/dy
        const double det = fx.x * fy.y - fy.x * fx.y;
        glm::dvec2 step = -f; // fixed-point step where the Jacobian is singular (a fold)
        if (std::abs(det) > 1e-12)
            step = -glm::dvec2(fy.y * f.x - fy.x * f.y, -fx.y * f.x + fx.x * f.y) / det;
        double scale = 1.0;
        glm::dvec2 next = x0 + step;
        glm::dvec3 dn = displacementAndSlopes(next, &gx, &gy);
        glm::dvec2 fn = next + glm::dvec2(dn) - xy;
        while (glm::length(fn) >= glm::length(f) && scale > 1e-4) { // step halving keeps |F| decreasing
            scale *= 0.5;
            next = x0 + step * scale;
            dn = displacementAndSlopes(next, &gx, &gy);
            fn = next + glm::dvec2(dn) - xy;
        }
        x0 = next;
        d = dn;
        f = fn;
    }
    if (displacement)
        *displacement = d;
    return x0;
}

double FftSampledSea::heightAt(const glm::dvec2& xy) const {
    glm::dvec3 d;
    lagrangianPointAt(xy, &d);
    return d.z;
}

glm::dvec3 FftSampledSea::normalAt(const glm::dvec2& xy) const {
    requireSampled("normalAt");
    glm::dvec3 gx, gy;
    displacementAndSlopes(xy, &gx, &gy);
    // P(x0) = x0 + (dx, dy, h) (Tessendorf 2001 eq. 30): the normal is dP/dx x dP/dy.
    return glm::normalize(glm::cross(glm::dvec3(1.0 + gx.x, gx.y, gx.z), glm::dvec3(gy.x, 1.0 + gy.y, gy.z)));
}

glm::dvec3 FftSampledSea::velocityAt(const glm::dvec2& xy) const {
    requireSampled("velocityAt");
    if (!mVelocity)
        throw std::logic_error("FftSampledSea::velocityAt(): made without velocity");
    glm::dvec3 v(0.0);
    const bool second = mTiles.size() > mCascades;
    for (size_t c = 0; c < mCascades; ++c) {
        const glm::dvec2 w = mSea.mixWeights(static_cast<int>(c), xy);
        v += w.x * sample(*mTiles[c], mTiles[c]->velocity, xy, nullptr, nullptr);
        if (second)
            v += w.y * sample(*mTiles[mCascades + c], mTiles[mCascades + c]->velocity, xy, nullptr, nullptr);
    }
    return v;
}

void FftSampledSea::heightsAt(std::span<const glm::dvec2> points, std::span<double> heights) const {
    if (points.size() != heights.size())
        throw std::invalid_argument("FftSampledSea::heightsAt(): " + std::to_string(points.size()) +
                                    " points but " + std::to_string(heights.size()) + " heights");
    for (size_t i = 0; i < points.size(); ++i)
        heights[i] = heightAt(points[i]);
}

} // namespace pacifica::ocean
