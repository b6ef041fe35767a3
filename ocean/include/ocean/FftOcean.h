// FftOcean: Tessendorf's statistical FFT ocean ("Simulating Ocean Water", 2001) — a spectrum of random
// Fourier amplitudes h0(k) evolved with the dispersion relation and transformed to heights, slopes and
// horizontal ("choppy": the water-rendering notes' "direct displacement") displacements by inverse FFT on the
// GPU.
//
//   h(x, t) = sum_k htilde(k, t) e^{i k.x}                                                   (eq. 26)
//   htilde(k, t) = h0(k) e^{i w t} + conj(h0(-k)) e^{-i w t}
//   D(x, t) = sum_k -i (k / |k|) htilde(k, t) e^{i k.x}                                       (eq. 29)
//   P = (x + lambda D_x, y + lambda D_y, h)                                                   (eq. 30)
//   h0(k) = (xi_r + i xi_i) sqrt(P(k) / 2)   (eq. 25) with the Phillips (eq. 40) or JONSWAP spectrum
//
// The wave vectors lie on the lattice k = 2 pi (n, m) / L (n, m in [-N/2, N/2)), so the field tiles with
// period L. This class is the double-precision CPU reference: it evaluates the same spectral components by
// direct sum at any point (O(N^2) per point) — the yardstick for the GPU FFT's accuracy.
//
// STEP BY STEP
//   1. FftDesc d; d.size = 256; d.tileSize = 500.0; d.windSpeed = 12.0; d.fetch = 200e3;   // or defaults
//   2. auto sea = std::make_shared<const FftOcean>(d);   // validates, draws h0(k) (deterministic per seed)
//   3. CPU queries: sea->displacementAt(xy, t), normalAt, jacobianAt, heightAt (any t: time loops with T)
//   4. GPU: FftGpu gpu(sea) (ocean/src/gpu/FftGpu.h); per frame gpu.update(t, camera); gpu.bind(program, ...)
// The sea an OceanDesc asks for is FftCascades (below): several such tiles, each its band of the spectrum
// and two draws mixed so that no tile repeats; FftOcean is one of its tiles (and the single-tile reference).
//
// Conventions (shared with the GPU, ocean/shaders/fft_*.comp):
//   - Lattice index (n, m) in [0, N)^2 stands for the wave vector k = 2 pi (n - N/2, m - N/2) / L;
//     x = east, y = north (ENU); the wind direction is a compass angle, so w_hat = (sin a, cos a).
//   - Nyquist row and column (n = 0 or m = 0, wave number -N/2) carry h0 = 0: their partner -k is not on
//     the lattice, so with them the sum would not be real between grid points, and i k (slopes, eq. 29) is
//     ambiguous there. With them zeroed, htilde(-k) = conj(htilde(k)) holds for every lattice k, the field
//     is real everywhere and the CPU sum and the GPU FFT hold exactly the same components.
//   - Time loops with period T = loopPeriod (Tessendorf 2001, "looping in time"): w(k) = q(k) w0 with
//     w0 = 2 pi / T and the integer q(k) = max(1, round(sqrt(g |k|) / w0)). So e^{i w t} depends only on
//     wrap(t, T), which is taken in double before anything else; the phase is q * wrap(t, T) / T turns,
//     reduced mod 1.
//   - P(k) in eq. 25 is F(k) dk^2 / 2 with F = directionalSpectrum() and dk = 2 pi / L, so that the tile's
//     expected height variance is sum_k F(k) dk^2 ~ integral F d^2k (derivation in FftOcean.cpp).
//   - amplitudeScale multiplies every h0 (so the variance by amplitudeScale^2).
#pragma once

#include "ocean/SurfaceModel.h"

#include <complex>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace pacifica::ocean {

enum class Spectrum { Phillips, Jonswap };

struct FftDesc {
    int size = 256;                 ///< N: grid points per side (power of two, 16..1024)
    double tileSize = 2000.0;       ///< L: metres per tile (the largest cascade's)
    double windSpeed = 12.0;        ///< U10, m/s
    double windDirectionDeg = 60.0; ///< compass direction the wind blows toward
    double fetch = 200000.0;        ///< metres (JONSWAP)
    Spectrum spectrum = Spectrum::Jonswap;
    double choppiness = 1.0;     ///< lambda (eq. 30); the surface must not fold at the chosen value
    double amplitudeScale = 1.0; ///< multiplies the spectrum's amplitude (a look knob)
    uint32_t seed = 3;
    double loopPeriod =
        200.0; ///< T: seconds after which the animation repeats exactly (Tessendorf: looping in time)
    /// Living whitecaps: the foam thresholds apply to the remembered crests (foamHeightAt), so foam forms on
    /// a crest, stays where the crest passed and decays over seconds. false: to the current height (a knob
    /// of `pacifica bench accuracy`).
    bool foamMemory = true;

