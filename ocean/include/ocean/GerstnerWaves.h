// GerstnerWaves: a sum of Gerstner (trochoidal) waves, the "Gerstner sums" of the water-rendering notes'
// "Choppy waves" section after Tessendorf 2001 §3.1 and Finch, GPU Gems 1 ch.1 eq. 9:
//
//   P(x, t) = ( x + sum_i Q_i A_i D_i cos(theta_i),  sum_i A_i sin(theta_i) )
//   theta_i = k_i D_i.x - w_i t + phi_i,  k_i = 2 pi / L_i,  w_i = sqrt(g k_i) (deep water)
//   Q_i the steepness of wave i (Q = 1: the trochoid, horizontal excursion equal to the vertical one).
//
// The surface loops over itself when sum_i Q_i k_i A_i > 1 (the Jacobian of x -> x + sum Q A D cos goes
// negative). A request above the limit is clamped — every Q_i scaled by the same factor so the sum is exactly
// the limit — and reported (clampedBy(), a log warning), so the surface never folds.
//
// STEP BY STEP
//   1. GerstnerWaves sea(GerstnerDesc{.waves = {...}});   // or GerstnerWaves sea; for the default wind sea
//   2. sea.displacementAt(xy, t), sea.normalAt(xy, t), sea.heightAt(xy, t)   // CPU, double, unfaded
//   3. GerstnerGpu gpu(std::make_shared<const GerstnerWaves>(sea));   // ocean/src/gpu/GerstnerGpu.h
//      gpu.bind(program, 0, t, camera) sets the uniforms of ocean/shaders/gerstner.glsl
//   4. sea.displacementSeenFrom(xy, t, camera), sea.lightingSeenFrom(...): exactly what the GPU draws
//
// Distance fade. The GPU evaluates theta_i = k_i D_i . rel + theta0_i in float for a camera-relative grid
// point rel (theta0_i wrapped in double, phaseOffsets()). Out to the grid's 40 km, k_i |rel| would reach
// ~3e4 rad for an 8 m wave, where float resolves only ~2e-3 rad — and the radial grid cannot carry such a
// wave that far anyway (its ring spacing exceeds L/2 beyond a few tens of wavelengths). So each wave fades
// out with the distance r = |rel| from the camera:
//   f(r, R) = s^2 (3 - 2 s),  s = clamp((R - r) / (R / 2), 0, 1)      (1 for r <= R/2, 0 for r >= R)
// with R = DISPLACEMENT_FADE_WAVELENGTHS * L_i for the vertex displacement and
// R = LIGHTING_FADE_WAVELENGTHS * L_i for the lighting slopes; the slope variance the lighting fade removes
// is handed to the lighting as unresolved roughness. On the GPU k_i r therefore stays below 2 pi * 400.
// displacementAt(), normalAt() and jacobianAt() are the unfaded reference surface; displacementSeenFrom()
// and lightingSeenFrom() apply the fade exactly as the GLSL does (the GPU-vs-CPU tests use them).
#pragma once

#include "ocean/SurfaceModel.h"

#include <cstdint>
#include <vector>

namespace pacifica::ocean {

struct GerstnerWave {
    double amplitude = 0.5;     ///< A_i, metres
    double wavelength = 60.0;   ///< L_i, metres
    double directionDeg = 60.0; ///< compass direction of travel, degrees clockwise from north
    double steepness = 0.5;     ///< Q_i in [0, 1] as requested (before the sum limit)
    double phase = 0.0;         ///< phi_i, radians
};

struct GerstnerDesc {
    std::vector<GerstnerWave> waves; ///< empty = a default 8-wave wind sea (see defaultWaves())
    double steepnessScale = 1.0;     ///< multiplies every Q_i before the limit (a quality/look knob)
    uint32_t seed = 7;               ///< for defaultWaves()
    /// Living whitecaps: the foam thresholds apply to the remembered crests (foamHeightAt), so foam forms on
    /// a crest, stays where the crest passed and decays over seconds. false: to the current height (a knob
    /// of `pacifica bench accuracy`).
    bool foamMemory = true;
};

class GerstnerWaves final : public SurfaceModel {
public:
    /// Most waves a description may hold (the GLSL's uniform arrays have this size).
    static constexpr int MAX_WAVES = 64;

    /// Validates (std::invalid_argument naming the field, e.g. "GerstnerDesc.waves[2].wavelength") and
    /// clamps.
    explicit GerstnerWaves(const GerstnerDesc& desc = {});

    /// A deterministic wind sea of `count` waves around `windDirectionDeg`: wavelengths log-spaced from
    /// 120 m down to 8 m, each jittered by up to +-10%; wave slopes k A in [0.015, 0.025] (equal slope per
    /// log band, the saturation range of Phillips 1958), so Hs is 1.1-1.9 m for 8 waves; directions within
    /// +-40 degrees of the wind; Q in [0.5, 1]; phases in [0, 2 pi). Depends only on the arguments
    /// (std::mt19937_64 and a portable mapping to [0, 1)). Throws std::invalid_argument unless
    /// 1 <= count <= MAX_WAVES and the direction is finite.
    static std::vector<GerstnerWave> defaultWaves(int count, double windDirectionDeg, uint32_t seed);

    SurfaceKind kind() const override { return SurfaceKind::Gerstner; }
    glm::dvec3 displacementAt(const glm::dvec2& xy, double t) const override;
    /// Exact: the cross product of the analytic tangents of GPU Gems 1 ch.1 eq. 10-11 (see the .cpp).
    glm::dvec3 normalAt(const glm::dvec2& xy, double t) const override;
    double jacobianAt(const glm::dvec2& xy, double t) const override;
    /// 4 sqrt(sum_i A_i^2 / 2).
    double significantWaveHeight() const override;

