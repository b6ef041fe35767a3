// FftOcean: validation, the Phillips and JONSWAP spectra, the random draw of h0(k) and the double-precision
// direct-sum reference (see the header for the model and its conventions).
#include "ocean/FftOcean.h"

#include "engine/Time.h"
#include "ocean/GerstnerWaves.h"
#include "ocean/OceanConstants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace pacifica::ocean {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Phillips' constant alpha = 0.0081 (Pierson & Moskowitz 1964; Phillips' saturation range
/// S(w) = alpha g^2 w^-5). Integrating over direction gives Tessendorf's eq. 40 with A = alpha / (2 pi):
/// the omnidirectional wavenumber spectrum of S(w) is alpha / 2 k^-3 (S(w) dw/dk with dw/dk = g / (2 w)),
/// and |k_hat . w_hat|^2 = cos^2 integrates to pi over the circle, so F(k) = alpha / (2 pi) k^-4 cos^2.
constexpr double PHILLIPS_ALPHA = 0.0081;
constexpr double JONSWAP_GAMMA = 3.3;

void require(bool ok, const std::string& message) {
    if (!ok)
        throw std::invalid_argument(message);
}

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

void validate(const FftDesc& d) {
    require(d.size >= 16 && d.size <= 1024 && (d.size & (d.size - 1)) == 0,
            "FftDesc.size must be a power of two in [16, 1024], got " + std::to_string(d.size));
    require(std::isfinite(d.tileSize) && d.tileSize > 0.0,
            "FftDesc.tileSize must be finite and > 0, got " + num(d.tileSize));
    require(std::isfinite(d.windSpeed) && d.windSpeed > 0.0,
            "FftDesc.windSpeed must be finite and > 0, got " + num(d.windSpeed));
    require(std::isfinite(d.windDirectionDeg),
            "FftDesc.windDirectionDeg must be finite, got " + num(d.windDirectionDeg));
    require(std::isfinite(d.fetch) && d.fetch > 0.0,
            "FftDesc.fetch must be finite and > 0, got " + num(d.fetch));
    require(d.spectrum == Spectrum::Phillips || d.spectrum == Spectrum::Jonswap,
            "FftDesc.spectrum must be Phillips or Jonswap, got " +
                std::to_string(static_cast<int>(d.spectrum)));
    require(std::isfinite(d.choppiness) && d.choppiness >= 0.0,
            "FftDesc.choppiness must be finite and >= 0, got " + num(d.choppiness));
    require(std::isfinite(d.amplitudeScale) && d.amplitudeScale >= 0.0,
            "FftDesc.amplitudeScale must be finite and >= 0, got " + num(d.amplitudeScale));
    require(std::isfinite(d.loopPeriod) && d.loopPeriod > 0.0,
            "FftDesc.loopPeriod must be finite and > 0, got " + num(d.loopPeriod));
    require(d.cascades >= 1 && d.cascades <= FFT_MAX_CASCADES, "FftDesc.cascades must be in [1, " +
                                                                   std::to_string(FFT_MAX_CASCADES) +
                                                                   "], got " + std::to_string(d.cascades));
    require(std::isfinite(d.cascadeRatio) && d.cascadeRatio >= 2.0,
            "FftDesc.cascadeRatio must be finite and >= 2, got " + num(d.cascadeRatio));
    require(d.detailSize >= 16 && d.detailSize <= 1024 && (d.detailSize & (d.detailSize - 1)) == 0,
            "FftDesc.detailSize must be a power of two in [16, 1024], got " + std::to_string(d.detailSize));
    require(!std::isnan(d.minWavenumber) && d.minWavenumber >= 0.0 && std::isfinite(d.minWavenumber),
            "FftDesc.minWavenumber must be finite and >= 0, got " + num(d.minWavenumber));
    require(!std::isnan(d.maxWavenumber) && d.maxWavenumber > d.minWavenumber,
            "FftDesc.maxWavenumber must be > minWavenumber, got " + num(d.maxWavenumber));
}

/// Unit vector the wind blows toward: compass angle (clockwise from north) to (east, north).
glm::dvec2 windVector(const FftDesc& d) {
    const double a = d.windDirectionDeg * std::numbers::pi / 180.0;
    return {std::sin(a), std::cos(a)};
}

