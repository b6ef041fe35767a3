// SurfaceModel: the CPU side of every ocean surface model (height-map octaves, Gerstner sum, FFT ocean),
// evaluated in double — the reference the GPU is tested against and what CPU queries (physics, cameras)
// use. Each model is defined once: its GLSL twin (ocean/shaders/<model>.glsl) uses the same constants and
// the same formulas, with every phase wrapped in double here before the GPU sees a float.
//
// Positions are world ENU metres. A model displaces the undisplaced (Lagrangian) grid point p = (x, y, 0)
// to p + displacementAt(p, t) = (x + dx, y + dy, dz). Models without horizontal displacement return
// dx = dy = 0.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace pacifica::ocean {

enum class SurfaceKind { Octaves, Gerstner, Fft };

/// "octaves", "gerstner", "fft".
const char* toString(SurfaceKind kind);

/// The lattice of the FFT's and the Gerstner sum's living whitecaps (OceanConstants.h FOAM_MEMORY_STEP):
/// j = floor(t / FOAM_MEMORY_STEP) and t_j = j FOAM_MEMORY_STEP, in double, shared by the CPU twins and the
/// GPU sides so both sample the same times. foamStepIndex throws std::invalid_argument for a non-finite t.
int64_t foamStepIndex(double t);
double foamStepTime(int64_t j);

/// The aperiodic mix of a tiled field (FFT_MIX_*, OceanConstants.h): over a tile of `tile` metres, two
/// uncorrelated copies A, B of the field are mixed as cos(theta) A + sin(theta) B with theta(x) =
/// FFT_MIX_AMPLITUDE sum_j sin(k_j . x + phase_j), so the mix has the field's variance everywhere but no
/// period (a lattice shift s correlates as E[cos(theta(x + s) - theta(x))] <= 0.02). Term j of mix `set` (a
/// different set of phases per tiled field) as (k_x, k_y, phase), k in rad/m, phase in [0, 2 pi).
glm::dvec3 aperiodicMixTerm(double tile, int set, int j);
/// (cos theta(xy), sin theta(xy)) of that mix; theta summed in double.
glm::dvec2 aperiodicMixWeights(double tile, int set, const glm::dvec2& xy);

class SurfaceModel {
public:
    virtual ~SurfaceModel() = default;
    virtual SurfaceKind kind() const = 0;

    /// (dx, dy, dz) of the undisplaced grid point (x, y) at time t (seconds, any magnitude).
    virtual glm::dvec3 displacementAt(const glm::dvec2& xy, double t) const = 0;
    /// Unit normal of the displaced surface at the image of grid point (x, y).
    virtual glm::dvec3 normalAt(const glm::dvec2& xy, double t) const = 0;
    /// Determinant of the Jacobian of the horizontal map (x, y) -> (x + dx, y + dy); 1 without horizontal
    /// displacement, <= 0 where the surface folds (Tessendorf 2001 §4.4; foam).
    virtual double jacobianAt(const glm::dvec2& xy, double t) const = 0;
    /// Significant wave height Hs = 4 * RMS height (for normalising errors), metres.
    virtual double significantWaveHeight() const = 0;
    /// What the GPU draws for grid point (x, y) seen from a camera at cameraXY: displacementAt() with any
    /// distance-dependent level-of-detail fade the model applies (Gerstner fades short waves far away).
    /// The GPU-vs-CPU tests compare against this.
    virtual glm::dvec3 displacementSeenFrom(const glm::dvec2& xy, double t,
                                            const glm::dvec2& /*cameraXY*/) const {
        return displacementAt(xy, t);
    }

    /// The height the foam thresholds (LightingDesc::foamHeightStart/Full) apply to at grid point (x, y):
    /// the displaced height by default; the octave model's living whitecaps remember crests that passed.
    virtual double foamHeightAt(const glm::dvec2& xy, double t) const { return displacementAt(xy, t).z; }
    /// foamHeightAt(xy, t) for each of `times` at one point (a model whose point evaluation has a costly
    /// per-point part, the FFT's direct sum, overrides it to share that part).
    virtual std::vector<double> foamHeightsAt(const glm::dvec2& xy, const std::vector<double>& times) const {
        std::vector<double> out;
        out.reserve(times.size());
        for (double t : times)
            out.push_back(foamHeightAt(xy, t));
        return out;
    }
    /// The grid point x0 whose image lies above world point (x, y) (Eulerian to Lagrangian): solves x0 +
    /// d_xy(x0) = (x, y) by Newton's method (below); (x, y) itself for a model without horizontal
    /// displacement. Where the surface folds, one of the images. `displacement`, if given, receives
    /// displacementAt(x0, t) (computed by the solve anyway).
    glm::dvec2 lagrangianPointAt(const glm::dvec2& xy, double t, glm::dvec3* displacement = nullptr) const;
    /// Height of the surface above world point (x, y) (Eulerian): dz(lagrangianPointAt(xy, t)).
    virtual double heightAt(const glm::dvec2& xy, double t) const;
    /// Velocity of the water at the surface point displaced from grid point (x, y): d/dt of (x + dx, y + dy,
    /// dz) at fixed (x, y), m/s -- the orbital velocity a floating body follows. By default the central
    /// difference over +-VELOCITY_STEP seconds (its error, (w h)^2 / 6 of the velocity, is below 1e-7 for
    /// the shortest waves drawn).
    virtual glm::dvec3 velocityAt(const glm::dvec2& xy, double t) const;
    static constexpr double VELOCITY_STEP = 1e-3;
    /// Batched heightAt.
    void heightsAt(const std::vector<glm::dvec2>& points, double t, std::vector<double>& out) const;

protected:
    /// For lagrangianPointAt's solve: a model with analytic derivatives sets d = displacementAt(xy, t) and
    /// grad = the Jacobian of (dx, dy) with respect to the grid point (columns d/dx, d/dy) in one pass and
    /// returns true; the default returns false (the solve then takes central differences).
    virtual bool displacementAndGradient(const glm::dvec2& /*xy*/, double /*t*/, glm::dvec3& /*d*/,
                                         glm::dmat2& /*grad*/) const {
        return false;
    }
};

} // namespace pacifica::ocean