    /// Cascades (FftCascades; the nested grids of Bruneton, Neyret & Holzschuch 2010, sec. 5): the sea is
    /// the sum of `cascades` tiles of tileSize / cascadeRatio^c (c < cascades), each holding its own band of
    /// the spectrum, so a camera sees waves from the largest tile's down to the finest tile's Nyquist and no
    /// single period: the tile sizes are incommensurate (cascadeRatio is irrational-looking, 7.37), and a
    /// finer tile starts where the coarser one's grid is too coarse for its waves (FFT_CASCADE_BAND_TEXELS).
    /// 1: one tile of tileSize (Tessendorf's FFT as it was). FftOcean itself is always one tile and ignores
    /// these three fields.
    int cascades = 4;
    double cascadeRatio = 7.37;
    int detailSize = 128; ///< N of cascades c >= 1 (power of two, 16..1024): shorter waves, fewer needed
    /// Each cascade is two independent draws A, B of its band mixed as cos(theta) A + sin(theta) B by a
    /// slowly turning angle theta(x) that never repeats (FFT_MIX_*, OceanConstants.h): same spectrum and
    /// variance everywhere, no period (a tile's lattice shift correlates below 0.03). Twice the FFT work.
    bool aperiodic = true;

    /// The band of wavenumbers |k| this tile holds, [minWavenumber, maxWavenumber) rad/m: lattice points
    /// outside it carry h0 = 0. FftCascades sets them per cascade; 0 and infinity: the whole lattice.
    double minWavenumber = 0.0;
    double maxWavenumber = std::numeric_limits<double>::infinity();
};

/// Directional wavenumber spectrum F(k) of `desc` (without amplitudeScale): the height variance per unit
/// area of wave-vector space, m^4, so that Var h = integral F d^2k. Phillips: Tessendorf eq. 40 with the
/// small-wave factor exp(-k^2 l^2); JONSWAP: S(w) converted through dw/dk with cos^2 spreading (see
/// FftOcean.cpp for the formulas and sources). F(0) = 0.
double directionalSpectrum(const FftDesc& desc, const glm::dvec2& k);

/// JONSWAP frequency spectrum S(w), m^2 s (Hasselmann et al. 1973): alpha g^2 w^-5 exp(-5/4 (wp/w)^4)
/// gamma^r with alpha = 0.076 (U^2 / (F g))^0.22, wp = 22 (g^2 / (U F))^(1/3), gamma = 3.3,
/// sigma = 0.07 (w <= wp) / 0.09. 0 for w <= 0.
double jonswapFrequencySpectrum(double omega, double windSpeed, double fetch);

class FftOcean final : public SurfaceModel {
public:
    /// Validates (std::invalid_argument naming the field) and draws h0(k).
    explicit FftOcean(const FftDesc& desc = {});

