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

/// Inverse transforms of N x N planes of lattice coefficients, in place: out(b, a) = sum_{m, i} in(m, i)
/// e^{+2 pi i (m b + i a) / N} (kiss_fftnd with inverse = 1 is unnormalised, as the sum needs).
class InverseTransform {
public:
    explicit InverseTransform(int n) : mConfig(alloc(n), [](void* p) { kiss_fft_free(p); }) {
        if (!mConfig)
            throw std::bad_alloc();
    }
    void operator()(std::vector<kiss_fft_cpx>& plane) const {
        std::vector<kiss_fft_cpx> out(plane.size());
        kiss_fftnd(static_cast<kiss_fftnd_cfg>(mConfig.get()), plane.data(), out.data());
        plane.swap(out);
    }

private:
    static void* alloc(int n) {
        const int dims[2] = {n, n};
        return kiss_fftnd_alloc(dims, 2, 1, nullptr, nullptr);
    }
    std::unique_ptr<void, void (*)(void*)> mConfig;
};

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

FftSampledSea::Tile FftSampledSea::sampleTile(const FftOcean& sea, double t) {
    const FftDesc& d = sea.desc();
    const int n = d.size;
    const size_t count = static_cast<size_t>(n) * static_cast<size_t>(n);
    // The time phase of every component as FftOcean::sumAt takes it: e^{i w t} = e^{i 2 pi q s}, s = wrap(t,
    // T) / T (Tessendorf 2001, "looping in time"), turns reduced mod 1 in double.
    const double s = wrapPhase(t, d.loopPeriod) / d.loopPeriod;
    const double dk = TWO_PI / d.tileSize;
    std::vector<kiss_fft_cpx> heights(count), sideways(count); // h; Dx + i Dy (both fields are real)
    const std::vector<std::complex<double>>& h0 = sea.h0();
    const std::vector<uint32_t>& q = sea.omegaMultiple();
    for (int m = 1; m < n; ++m) { // the Nyquist row and column (index 0) hold nothing (FftOcean.h)
        for (int i = 1; i < n; ++i) {
            const size_t idx = static_cast<size_t>(m) * n + i;
            if (q[idx] == 0)
                continue;                                                // k = 0
            const size_t neg = static_cast<size_t>(n - m) * n + (n - i); // the lattice index of -k
            const double turns = q[idx] * s;
            const double r = turns - std::round(turns);
            const std::complex<double> e(std::cos(TWO_PI * r), std::sin(TWO_PI * r));
            // Tessendorf 2001 eq. 26: htilde = h0(k) e^{i w t} + conj(h0(-k)) e^{-i w t}.
            const std::complex<double> ht = h0[idx] * e + std::conj(h0[neg]) * std::conj(e);
            const double kx = dk * (i - n / 2), ky = dk * (m - n / 2);
            const double k = std::sqrt(kx * kx + ky * ky);
            // Eq. 29: D = -i (k / |k|) htilde per axis; Dx + i Dy carries both real fields in one transform.
            const std::complex<double> dx = std::complex<double>(0.0, -kx / k) * ht;
            const std::complex<double> dy = std::complex<double>(0.0, -ky / k) * ht;
            const std::complex<double> both = dx + std::complex<double>(0.0, 1.0) * dy;
            heights[idx] = {static_cast<float>(ht.real()), static_cast<float>(ht.imag())};
            sideways[idx] = {static_cast<float>(both.real()), static_cast<float>(both.imag())};
        }
    }
    const InverseTransform inverse(n);
    inverse(heights);
    inverse(sideways);
    // Lattice index i stands for the wave number i - N/2: at x = a L / N its e^{i k x} is the transform's
    // e^{2 pi i i a / N} times e^{-i pi a} = (-1)^a (and (-1)^b along y).
    Tile tile{n, d.tileSize, std::vector<glm::vec3>(count)};
    const float l = static_cast<float>(d.choppiness);
    for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
            const size_t j = static_cast<size_t>(b) * n + a;
            const float sign = (a + b) % 2 == 0 ? 1.0f : -1.0f;
            tile.values[j] = sign * glm::vec3(l * sideways[j].r, l * sideways[j].i, heights[j].r);
        }
    return tile;
}