/// Standard normal pairs by Box–Muller (Box & Muller 1958) on std::mt19937_64, whose output sequence the
/// standard fixes; std::normal_distribution's algorithm is not (libstdc++ and libc++ differ), so it would
/// make the sea depend on the standard library.
class NormalPairs {
public:
    explicit NormalPairs(uint64_t seed) : mRng(seed) {}
    std::complex<double> next() {
        const double u1 = 1.0 - uniform(); // (0, 1]: log(u1) finite
        const double u2 = uniform();
        const double r = std::sqrt(-2.0 * std::log(u1));
        return {r * std::cos(kTwoPi * u2), r * std::sin(kTwoPi * u2)};
    }

private:
    double uniform() { return static_cast<double>(mRng() >> 11) * 0x1.0p-53; } // [0, 1), 53 random bits
    std::mt19937_64 mRng;
};

/// e^{i 2 pi turns}, turns reduced to [-0.5, 0.5] first so cos/sin see small arguments.
std::complex<double> cisTurns(double turns) {
    const double r = turns - std::round(turns);
    return {std::cos(kTwoPi * r), std::sin(kTwoPi * r)};
}

/// e^{i k x} per axis at a point: the coordinate wrapped to the tile in double (fmod is exact), then
/// e^{i 2 pi n' x / L} from turns reduced mod 1 for lattice index i (n' = i - N/2), so x = 1e7 m loses
/// nothing; the 2D exponential of lattice point (i, m) is ex[i] * ey[m].
struct AxisPhases {
    std::vector<std::complex<double>> ex, ey;
};
AxisPhases axisPhases(const glm::dvec2& xy, double tile, int n) {
    const double u = wrapPhase(xy.x, tile) / tile, v = wrapPhase(xy.y, tile) / tile;
    AxisPhases p{std::vector<std::complex<double>>(static_cast<size_t>(n)),
                 std::vector<std::complex<double>>(static_cast<size_t>(n))};
    for (int i = 0; i < n; ++i) {
        p.ex[static_cast<size_t>(i)] = cisTurns((i - n / 2) * u);
        p.ey[static_cast<size_t>(i)] = cisTurns((i - n / 2) * v);
    }
    return p;
}

} // namespace

double jonswapFrequencySpectrum(double omega, double windSpeed, double fetch) {
    if (!(omega > 0.0))
        return 0.0;
    // Hasselmann et al. 1973 (JONSWAP) with its fetch laws for alpha and the peak frequency as usually
    // quoted for graphics (Horvath 2015, "Empirical directional wave spectra for computer graphics"):
    // alpha = 0.076 (U^2/(F g))^0.22, wp = 22 (g^2/(U F))^(1/3).
    const double g = GRAVITY;
    const double alpha = 0.076 * std::pow(windSpeed * windSpeed / (fetch * g), 0.22);
    const double wp = 22.0 * std::cbrt(g * g / (windSpeed * fetch));
    const double sigma = omega <= wp ? 0.07 : 0.09;
    const double dw = omega - wp;
    const double r = std::exp(-dw * dw / (2.0 * sigma * sigma * wp * wp));
    const double w4 = (wp / omega) * (wp / omega) * (wp / omega) * (wp / omega);
    return alpha * g * g / std::pow(omega, 5.0) * std::exp(-1.25 * w4) * std::pow(JONSWAP_GAMMA, r);
}