    SurfaceKind kind() const override { return SurfaceKind::Fft; }
    /// Direct sum over all N^2 components at the point: O(N^2) — about 1 ms for N = 256 on one core (2N +
    /// q_max sin/cos, then N^2 complex multiply-adds) — for tests and sparse CPU queries; the GPU evaluates
    /// the whole tile by FFT. Every query throws std::invalid_argument for a non-finite point or time.
    glm::dvec3 displacementAt(const glm::dvec2& xy, double t) const override;
    /// What the GPU renders: the displacement maps hold the field at the N x N grid points x = (i, j) L / N,
    /// sampled bilinearly; this evaluates the direct sum at the 4 surrounding grid points and interpolates
    /// the same way (4 direct sums: O(4 N^2)). displacementAt() is the continuous reference.
    glm::dvec3 displacementSeenFrom(const glm::dvec2& xy, double t,
                                    const glm::dvec2& cameraXY) const override;
    /// Normal of the displaced surface: normalize(dP/dx x dP/dy) (eq. 30), O(N^2). It points down where the
    /// surface has folded (jacobianAt < 0).
    glm::dvec3 normalAt(const glm::dvec2& xy, double t) const override;
    /// (1 + l Dxx)(1 + l Dyy) - (l Dxy)^2 (Tessendorf §4.4), O(N^2).
    double jacobianAt(const glm::dvec2& xy, double t) const override;
    /// Foam height input (the GPU's modelFoamInputs().x, fft.glsl). With foamMemory: the living whitecaps'
    /// remembered crest height at grid point xy,
    ///   max(h(t), e^(-(t - t_j) / tau) M_j),  M_j = max_{k < W} e^(-k s / tau) max(h(t_{j-k}), 0),
    /// t_j = j s the last lattice time <= t (s = FOAM_MEMORY_STEP, W = FOAM_MEMORY_WINDOW, tau =
    /// FOAM_DECAY_TIME; OceanConstants.h): a crest leaves its height behind where it passed (at the grid
    /// point, which the choppy displacement carries with the water, so the foam rides the orbital motion) and
    /// the memory decays with Callaghan et al.'s e-folding time. Without: h(t). O(N^2 + W q_max): the
    /// height's time series at a point is a trigonometric polynomial in q w0 t (FftGpu samples it by FFT).
    double foamHeightAt(const glm::dvec2& xy, double t) const override;
    /// The same at several times: one O(N^2) pass for the point, then O(W q_max) per time.
    std::vector<double> foamHeightsAt(const glm::dvec2& xy, const std::vector<double>& times) const override;
    /// What foamHeightsAt() is made of, per time: the height h(t) and the decayed memories of the crests of
    /// +h (up) and of -h (down), e^(-(t - t_j) / tau) M_j as above for h and for -h (0 without foamMemory).
    /// A mix of draws (FftCascades) remembers the crests of -h where it takes a draw with a negative weight.
    struct CrestMemory {
        double height = 0, up = 0, down = 0;
    };
    std::vector<CrestMemory> crestMemoriesAt(const glm::dvec2& xy, const std::vector<double>& times) const;

    /// 4 * RMS of h over one tile at t = 0, from Parseval: 4 sqrt(sum_k |htilde(k, 0)|^2) — the sea actually
    /// realised (random draws, lattice truncation), not the spectrum's expectation.
    double significantWaveHeight() const override;

    /// The first derivatives of the displacement at grid point xy (choppiness applied): dh/dx, dh/dy and
    /// d(lambda D_x)/dx, d(lambda D_y)/dy, d(lambda D_x)/dy (= d(lambda D_y)/dx), O(N^2). A sum of cascades
    /// (FftCascades) adds them to form its normal and Jacobian.
    struct Derivatives {
        double hx = 0, hy = 0, dxx = 0, dyy = 0, dxy = 0;
    };
    Derivatives derivativesAt(const glm::dvec2& xy, double t) const;

    /// Test hook: the direct height sum sum_k htilde(k, t) e^{i k.x} before taking its real part. Its
    /// imaginary part measures the Hermitian symmetry of the realised spectrum (0 up to rounding).
    std::complex<double> complexHeightAt(const glm::dvec2& xy, double t) const;

    const FftDesc& desc() const { return mDesc; }
    /// h0(k) for lattice index (n, m), n, m in [0, N): row-major, n = column. Index (i - N/2) is the wave
    /// number.
    const std::vector<std::complex<double>>& h0() const { return mH0; }
    /// w(k) for the same lattice (quantised: integer multiples of 2 pi / loopPeriod; 0 at k = 0).
    const std::vector<double>& omega() const { return mOmega; }
    /// The integer q(k) = w(k) / w0 for the same lattice (0 at k = 0), as the GPU receives it.
    const std::vector<uint32_t>& omegaMultiple() const { return mQ; }

private:
    struct Sums; // complex field sums at one point (FftOcean.cpp)
    Sums sumAt(const glm::dvec2& xy, double t, bool derivatives) const;

    FftDesc mDesc;
    std::vector<std::complex<double>> mH0;
    std::vector<double> mOmega;
    std::vector<uint32_t> mQ;
    uint32_t mMaxQ = 0;
    double mHs = 0.0;
};