    /// D_i: the unit (east, north) vector of wave i's compass direction of travel.
    static glm::dvec2 direction(const GerstnerWave& wave);
    /// k_i = 2 pi / L_i, radians per metre.
    static double wavenumber(const GerstnerWave& wave);

    /// GerstnerDesc::foamMemory.
    bool foamMemory() const { return mFoamMemory; }
    /// The waves as used (steepness after the limit).
    const std::vector<GerstnerWave>& waves() const { return mWaves; }
    /// sum_i Q_i k_i A_i as requested, and the factor applied to every Q_i (1 if none was needed).
    double requestedSteepnessSum() const { return mRequestedSum; }
    double clampedBy() const { return mClampFactor; }

    /// Per-wave phase offsets for the GPU: theta0_i = wrap(k_i D_i . camera - w_i t + phi_i, 2 pi), in
    /// double. Each value lies in [0, 2 pi) also as a float (a value that would round up to 2 pi is 0).
    std::vector<float> phaseOffsets(const glm::dvec2& cameraXY, double t) const;

    /// Fade distances in wavelengths (see "Distance fade" above): wave i no longer displaces vertices beyond
    /// DISPLACEMENT_FADE_WAVELENGTHS * L_i from the camera, nor tilts the lighting normal beyond
    /// LIGHTING_FADE_WAVELENGTHS * L_i.
    static constexpr double DISPLACEMENT_FADE_WAVELENGTHS = 40.0;
    static constexpr double LIGHTING_FADE_WAVELENGTHS = 400.0;
    /// The lighting divides by the Jacobian (the Eulerian slope is infinite at a cusp, which the clamped
    /// surface may touch); it divides by max(J, MIN_LIGHTING_JACOBIAN) so the slope stays finite.
    static constexpr double MIN_LIGHTING_JACOBIAN = 1e-2;
    /// The fade factor f(r, R) above: 1 for r <= R / 2, 0 for r >= R, a smoothstep in between.
    static double fade(double distance, double fadeEnd);

    /// What the GPU draws for a camera at cameraXY: displacementAt() with every amplitude A_i multiplied by
    /// f(|xy - cameraXY|, DISPLACEMENT_FADE_WAVELENGTHS * L_i). Equal to displacementAt() within half the
    /// shortest wave's fade distance of the camera.
    glm::dvec3 displacementSeenFrom(const glm::dvec2& xy, double t,
                                    const glm::dvec2& cameraXY) const override;
    /// The CPU twin of the GLSL modelLighting() for a camera at cameraXY: (dH/dx, dH/dy, variance) — the
    /// Eulerian slope of the surface at the image of grid point xy with every A_i multiplied by
    /// f_i = f(|xy - cameraXY|, LIGHTING_FADE_WAVELENGTHS * L_i) (the fade's own gradient is neglected: it
    /// tilts the normal by at most 3 A_i / R_i), and the slope variance the fade removed,
    /// sum_i ((1 - f_i) k_i A_i)^2 / 2 (the mean |grad h|^2 of a sinusoid of slope amplitude k A).
    glm::dvec3 lightingSeenFrom(const glm::dvec2& xy, double t, const glm::dvec2& cameraXY) const;
    /// The foam inputs the GPU computes per fragment (gerstner.glsl modelFoamInputs): (foam height, Jacobian
    /// determinant), both with the displacement fade, as the sea is drawn. J < threshold makes folding foam.
    /// The foam height is the current dz, or with foamMemory the remembered crest (foamHeightAt's formula).
    glm::dvec2 foamInputsSeenFrom(const glm::dvec2& xy, double t, const glm::dvec2& cameraXY) const;
    /// With foamMemory, the living whitecaps' remembered crest height at grid point xy (unfaded), as the FFT
    /// sea's (FftOcean::foamHeightAt): max(h(t), e^(-(t - t_j) / tau) max_{k < W} e^(-k s / tau)
    /// max(h(t_{j-k}), 0)) on the lattice t_j = foamStepTime(j) (SurfaceModel.h, OceanConstants.h). The
    /// grid point is the water parcel's label, so the foam rides the orbital motion and stays where the
    /// crest passed. Without: dz.
    double foamHeightAt(const glm::dvec2& xy, double t) const override;

private:
    struct Terms {      // per wave, derived once from mWaves
        glm::dvec2 dir; // D_i, unit (east, north)
        double k = 0.0, omega = 0.0, amplitude = 0.0, q = 0.0, wavelength = 0.0, phase = 0.0;
    };
    /// At grid point xy with amplitudes A_i * fades[i] (fades null: 1): s = (sxx, sxy, syy), the sums with
    /// J = I - [[sxx, sxy], [sxy, syy]], and gradZ = the gradient of dz with respect to the grid point.
    void jacobianTerms(const glm::dvec2& xy, double t, const double* fades, glm::dvec3& s,
                       glm::dvec2& gradZ) const;
    glm::dvec3 displacement(const glm::dvec2& xy, double t, const double* fades) const;

protected:
    /// displacement() and the horizontal part of jacobianTerms() in one pass over the waves (one sine and
    /// cosine each): the Eulerian solve's Jacobian without central differences.
    bool displacementAndGradient(const glm::dvec2& xy, double t, glm::dvec3& d,
                                 glm::dmat2& grad) const override;

private:
    /// foamHeightAt's formula with amplitudes A_i * fades[i] (fades null: 1).
    double rememberedHeight(const glm::dvec2& xy, double t, const double* fades) const;

    std::vector<GerstnerWave> mWaves;
    std::vector<Terms> mTerms;
    double mRequestedSum = 0.0, mClampFactor = 1.0;
    bool mFoamMemory = true;
};

} // namespace pacifica::ocean