double directionalSpectrum(const FftDesc& desc, const glm::dvec2& kv) {
    const double k = glm::length(kv);
    if (!(k > 0.0))
        return 0.0;
    const double c = glm::dot(kv / k, windVector(desc)); // cos of the angle to the wind
    const double g = GRAVITY;
    if (desc.spectrum == Spectrum::Phillips) {
        // Tessendorf 2001 eq. 40 times the small-wave factor exp(-k^2 l^2) Tessendorf gives after it:
        //   F(k) = A exp(-1 / (k Lw)^2) / k^4 |k_hat . w_hat|^2 exp(-k^2 l^2),   Lw = U^2 / g,
        // A = alpha / (2 pi) from Phillips' alpha (see PHILLIPS_ALPHA). l = half a grid spacing L / (2 N):
        // waves near the grid's Nyquist wavenumber pi N / L are damped (by e^{-pi^2/4} = 0.085 there) instead
        // of aliasing. Waves travelling against the wind keep their cos^2 share, as in eq. 40.
        const double lw = desc.windSpeed * desc.windSpeed / g;
        const double l = 0.5 * desc.tileSize / desc.size;
        const double kl = k * lw;
        return PHILLIPS_ALPHA / kTwoPi * std::exp(-1.0 / (kl * kl)) / (k * k * k * k) * c * c *
               std::exp(-k * k * l * l);
    }
    // JONSWAP: the frequency spectrum S(w) (m^2 s) becomes the omnidirectional wavenumber spectrum
    // Phi(k) = S(w(k)) dw/dk (m^3) with deep water w = sqrt(g k), dw/dk = g / (2 w); the directional
    // spectrum over the wave-vector plane is F(k) = Phi(k) / k * D(theta) (d^2k = k dk dtheta), with the
    // "positive cosine squared" spreading D = (2 / pi) cos^2(theta) for |theta| < pi / 2, 0 otherwise
    // (Horvath 2015; integrates to 1: waves run with the wind only). Uses the unquantised w.
    if (c <= 0.0)
        return 0.0;
    const double w = std::sqrt(g * k);
    const double phi = jonswapFrequencySpectrum(w, desc.windSpeed, desc.fetch) * g / (2.0 * w);
    return phi / k * (2.0 / std::numbers::pi) * c * c;
}

struct FftOcean::Sums {
    std::complex<double> h, dx, dy;     // height, D_x, D_y (eq. 29, without lambda)
    std::complex<double> hx, hy;        // dh/dx, dh/dy
    std::complex<double> dxx, dyy, dxy; // dD_x/dx, dD_y/dy, dD_x/dy = dD_y/dx
};

FftOcean::FftOcean(const FftDesc& desc) : mDesc(desc) {
    validate(desc);
    const int n = desc.size;
    const size_t count = static_cast<size_t>(n) * n;
    mH0.assign(count, {0.0, 0.0});
    mOmega.assign(count, 0.0);
    mQ.assign(count, 0u);
    const double dk = kTwoPi / desc.tileSize;
    const double w0 = kTwoPi / desc.loopPeriod;
    NormalPairs normal(desc.seed);
    for (int m = 0; m < n; ++m) {
        for (int i = 0; i < n; ++i) {
            // One draw per lattice point in a fixed order, also where the amplitude is 0, so the sea of a
            // seed does not depend on the spectrum's support.
            const std::complex<double> xi = normal.next();
            const size_t idx = static_cast<size_t>(m) * n + i;
            const glm::dvec2 k(dk * (i - n / 2), dk * (m - n / 2));
            const double kl = glm::length(k);
            if (i == 0 || m == 0 || kl == 0.0)
                continue; // Nyquist row/column and k = 0 stay 0 (see the header)
            if (kl < desc.minWavenumber || kl >= desc.maxWavenumber)
                continue; // another cascade's band (FftCascades)
            // Dispersion w = sqrt(g k) (deep water) quantised to the loop (Tessendorf: looping in time).
            const double q = std::max(1.0, std::round(std::sqrt(GRAVITY * kl) / w0));
            mQ[idx] = static_cast<uint32_t>(q);
            mOmega[idx] = q * w0;
            mMaxQ = std::max(mMaxQ, mQ[idx]);
            // Eq. 25 with P_h = F(k) dk^2 / 2: a lattice point stands for the area dk^2 of wave-vector space,
            // and each htilde(k) receives both h0(k) and conj(h0(-k)) (eq. 26), so E|htilde(k)|^2 =
            // (F(k) + F(-k)) dk^2 / 2 and the tile variance sum_k E|htilde|^2 = sum_k F(k) dk^2 = Var h.
            const double ph = directionalSpectrum(desc, k) * dk * dk / 2.0;
            mH0[idx] = xi * std::sqrt(ph / 2.0) * desc.amplitudeScale;
        }
    }
    // Parseval over one tile at t = 0: mean of h^2 = sum_k |htilde(k, 0)|^2, htilde(k, 0) = h0(k) +
    // conj(h0(-k)).
    double var = 0.0;
    for (int m = 1; m < n; ++m) {
        for (int i = 1; i < n; ++i) {
            const std::complex<double> a = mH0[static_cast<size_t>(m) * n + i];
            const std::complex<double> b = std::conj(mH0[static_cast<size_t>(n - m) * n + (n - i)]);
            var += std::norm(a + b);
        }
    }
    mHs = 4.0 * std::sqrt(var);
}

