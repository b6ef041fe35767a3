// FftOcean: Tessendorf's statistical FFT ocean ("Simulating Ocean Water", 2001) — a spectrum of random
// Fourier amplitudes h0(k) evolved with the dispersion relation and transformed to heights, slopes and
// horizontal ("choppy", seed 002 "direct displacement") displacements by inverse FFT on the GPU.
//
//   h(x, t)  = sum_k htilde(k, t) e^{i k.x},   htilde(k, t) = h0(k) e^{i w t} + conj(h0(-k)) e^{-i w t} (eq.
//   26) D(x, t)  = sum_k -i (k / |k|) htilde(k, t) e^{i k.x} (eq. 29) P        = (x + lambda D_x, y + lambda
//   D_y, h)                                                       (eq. 30) h0(k)    = (xi_r + i xi_i)
//   sqrt(P(k) / 2)   (eq. 25) with the Phillips (eq. 40) or JONSWAP spectrum
//
// The wave vectors lie on the lattice k = 2 pi (n, m) / L (n, m in [-N/2, N/2)), so the field tiles with
// period L. This class is the double-precision CPU reference: it evaluates the same spectral components by
// direct sum at any point (O(N^2) per point) — the yardstick for the GPU FFT's accuracy.
#pragma once

#include "ocean/SurfaceModel.h"

#include <complex>
#include <cstdint>
#include <vector>

namespace pacifica::ocean {

enum class Spectrum { Phillips, Jonswap };

struct FftDesc {
    int size = 256;                 ///< N: grid points per side (power of two, 16..1024)
    double tileSize = 500.0;        ///< L: metres per tile
    double windSpeed = 12.0;        ///< U10, m/s
    double windDirectionDeg = 60.0; ///< compass direction the wind blows toward
    double fetch = 200000.0;        ///< metres (JONSWAP)
    Spectrum spectrum = Spectrum::Jonswap;
    double choppiness = 1.0;     ///< lambda (eq. 30); the surface must not fold at the chosen value
    double amplitudeScale = 1.0; ///< multiplies the spectrum's amplitude (a look knob)
    uint32_t seed = 3;
};

class FftOcean final : public SurfaceModel {
public:
    /// Validates (std::invalid_argument naming the field) and draws h0(k).
    explicit FftOcean(const FftDesc& desc = {});

    SurfaceKind kind() const override { return SurfaceKind::Fft; }
    glm::dvec3 displacementAt(const glm::dvec2& xy, double t) const override;
    glm::dvec3 normalAt(const glm::dvec2& xy, double t) const override;
    double jacobianAt(const glm::dvec2& xy, double t) const override;
    double significantWaveHeight() const override;

    const FftDesc& desc() const { return mDesc; }
    /// h0(k) for lattice index (n, m), n, m in [0, N): row-major, n = column. Index (i - N/2) is the wave
    /// number.
    const std::vector<std::complex<double>>& h0() const { return mH0; }
    /// w(k) for the same lattice.
    const std::vector<double>& omega() const { return mOmega; }

private:
    FftDesc mDesc;
    std::vector<std::complex<double>> mH0;
    std::vector<double> mOmega;
    double mHs = 0.0;
};

} // namespace pacifica::ocean