/// The FFT sea as FftDesc::cascades tiles (see there): cascade c has tile L_c = tileSize / cascadeRatio^c,
/// N = size (c = 0) or detailSize, seed + c, and the band [k_c, k_{c+1}) with k_0 = 0, the finest cascade's
/// top open, and k_c (c >= 1) the wavenumber whose wavelength spans FFT_CASCADE_BAND_TEXELS grid spacings of
/// cascade c - 1: each wave lives in the coarsest tile that samples it well enough. The cascades are
/// independent draws, so the fields add: displacement, heights and slopes are sums; the normal and the
/// Jacobian come from the summed derivatives (FftOcean::derivativesAt).
/// displacementSeenFrom() fades each cascade with the distance from the camera (displacementFadeEnd), as
/// fft.glsl does; displacementAt() is the unfaded surface.
/// With FftDesc::aperiodic each cascade is w_A A + w_B B, (w_A, w_B) = (cos theta_c(x), sin theta_c(x))
/// (mixWeights), A and B two draws (seeds seed + c and seed + 64 + c). The derivatives are w_A dA + w_B dB:
/// theta's own gradient (RMS 6.4 / L_c rad/m) is left out, a few percent of the slopes, so the normal is the
/// one the GPU lights.
/// The living whitecaps follow the largest cascade (its crests are the ones that break) with the next one's
/// waves riding on them: foamHeightAt is max(h, w_A M_A + w_B M_B) of cascade 0, with h = w_A h_A + w_B h_B
/// and M the draw's decayed memory of the crests of +h for a positive weight, of -h for a negative one
/// (FftOcean::crestMemoriesAt; |w| multiplies), plus cascade 1's mixed height (no memory of its own).
class FftCascades final : public SurfaceModel {
public:
    /// Validates `desc` (std::invalid_argument naming the field) and draws every cascade.
    explicit FftCascades(const FftDesc& desc = {});

    SurfaceKind kind() const override { return SurfaceKind::Fft; }
    glm::dvec3 displacementAt(const glm::dvec2& xy, double t) const override;
    glm::dvec3 displacementSeenFrom(const glm::dvec2& xy, double t,
                                    const glm::dvec2& cameraXY) const override;
    glm::dvec3 normalAt(const glm::dvec2& xy, double t) const override;
    double jacobianAt(const glm::dvec2& xy, double t) const override;
    double foamHeightAt(const glm::dvec2& xy, double t) const override;
    std::vector<double> foamHeightsAt(const glm::dvec2& xy, const std::vector<double>& times) const override;
    /// 4 sqrt(sum of the cascades' height variances).
    double significantWaveHeight() const override { return mHs; }
    /// The summed (mixed) first derivatives at grid point xy, as FftOcean::derivativesAt.
    FftOcean::Derivatives derivativesAt(const glm::dvec2& xy, double t) const;

    const FftDesc& desc() const { return mDesc; }
    /// Draw A of every cascade, in order.
    const std::vector<std::shared_ptr<const FftOcean>>& cascades() const { return mCascades; }
    /// Draw B of every cascade (empty without FftDesc::aperiodic).
    const std::vector<std::shared_ptr<const FftOcean>>& secondDraws() const { return mSecond; }
    /// The FftDesc of cascade c of `desc` (tile, N, seed, band) — what FftCascades builds; draw 1 is B.
    static FftDesc cascadeDesc(const FftDesc& desc, int c, int draw = 0);
    /// Term j of cascade c's mix angle: theta_c(x) = FFT_MIX_AMPLITUDE sum_j sin(k.x + phase), as
    /// (k_x, k_y, phase), k in rad/m, phase in [0, 2 pi).
    glm::dvec3 mixTerm(int c, int j) const;
    /// (cos theta_c(xy), sin theta_c(xy)); (1, 0) without FftDesc::aperiodic. theta is summed in double.
    glm::dvec2 mixWeights(int c, const glm::dvec2& xy) const;
    /// Distance from the camera beyond which cascade c no longer displaces the grid (its waves still light
    /// it): GerstnerWaves::DISPLACEMENT_FADE_WAVELENGTHS times the shortest wavelength of its band, the fade
    /// f(r, R) of GerstnerWaves::fade (1 within R / 2). The radial grid cannot carry a wave farther (its
    /// spacing grows with the distance), and a displaced vertex would alias it: in a slow pan the far sea
    /// flickered 1.1 % a frame from 20 m with the FFT's displacement unfaded, 0.56 % without any.
    double displacementFadeEnd(int c) const;

private:
    FftDesc mDesc;
    std::vector<std::shared_ptr<const FftOcean>> mCascades, mSecond;
    std::vector<glm::dvec3> mMixTerms; // mixTerm(c, j) at [c * FFT_MIX_TERMS + j] (the weights' every call)
    double mHs = 0.0;
};

} // namespace pacifica::ocean