FftOcean::Sums FftOcean::sumAt(const glm::dvec2& xy, double t, bool derivatives) const {
    const int n = mDesc.size;
    const double tile = mDesc.tileSize;
    const auto [ex, ey] = axisPhases(xy, tile, n); // space: e^{i k x} per axis
    // Time: e^{i w t} = e^{i 2 pi q s}, s = wrap(t, T) / T (Tessendorf: looping in time); one table entry per
    // q.
    const double s = wrapPhase(t, mDesc.loopPeriod) / mDesc.loopPeriod;
    std::vector<std::complex<double>> et(static_cast<size_t>(mMaxQ) + 1);
    for (uint32_t q = 0; q <= mMaxQ; ++q)
        et[q] = cisTurns(q * s);

    const double dk = kTwoPi / tile;
    const std::complex<double> I(0.0, 1.0);
    Sums r{};
    for (int m = 1; m < n; ++m) {
        for (int i = 1; i < n; ++i) {
            const size_t idx = static_cast<size_t>(m) * n + i;
            const size_t neg = static_cast<size_t>(n - m) * n + (n - i); // lattice index of -k
            const uint32_t q = mQ[idx];
            if (q == 0)
                continue; // k = 0
            const std::complex<double> e = et[q];
            // Eq. 26: htilde = h0(k) e^{i w t} + conj(h0(-k)) e^{-i w t}; w(-k) = w(k).
            const std::complex<double> ht = mH0[idx] * e + std::conj(mH0[neg]) * std::conj(e);
            const std::complex<double> c = ht * (ex[static_cast<size_t>(i)] * ey[static_cast<size_t>(m)]);
            const double kx = dk * (i - n / 2), ky = dk * (m - n / 2);
            const double kl = std::sqrt(kx * kx + ky * ky);
            const double ux = kx / kl, uy = ky / kl;
            r.h += c;
            const std::complex<double> ic = I * c;
            r.dx -= ux * ic; // eq. 29: -i k_hat htilde
            r.dy -= uy * ic;
            if (derivatives) {
                r.hx += kx * ic; // d/dx e^{i k.x} = i k_x e^{i k.x}
                r.hy += ky * ic;
                r.dxx += kx * ux * c; // i k_x (-i k_x / k) = k_x^2 / k
                r.dyy += ky * uy * c;
                r.dxy += kx * uy * c;
            }
        }
    }
    return r;
}

glm::dvec3 FftOcean::displacementAt(const glm::dvec2& xy, double t) const {
    const Sums s = sumAt(xy, t, false);
    const double l = mDesc.choppiness;
    return {l * s.dx.real(), l * s.dy.real(), s.h.real()};
}

std::complex<double> FftOcean::complexHeightAt(const glm::dvec2& xy, double t) const {
    return sumAt(xy, t, false).h;
}

glm::dvec3 FftOcean::normalAt(const glm::dvec2& xy, double t) const {
    const Sums s = sumAt(xy, t, true);
    const double l = mDesc.choppiness;
    // dP/dx = (1 + l Dxx, l Dxy, hx), dP/dy = (l Dxy, 1 + l Dyy, hy) for P = (x + l Dx, y + l Dy, h).
    const glm::dvec3 px(1.0 + l * s.dxx.real(), l * s.dxy.real(), s.hx.real());
    const glm::dvec3 py(l * s.dxy.real(), 1.0 + l * s.dyy.real(), s.hy.real());
    return glm::normalize(glm::cross(px, py));
}

double FftOcean::jacobianAt(const glm::dvec2& xy, double t) const {
    const Sums s = sumAt(xy, t, true);
    const double l = mDesc.choppiness;
    const double jxy = l * s.dxy.real();
    return (1.0 + l * s.dxx.real()) * (1.0 + l * s.dyy.real()) - jxy * jxy;
}

FftOcean::Derivatives FftOcean::derivativesAt(const glm::dvec2& xy, double t) const {
    const Sums s = sumAt(xy, t, true);
    const double l = mDesc.choppiness;
    return {s.hx.real(), s.hy.real(), l * s.dxx.real(), l * s.dyy.real(), l * s.dxy.real()};
}