FftSampledSea::FftSampledSea(const FftCascades& sea, double t, Interpolation interpolation, unsigned threads)
    : mSea(sea), mTime(t), mInterpolation(interpolation) {
    if (!std::isfinite(t))
        throw std::invalid_argument("FftSampledSea: time must be finite, got " + std::to_string(t));
    std::vector<const FftOcean*> tiles;
    for (const auto& tile : sea.cascades())
        tiles.push_back(tile.get());
    for (const auto& tile : sea.secondDraws())
        tiles.push_back(tile.get());
    std::vector<Tile> sampled(tiles.size());
    std::vector<std::exception_ptr> errors(tiles.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i = next++; i < tiles.size(); i = next++) {
            try {
                sampled[i] = sampleTile(*tiles[i], t);
            } catch (...) {
                errors[i] = std::current_exception();
            }
        }
    };
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const size_t helpers = std::min<size_t>(threads == 0 ? hardware : threads, tiles.size());
    std::vector<std::thread> pool;
    for (size_t i = 1; i < helpers; ++i)
        pool.emplace_back(work);
    work();
    for (std::thread& th : pool)
        th.join();
    for (const std::exception_ptr& e : errors)
        if (e)
            std::rethrow_exception(e);
    mFirst.assign(
        std::make_move_iterator(sampled.begin()),
        std::make_move_iterator(sampled.begin() + static_cast<std::ptrdiff_t>(sea.cascades().size())));
    mSecond.assign(
        std::make_move_iterator(sampled.begin() + static_cast<std::ptrdiff_t>(sea.cascades().size())),
        std::make_move_iterator(sampled.end()));
}

glm::dvec3 FftSampledSea::sample(const Tile& tile, const glm::dvec2& xy, glm::dvec3* ddx,
                                 glm::dvec3* ddy) const {
    const int n = tile.n;
    const double perMetre = n / tile.size;
    // The grid coordinate of xy, wrapped to the tile in double first (the tile repeats with period L).
    const glm::dvec2 u = glm::dvec2(wrapPhase(xy.x, tile.size), wrapPhase(xy.y, tile.size)) * perMetre;
    const int a0 = static_cast<int>(std::floor(u.x)), b0 = static_cast<int>(std::floor(u.y));
    const glm::dvec2 f = u - glm::dvec2(a0, b0);
    auto wrap = [n](int i) { return ((i % n) + n) % n; };
    auto at = [&](int a, int b) { return glm::dvec3(tile.values[static_cast<size_t>(b) * n + a]); };
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
    // slopes hold the weights (theta's own gradient, ~6 / L_c rad/m, left out: they steer Newton's steps
    // only).
    glm::dvec3 d(0.0), gx(0.0), gy(0.0), tx, ty;
    for (size_t c = 0; c < mFirst.size(); ++c) {
        const glm::dvec2 w = mSea.mixWeights(static_cast<int>(c), xy);
        d += w.x * sample(mFirst[c], xy, ddx ? &tx : nullptr, &ty);
        if (ddx) {
            gx += w.x * tx;
            gy += w.x * ty;
        }
        if (!mSecond.empty()) {
            d += w.y * sample(mSecond[c], xy, ddx ? &tx : nullptr, &ty);
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
    return displacementAndSlopes(xy, nullptr, nullptr);
}

double FftSampledSea::heightAt(const glm::dvec2& xy) const {
    // SurfaceModel::heightAt's solve of F(x0) = x0 + d_xy(x0) - xy = 0 (Newton, step halving, |F| < 1e-9 m),
    // with the Jacobian I + grad d_xy from the interpolant's own slopes instead of central differences: one
    // evaluation per step instead of five (the same root; the Jacobian only steers the steps).
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
    return d.z;
}

void FftSampledSea::heightsAt(std::span<const glm::dvec2> points, std::span<double> heights) const {
    if (points.size() != heights.size())
        throw std::invalid_argument("FftSampledSea::heightsAt(): " + std::to_string(points.size()) +
                                    " points but " + std::to_string(heights.size()) + " heights");
    for (size_t i = 0; i < points.size(); ++i)
        heights[i] = heightAt(points[i]);
}

} // namespace pacifica::ocean
