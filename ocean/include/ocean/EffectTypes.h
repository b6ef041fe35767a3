// EffectTypes: the effects' data and maths without any ECS (Effects.h adds the events, the system and the
// registry adapters on top). Explosions (GPU Gems 2 §18.3's ring wave) and ship trails (a Kelvin wake) as
// plain structs; the field all of them make together, E(x, t), evaluated by the CPU from plain spans
// (EffectsView: effectsAt, effectsFieldAt, sampleEffectField) and by the GPU into the effects field, a
// camera-centred clipmap (EffectFieldLayout) every grid reads. The GLSL twins are ocean/shaders/effects.glsl
// (the field), effects_field.comp (its texels) and effects_sample.glsl (the read).
//
// The field of all active effects together is one function E(x, t) of the world point x (summed, then
// softly saturated at EFFECT_HEIGHT_LIMIT); every grid draws base + E read from the field, so overlapping
// effects meet without seams, and the base grid leaves out the discs the secondary grids cover.
#pragma once

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace pacifica::ocean {

/// Soft limit of the summed effect height, metres: E = L tanh(sum / L), so a thousand explosions in one
/// spot stay a bounded (if violent) sea instead of a kilometre-high spike.
inline constexpr double EFFECT_HEIGHT_LIMIT = 12.0;
/// Most history points of one ship trail (the GPU buffer's stride).
inline constexpr int MAX_WAKE_POINTS = 64;
/// Kelvin wake half-angle: asin(1/3) = 19.47 degrees (Kelvin 1887; the cusp of the stationary-phase
/// solution of deep-water ship waves, tan^2 = 1/8).
inline constexpr double KELVIN_TAN2 = 1.0 / 8.0;
/// Shortest wave a secondary grid resolves, metres: components of the wake (the divergent waves near the
/// track have unbounded wave number) fade out between twice this and this wavelength.
inline constexpr double EFFECT_MIN_WAVELENGTH = 3.0;
/// The wave number of EFFECT_MIN_WAVELENGTH: an effect's components fade out between half this and this
/// (the analytic field's band limit; a level of the effects field lowers it to its own, EffectFieldLevel).
inline constexpr double EFFECT_K_MAX = 2.0 * 3.14159265358979323846 / EFFECT_MIN_WAVELENGTH;
/// The band-limit factor of a component of wave number k: 1 - smoothstep(kMax / 2, kMax, k).
double effectBandFade(double k, double kMax);
/// A wake component of wavelength lambda decays as e^(-x / (KELVIN_DECAY_WAVELENGTHS lambda)) with the
/// distance x behind the ship: the short divergent waves break and fade within tens of their wavelengths
/// while the long transverse ones run on (heuristic; viscous damping, 2 nu k^2 (Lamb 1932 §348), alone is far
/// weaker). It also keeps the far wake within what its grid can carry.
inline constexpr double KELVIN_DECAY_WAVELENGTHS = 25.0;

/// The wake's white water (wakeFoam; docs/EFFECTS.md "The wake's white water"), in ship lengths L and beams
/// B (B = L / 5) from the hull's centre, where the ship's position is:
/// - propeller wash: a bright core behind the stern, 1/e half-width WAKE_WASH_WIDTH B (1 + x_s / 2L)^(1/2)
///   at x_s behind the stern;
/// - turbulent wake: the paler strip around it, WAKE_STRIP_SHARE as white, half-width B (1 + x_s / 400 m);
/// - stern foam: churned water right behind the stern, half-width WAKE_STERN_WIDTH B, fading over
///   WAKE_STERN_LENGTH L;
/// - bow wave: white water breaking off each bow shoulder along a line spreading at the Kelvin angle,
///   half-width WAKE_BOW_WIDTH B + WAKE_BOW_WIDTH_GROWTH x_b at x_b behind the bow, fading over
///   WAKE_BOW_LENGTH L and gone by WAKE_BOW_END L (so it stays inside the foam's reach, 3 B beside the
///   track), and only above a Froude number U / sqrt(g L) of WAKE_BOW_FROUDE_START (full from
///   WAKE_BOW_FROUDE_FULL): slow ships push a smooth bow wave.
inline constexpr double WAKE_WASH_WIDTH = 0.3;
inline constexpr double WAKE_STRIP_SHARE = 0.45;
inline constexpr double WAKE_STERN_WIDTH = 0.6;
inline constexpr double WAKE_STERN_LENGTH = 0.25;
inline constexpr double WAKE_BOW_WIDTH = 0.08;
inline constexpr double WAKE_BOW_WIDTH_GROWTH = 0.03;
inline constexpr double WAKE_BOW_LENGTH = 0.35;
inline constexpr double WAKE_BOW_END = 1.0;
inline constexpr double WAKE_BOW_FROUDE_START = 0.12;
inline constexpr double WAKE_BOW_FROUDE_FULL = 0.3;

// ---- Explosion ------------------------------------------------------------------------------------------

/// The §18.3 ring wave's parameters (the seed names I0, b, k and w): amplitude I0, decay b, wave number k,
/// frequency w = sqrt(g k) (deep water). Derived from a strength by explosionParams().
struct ExplosionParams {
    double amplitude = 2.0;  ///< I0, metres: peak height once grown
    double wavenumber = 0.2; ///< k, rad/m
    double decay = 0.06;     ///< b, 1/s: temporal decay e^(-b tau)
    double rise = 0.6;       ///< s: growth 1 - e^(-tau / rise), so the sea is flat at tau = 0
    double coreRadius = 8.0; ///< r0, metres: regularises the cylindrical spreading r0 / sqrt(r0^2 + r^2)
    double foamLife = 12.0;  ///< s: crown foam decays as e^(-tau / foamLife)
    double foamRise = 0.4;   ///< s: crown foam grows as 1 - e^(-tau / foamRise)
    /// The slick an impact leaves: churned, aerated water that stays white and spreads for minutes after the
    /// crown has gone (seen from the air as a pale disc where a bomb or shell fell; observation, no model
    /// in the seeds): strength slickFoam (1 - e^(-tau / 5 s)) e^(-tau / slickLife), radius
    /// 2 r0 sqrt(1 + tau / 30 s).
    double slickFoam = 0.6;
    double slickLife = 120.0; ///< s
};

/// Parameters for a strength s (1 = a nominal 500 kg charge): lengths scale with the cube root of the
/// energy (Hopkinson–Cranz scaling), so amplitude, wavelength and core radius go as s^(1/3).
/// Throws std::invalid_argument unless s is finite and > 0.
ExplosionParams explosionParams(double strength);

/// The component of an explosion entity (created by EffectsSystem from SpawnExplosion).
struct Explosion {
    glm::dvec2 center{0.0};
    double startTime = 0.0;
    double strength = 1.0;
    ExplosionParams params;
    double endAmplitude = 0.01; ///< EffectsDesc::endAmplitude when spawned: sets the grid radius and the end
};

/// What an explosion is at time t (tau = t - startTime): the quantities both the CPU and the GPU evaluate
/// the ring from. Before the start (tau < 0) everything is 0.
struct ExplosionState {
    double tau = 0.0;
    double amplitude = 0.0;   ///< I0 (1 - e^(-tau/rise)) e^(-b tau), metres
    double phase = 0.0;       ///< w tau wrapped to [0, 2 pi) (in double)
    double front = 0.0;       ///< radius the wave train has reached: r0 + c_g tau, c_g = w / (2 k)
    double frontWidth = 0.0;  ///< half a wavelength: pi / k
    double radius = 0.0;      ///< the secondary grid's radius: where the field has been tapered to 0
    double foam = 0.0;        ///< crown foam strength in [0, 1]: (1 - e^(-tau/foamRise)) e^(-tau/foamLife)
    double crownRadius = 0.0; ///< the crown foam's e-folding radius, metres
    double slick = 0.0;       ///< the slick's foam strength in [0, 1]
    double slickRadius = 0.0; ///< its e-folding radius, metres
};
ExplosionState explosionState(const Explosion& e, double t);

/// The ring wave of one explosion at offset q from its centre (metres), GPU Gems 2 §18.3 made regular:
///   h = A(tau) * r0 / sqrt(r0^2 + r^2) * W(r) * cos(k rho - w tau) * T(r),
/// rho = sqrt(r^2 + r0^2) - r0 (smooth at r = 0), W = 1 - smoothstep(front - width, front + width, r)
/// (no wave ahead of the group front), T = 1 - smoothstep(0.8 R, R, r) (zero at the grid's rim).
/// The seed's printed formula is missing from our copy; this form keeps its symbols (I0, b, k, w) and its
/// 1/r spreading, regularised so nothing is singular at r = 0 or tau = 0. Returns (h, dh/dx, dh/dy).
/// All radial factors are functions of s = sqrt(r^2 + r0^2) (so the field is smooth at r = 0). The ring is
/// scaled by effectBandFade(k, kMax) (a ring shorter than the band limit is not drawn).
glm::dvec3 explosionWave(const ExplosionParams& p, const ExplosionState& s, const glm::dvec2& q,
                         double kMax = EFFECT_K_MAX);
/// Crown foam coverage in [0, 1] at offset q: foam * exp(-(r / crownRadius)^2), the slick's
/// slick * exp(-(r / slickRadius)^2) and the §18.3 height threshold on the ring's crests (alpha = (h - H0) /
/// (Hmax - H0), H0 = 0.35 I0, Hmax = 0.8 I0), the largest of the three.
/// `filter2` (m^2) prefilters the crown for a texel of the effects field: the Gaussian convolved with one of
/// e-folding radius^2 filter2, exp(-r^2 / (R^2 + F^2)) R^2 / (R^2 + F^2), so a crown smaller than a texel
/// keeps its area (its coverage) instead of falling between texel centres.
double explosionFoam(const ExplosionParams& p, const ExplosionState& s, const glm::dvec2& q, double h,
                     double filter2 = 0.0);

// ---- Ship trail (Kelvin wake) ---------------------------------------------------------------------------

/// A ship the host moves: its position on the sea, updated every frame.
struct Ship {
    glm::dvec2 position{0.0};
    double length = 60.0; ///< metres (sets the wake's amplitude and the turbulent strip's width)
};

struct WakeParams {
    double amplitude = 0.5;    ///< metres at the stern for a 60 m ship at 10 m/s (scales with L and U^2)
    double waveLife = 90.0;    ///< s: wake waves decay as e^(-age / waveLife)
    double foamLife = 150.0;   ///< s: the turbulent strip's foam decays as e^(-age / foamLife)
    double maxLength = 3000.0; ///< metres of path kept
    double minSpeed = 0.5;     ///< m/s: below it the ship makes no waves
};

/// One recorded point of the ship's path: where it was, when, and the arc length back to the newest point.
struct WakePoint {
    glm::dvec2 position{0.0};
    double time = 0.0;
    double speed = 0.0; ///< m/s over the segment from the next-older point
};

/// The ship-trail source attached to a ship entity (AttachShipTrail). history[0] is the newest point.
struct ShipTrail {
    WakeParams params;
    std::vector<WakePoint> history;
    bool active = false; ///< drawn and queried this frame (EffectsSystem::update)
};

/// What a trail is at time t: the points relative to the ship, their arc length, age, and the amplitude
/// and wave number each point's speed gave it (a ship that stops leaves its wake to decay).
struct WakeState {
    std::vector<glm::dvec2> offsets; ///< point - ship position, newest (the ship) first
    std::vector<double> sigma;       ///< arc length from the ship along the path
    std::vector<double> age;         ///< t - point time
    std::vector<double> amplitude;   ///< stern wave amplitude when the point was laid, metres
    std::vector<double> k0;          ///< g / U^2 at that point, rad/m (transverse wave number)
    glm::dvec2 ship{0.0};
    double length = 60.0; ///< ship length, metres (amplitude falls as 1 / sqrt(1 + x / L))
    double beam = 0.0;    ///< half-width of the turbulent strip at the stern, metres
    double waveLife = 0.0, foamLife = 0.0;
    double radius = 0.0;   ///< the secondary grid's radius (0: nothing to draw)
    double peak = 0.0;     ///< largest wave amplitude anywhere in the wake, metres
    double foamPeak = 0.0; ///< largest foam strength anywhere in the wake, [0, 1]
    /// Relative to the ship: outside this box (and the radius) the wake is 0 (insideWakeBox).
    glm::dvec2 boxMin{0.0}, boxMax{0.0};
};
/// Whether q (relative to the ship) is where the wake can be non-zero: inside the radius and the box of the
/// path widened by the wedge's reach and 3 foam-strip widths.
bool insideWakeBox(const WakeState& s, const glm::dvec2& q);
WakeState wakeState(const Ship& ship, const ShipTrail& trail, double t);
/// The same into `out`, reusing its vectors' capacity (no allocation once they are large enough).
void wakeState(const Ship& ship, const ShipTrail& trail, double t, WakeState& out);

/// Where a point lies relative to the path: arc length behind the ship, signed lateral offset, age of the
/// path there, and the path's travel direction there. behind < 0 means ahead of the ship.
struct WakeCoords {
    double behind = 0.0, lateral = 0.0, age = 0.0;
    double amplitude = 0.0, k0 = 0.0; ///< interpolated from the path points
    glm::dvec2 direction{1.0, 0.0};
};
/// q is relative to the ship. Closest point on the history polyline (ahead of the ship: the first
/// segment's line extended).
WakeCoords wakeCoords(const WakeState& s, const glm::dvec2& q);
/// The phase of the Kelvin system with direction T = tan(theta) at x behind and y beside the track:
/// k0 sqrt(1 + T^2) (x - |y| T), i.e. k0 sec^2(theta) (x cos(theta) - |y| sin(theta)). It is stationary in T
/// exactly at the roots of 2 tan(a) T^2 - T + tan(a) = 0 (the systems kelvinHeight() sums).
double kelvinPhase(double k0, double x, double y, double t);
/// Kelvin pattern (stationary phase, deep water; e.g. Lighthill, "Waves in Fluids" §3.10): at x behind
/// and y beside the track, tan a = |y| / x <= 1/sqrt(8), the wave directions T = tan(theta) solve
/// 2 tan(a) T^2 - T + tan(a) = 0 (transverse and divergent), wave number k0 (1 + T^2), phase
/// kelvinPhase() = k0 sqrt(1 + T^2) (x - |y| T) (until 2026-11 written with + |y| T, which is not
/// stationary at these roots and bent the crests the wrong way). Amplitude A e^(-age/waveLife) / sqrt(1 + x /
/// L); the divergent system at 0.6 of the transverse. c gives the path's amplitude, k0 and age there. Each
/// system is scaled by effectBandFade(k, kMax). Returns h.
double kelvinHeight(const WakeState& s, const WakeCoords& c, double behind, double lateral,
                    double kMax = EFFECT_K_MAX);
/// (h, dh/dbehind, dh/dlateral) of kelvinHeight(), the derivatives analytic (c held, as the path's
/// amplitude, k0 and age are): the phase's gradient at a stationary root is its wave vector k0 sqrt(1 + T^2)
/// (1, -T) (T held), plus the envelope's and the roots' own variation (dT/dtan(a) from the quadratic). One
/// evaluation instead of the five of central differences.
glm::dvec3 kelvinWave(const WakeState& s, const WakeCoords& c, double behind, double lateral,
                      double kMax = EFFECT_K_MAX);
/// (h, dh/dx, dh/dy) of the wake at q (relative to the ship).
glm::dvec3 wakeWave(const WakeState& s, const glm::dvec2& q, double kMax = EFFECT_K_MAX);
/// The same from the point's path coordinates (wakeCoords), for a caller that also needs them (foam); no box
/// test.
glm::dvec3 wakeWaveAt(const WakeState& s, const WakeCoords& c, double kMax = EFFECT_K_MAX);
/// Wake foam in [0, 1]: the brightest of the propeller wash, the turbulent strip, the stern foam and the bow
/// wave (the WAKE_* constants above), each a band exp(-(d / w)^2) across its line for |d| < 3 w (0 beyond),
/// times the strength the ship's speed gave the path there and e^(-age / foamLife).
/// `filter2` prefilters each band as explosionFoam() does the crown (across it: w^2 -> w^2 + F^2, strength
/// times w / sqrt(w^2 + F^2)).
double wakeFoam(const WakeState& s, const WakeCoords& c, double filter2 = 0.0);

enum class EffectKind { Explosion, Wake };
const char* toString(EffectKind kind);

// ---- The effects field: what the GPU draws ----------------------------------------------------------------

/// The GPU evaluates the effects once per frame into a camera-centred clipmap (one texture array, a level per
/// layer, each level twice the texel of the one before; ocean/shaders/effects_field.comp) and every grid
/// samples it, so an effect costs the texels it touches, whatever the grids' vertex counts and however many
/// effects overlap. Level L holds the field band-limited to its texel (components shorter than 4 texels fade
/// out between 8 and 4 texels a wavelength: EffectFieldLevel::kMax) so that coarse levels do not alias.
inline constexpr int EFFECT_FIELD_MAX_LEVELS = 16;
struct EffectFieldDesc {
    int size = 512;           ///< texels per side of each level (a multiple of 8, 16..2048)
    int levels = 9;           ///< 1..16; level L's texel is finestTexel 2^L (9 levels of 0.5 m: +-32 km)
    double finestTexel = 0.5; ///< metres
    /// Evaluate only the tiles this frame's readers can reach: the base grid's view sector (RadialGrid.h
    /// computeViewSector) widened by twice the horizontal displacement bound, and the discs of the secondary
    /// grids drawn. Off: every tile an effect touches (a wake's trail behind the camera too). The image is
    /// the same either way; a frame with GPU height queries waiting, a projected grid or a whole-circle
    /// sector evaluates every tile.
    bool viewCull = true;
};
/// Throws std::invalid_argument naming the field (EffectFieldDesc.size ...) if out of range.
void validate(const EffectFieldDesc& desc);

struct EffectFieldLevel {
    glm::dvec2 centre{0.0}; ///< world; texel (i, j) is centred at centre + (i + 0.5 - size/2, j + ...) texel
    double texel = 0.0;     ///< metres
    double kMax = 0.0;      ///< band limit: min(EFFECT_K_MAX, 2 pi / (4 texel)), 4 texels per wavelength
    double inner = 0.0; ///< half-width (Chebyshev, from centre) where this level is read: (size/2 - 2) texel
    double band = 0.0;  ///< outermost width of `inner` that blends into the next level: size/8 texels
    double foamFilter2 = 0.0; ///< the foam's prefilter, texel^2 / 6 (a box of one texel as a Gaussian)
};

/// The levels of the field around a camera, as the GPU lays them out: each centre snapped to its level's
/// texel grid (so the texels stay put in the world while the camera moves within a texel). The finest level
/// is the coarsest finestTexel 2^n no larger than `finestUseful` (a pixel's footprint on the nearest sea,
/// effectFieldLayout() in Ocean.h): from altitude no texel finer than a pixel is evaluated, and the levels
/// reach further.
class EffectFieldLayout {
public:
    EffectFieldLayout(const EffectFieldDesc& desc, const glm::dvec2& cameraWorld, double finestUseful = 0.0);
    const EffectFieldDesc& desc() const { return mDesc; }
    const EffectFieldLevel& level(int l) const { return mLevels[static_cast<size_t>(l)]; }
    int levels() const { return static_cast<int>(mLevels.size()); }
    /// World centre of texel (i, j) of level l.
    glm::dvec2 texelCentre(int l, int i, int j) const;
    /// Which level a world point reads, and its blend toward the next level (0: this level only; toward 1
    /// at the level's edge: the next, or 0 beyond the last level). level = -1 outside the field.
    struct Pick {
        int level = -1;
        double blend = 0.0;
    };
    Pick pick(const glm::dvec2& world) const;

private:
    EffectFieldDesc mDesc;
    std::vector<EffectFieldLevel> mLevels;
};

// ---- What a frame or a query sees ----------------------------------------------------------------------

/// A ship's wake as the renderer and the queries read it: the host's ship and its trail. A trail whose
/// `active` is false (EffectsSystem's cap, or a host that hides it) is left out.
struct WakeRef {
    const Ship* ship = nullptr;
    const ShipTrail* trail = nullptr;
};

/// Every effect of a frame or a query, as plain spans the host owns for the duration of the call (no ECS:
/// Effects.h's RegistryEffects builds one from a registry). Order matters only to floating-point sums:
/// the same spans in the same order give the same pixels.
struct EffectsView {
    std::span<const Explosion> explosions;
    std::span<const WakeRef> wakes;
    bool empty() const { return explosions.empty() && wakes.empty(); }
};

/// Sum of every active effect at world point xy, time t: (height, dh/dx, dh/dy), saturated (E = L tanh(sum
/// / L)), band-limited at kMax. Zero with no effects. The analytic field: the effects field's texels hold it
/// (EffectFieldLayout), the GPU draws it interpolated.
glm::dvec3 effectsAt(const EffectsView& effects, const glm::dvec2& xy, double t, double kMax = EFFECT_K_MAX);
/// The effects at one time for many points: each explosion's and wake's state made once by update() (into
/// buffers it keeps: no allocation once they are large enough), then at() per point -- the same sums in the
/// same order as effectsAt(effects, xy, t), so the same bits, without rebuilding every wake's path for every
/// point. The view's spans must stay valid while at() is used.
class EffectsSnapshot {
public:
    void update(const EffectsView& effects, double t);
    bool empty() const { return mView.empty(); }
    double time() const { return mTime; }
    /// effectsAt(effects, xy, time(), kMax).
    glm::dvec3 at(const glm::dvec2& xy, double kMax = EFFECT_K_MAX) const;

private:
    EffectsView mView;
    double mTime = 0.0;
    std::vector<ExplosionState> mExplosions;
    std::vector<WakeState> mWakes; // one per wake of the view (an inactive one's is not used)
};

/// Foam coverage of the effects at xy (max over effects).
double effectsFoamAt(const EffectsView& effects, const glm::dvec2& xy, double t);
/// (E, dE/dx, dE/dy, foam) at xy in one pass over the effects; foam prefiltered by `foamFilter2`
/// (explosionFoam, wakeFoam).
glm::dvec4 effectsFieldAt(const EffectsView& effects, const glm::dvec2& xy, double t,
                          double kMax = EFFECT_K_MAX, double foamFilter2 = 0.0);

/// The CPU twin of what the GPU samples at world point xy: each level's texels hold effectsFieldAt() at their
/// centres with the level's kMax; the point reads its level bilinearly, blended into the next level toward
/// the edge (EffectFieldLayout::pick). (E, dE/dx, dE/dy, foam).
glm::dvec4 sampleEffectField(const EffectsView& effects, const EffectFieldLayout& layout,
                             const glm::dvec2& xy, double t);

} // namespace pacifica::ocean