double FftOcean::significantWaveHeight() const {
    return mHs;
}

double FftOcean::foamHeightAt(const glm::dvec2& xy, double t) const {
    return foamHeightsAt(xy, {t})[0];
}

std::vector<double> FftOcean::foamHeightsAt(const glm::dvec2& xy, const std::vector<double>& times) const {
    std::vector<double> out;
    out.reserve(times.size());
    if (!mDesc.foamMemory) {
        for (double t : times)
            out.push_back(displacementAt(xy, t).z);
        return out;
    }
    for (const CrestMemory& m : crestMemoriesAt(xy, times))
        out.push_back(std::max(m.height, m.up));
    return out;
}

std::vector<FftOcean::CrestMemory> FftOcean::crestMemoriesAt(const glm::dvec2& xy,
                                                             const std::vector<double>& times) const {
    if (!std::isfinite(xy.x) || !std::isfinite(xy.y))
        throw std::invalid_argument("FftOcean::foamHeightAt(): point must be finite");
    // h(x, t) = Re sum_k htilde(k, t) e^{i k.x} = Re sum_q (a_q e^{i 2 pi q s} + b_q e^{-i 2 pi q s}),
    // s = wrap(t, T) / T, with a_q = sum_{q(k) = q} h0(k) e^{i k.x} and b_q the same of conj(h0(-k)) (eq.
    // 26): one O(N^2) pass per point, then O(q_max) per time (the same terms sumAt() adds, grouped by q).
    const int n = mDesc.size;
    const auto [ex, ey] = axisPhases(xy, mDesc.tileSize, n);
    std::vector<std::complex<double>> a(static_cast<size_t>(mMaxQ) + 1), b(static_cast<size_t>(mMaxQ) + 1);
    for (int m = 1; m < n; ++m) {
        for (int i = 1; i < n; ++i) {
            const size_t idx = static_cast<size_t>(m) * n + i;
            const uint32_t q = mQ[idx];
            if (q == 0)
                continue;
            const size_t neg = static_cast<size_t>(n - m) * n + (n - i);
            const std::complex<double> e = ex[static_cast<size_t>(i)] * ey[static_cast<size_t>(m)];
            a[q] += mH0[idx] * e;
            b[q] += std::conj(mH0[neg]) * e;
        }
    }
    // e^{i 2 pi q s} by powers of e^{i 2 pi s} (error ~q_max * 1e-16, far below the GPU's float FFT).
    auto heightAt = [&](double time) {
        const std::complex<double> step = cisTurns(wrapPhase(time, mDesc.loopPeriod) / mDesc.loopPeriod);
        std::complex<double> c = 1.0;
        double h = 0.0;
        for (uint32_t q = 1; q <= mMaxQ; ++q) {
            c *= step;
            h += (a[q] * c + b[q] * std::conj(c)).real();
        }
        return h;
    };
    std::vector<CrestMemory> out;
    out.reserve(times.size());
    for (double t : times) {
        CrestMemory m;
        m.height = heightAt(t);
        if (mDesc.foamMemory) {
            const int64_t j = foamStepIndex(t);
            double up = 0.0, down = 0.0;
            for (int k = 0; k < FOAM_MEMORY_WINDOW; ++k) {
                const double w = std::exp(-k * FOAM_MEMORY_STEP / FOAM_DECAY_TIME);
                const double h = heightAt(foamStepTime(j - k));
                up = std::max(up, w * std::max(h, 0.0));
                down = std::max(down, w * std::max(-h, 0.0));
            }
            const double decay = std::exp(-(t - foamStepTime(j)) / FOAM_DECAY_TIME);
            m.up = decay * up;
            m.down = decay * down;
        }
        out.push_back(m);
    }
    return out;
}

glm::dvec3 FftOcean::displacementSeenFrom(const glm::dvec2& xy, double t, const glm::dvec2&) const {
    // Same lookup as fft.glsl's exact path: grid point i sits at x = i L / N (period L), bilinear between.
    const double l = mDesc.tileSize, n = mDesc.size, dx = l / n;
    const double px = wrapPhase(xy.x, l) / dx, py = wrapPhase(xy.y, l) / dx;
    const double fx = std::floor(px), fy = std::floor(py), ax = px - fx, ay = py - fy;
    auto at = [&](double i, double j) { return displacementAt({i * dx, j * dx}, t); };
    const glm::dvec3 bottom = glm::mix(at(fx, fy), at(fx + 1.0, fy), ax);
    const glm::dvec3 top = glm::mix(at(fx, fy + 1.0), at(fx + 1.0, fy + 1.0), ax);
    return glm::mix(bottom, top, ay);
}

// FftCascades ---------------------------------------------------------------------------------------------

FftDesc FftCascades::cascadeDesc(const FftDesc& desc, int c, int draw) {
    FftDesc d = desc;
    d.cascades = 1;
    d.tileSize = desc.tileSize / std::pow(desc.cascadeRatio, c);
    d.size = c == 0 ? desc.size : desc.detailSize;
    d.seed = desc.seed + static_cast<uint32_t>(c + 64 * draw);
    // Band edges: a wave of wavelength lambda goes to the coarsest cascade whose grid spacing L_c / N_c is
    // at most lambda / FFT_CASCADE_BAND_TEXELS, i.e. k < 2 pi N_c / (FFT_CASCADE_BAND_TEXELS L_c).
    auto edge = [&](int coarse) { // top of cascade `coarse`'s band
        const double tile = desc.tileSize / std::pow(desc.cascadeRatio, coarse);
        const int n = coarse == 0 ? desc.size : desc.detailSize;
        return kTwoPi * n / (FFT_CASCADE_BAND_TEXELS * tile);
    };
    d.minWavenumber = c == 0 ? desc.minWavenumber : edge(c - 1);
    d.maxWavenumber = c + 1 < desc.cascades ? edge(c) : desc.maxWavenumber;
    return d;
}

FftCascades::FftCascades(const FftDesc& desc) : mDesc(desc) {
    validate(desc);
    double var = 0.0;
    for (int c = 0; c < desc.cascades; ++c) {
        mCascades.push_back(std::make_shared<const FftOcean>(cascadeDesc(desc, c)));
        if (desc.aperiodic)
            mSecond.push_back(std::make_shared<const FftOcean>(cascadeDesc(desc, c, 1)));
        // cos^2 + sin^2 = 1: the mix has the variance of the draws (taken as A's).
        const double hs = mCascades.back()->significantWaveHeight();
        var += hs * hs / 16.0;
    }
    mHs = 4.0 * std::sqrt(var);
    for (size_t c = 0; c < mCascades.size(); ++c)
        for (int j = 0; j < FFT_MIX_TERMS; ++j)
            mMixTerms.push_back(aperiodicMixTerm(mCascades[c]->desc().tileSize, static_cast<int>(c), j));
}

glm::dvec3 FftCascades::mixTerm(int c, int j) const {
    return aperiodicMixTerm(mCascades.at(static_cast<size_t>(c))->desc().tileSize, c, j);
}

glm::dvec2 FftCascades::mixWeights(int c, const glm::dvec2& xy) const {
    if (!mDesc.aperiodic)
        return {1.0, 0.0};
    // aperiodicMixWeights(L_c, c, xy) with the terms made once (the same sums, so the same bits).
    const glm::dvec3* m = &mMixTerms.at(static_cast<size_t>(c) * FFT_MIX_TERMS);
    double theta = 0.0;
    for (int j = 0; j < FFT_MIX_TERMS; ++j)
        theta += std::sin(m[j].x * xy.x + m[j].y * xy.y + m[j].z);
    theta *= FFT_MIX_AMPLITUDE;
    return {std::cos(theta), std::sin(theta)};
}

glm::dvec3 FftCascades::displacementAt(const glm::dvec2& xy, double t) const {
    glm::dvec3 d(0.0);
    for (size_t c = 0; c < mCascades.size(); ++c) {
        const glm::dvec2 w = mixWeights(static_cast<int>(c), xy);
        d += w.x * mCascades[c]->displacementAt(xy, t);
        if (!mSecond.empty())
            d += w.y * mSecond[c]->displacementAt(xy, t);
    }
    return d;
}

double FftCascades::displacementFadeEnd(int c) const {
    const FftDesc& d = mCascades.at(static_cast<size_t>(c))->desc();
    // The band's shortest wave: 2 pi / its top wavenumber, or the grid's Nyquist wavelength 2 L / N.
    const double shortest = std::max(kTwoPi / d.maxWavenumber, 2.0 * d.tileSize / d.size);
    return GerstnerWaves::DISPLACEMENT_FADE_WAVELENGTHS * shortest;
}

glm::dvec3 FftCascades::displacementSeenFrom(const glm::dvec2& xy, double t,
                                             const glm::dvec2& cameraXY) const {
    glm::dvec3 d(0.0);
    const double r = glm::length(xy - cameraXY);
    for (size_t c = 0; c < mCascades.size(); ++c) {
        const double f = GerstnerWaves::fade(r, displacementFadeEnd(static_cast<int>(c)));
        if (f == 0.0)
            continue;
        const glm::dvec2 w = f * mixWeights(static_cast<int>(c), xy);
        d += w.x * mCascades[c]->displacementSeenFrom(xy, t, cameraXY);
        if (!mSecond.empty())
            d += w.y * mSecond[c]->displacementSeenFrom(xy, t, cameraXY);
    }
    return d;
}

FftOcean::Derivatives FftCascades::derivativesAt(const glm::dvec2& xy, double t) const {
    FftOcean::Derivatives s;
    auto add = [&](const FftOcean& sea, double w) {
        const FftOcean::Derivatives d = sea.derivativesAt(xy, t);
        s.hx += w * d.hx;
        s.hy += w * d.hy;
        s.dxx += w * d.dxx;
        s.dyy += w * d.dyy;
        s.dxy += w * d.dxy;
    };
    for (size_t c = 0; c < mCascades.size(); ++c) {
        const glm::dvec2 w = mixWeights(static_cast<int>(c), xy);
        add(*mCascades[c], w.x);
        if (!mSecond.empty())
            add(*mSecond[c], w.y);
    }
    return s;
}

glm::dvec3 FftCascades::normalAt(const glm::dvec2& xy, double t) const {
    const FftOcean::Derivatives s = derivativesAt(xy, t);
    const glm::dvec3 px(1.0 + s.dxx, s.dxy, s.hx), py(s.dxy, 1.0 + s.dyy, s.hy); // as FftOcean::normalAt
    return glm::normalize(glm::cross(px, py));
}

double FftCascades::jacobianAt(const glm::dvec2& xy, double t) const {
    const FftOcean::Derivatives s = derivativesAt(xy, t);
    return (1.0 + s.dxx) * (1.0 + s.dyy) - s.dxy * s.dxy;
}

double FftCascades::foamHeightAt(const glm::dvec2& xy, double t) const {
    return foamHeightsAt(xy, {t})[0];
}

std::vector<double> FftCascades::foamHeightsAt(const glm::dvec2& xy, const std::vector<double>& times) const {
    std::vector<double> out;
    if (mSecond.empty()) {
        out = mCascades.front()->foamHeightsAt(xy, times);
    } else {
        const glm::dvec2 w = mixWeights(0, xy);
        const auto a = mCascades.front()->crestMemoriesAt(xy, times);
        const auto b = mSecond.front()->crestMemoriesAt(xy, times);
        auto remembered = [](const FftOcean::CrestMemory& m, double weight) {
            return weight >= 0.0 ? weight * m.up : -weight * m.down;
        };
        out.reserve(times.size());
        for (size_t i = 0; i < times.size(); ++i) {
            const double h = w.x * a[i].height + w.y * b[i].height;
            out.push_back(mDesc.foamMemory ? std::max(h, remembered(a[i], w.x) + remembered(b[i], w.y)) : h);
        }
    }
    // The shorter waves riding on the crests (cascade 1's height, mixed): they break the long crests'
    // smooth caps into ragged patches of many sizes. Heights only (crestMemoriesAt's one O(N^2) pass per
    // point), no memory of their own.
    if (mCascades.size() > 1) {
        const glm::dvec2 w = mixWeights(1, xy);
        const auto a = mCascades[1]->crestMemoriesAt(xy, times);
        for (size_t i = 0; i < times.size(); ++i)
            out[i] += w.x * a[i].height;
        if (!mSecond.empty()) {
            const auto b = mSecond[1]->crestMemoriesAt(xy, times);
            for (size_t i = 0; i < times.size(); ++i)
                out[i] += w.y * b[i].height;
        }
    }
    return out;
}

} // namespace pacifica::ocean
