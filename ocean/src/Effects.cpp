// Effects: the CPU (double) side of explosions and ship trails — the analytic fields, the per-frame states
// the GPU is given, and the system that turns events into components. The GLSL twin is
// ocean/shaders/effects.glsl; keep them in step (tests/gl/test_effects_gl.cpp compares them).
#include "ocean/Effects.h"

#include "engine/Log.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanHost.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pacifica::ocean {

namespace {

constexpr double TWO_PI = 2.0 * std::numbers::pi;

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}
/// d/dx smoothstep(e0, e1, x).
double smoothstepDerivative(double e0, double e1, double x) {
    const double t = (x - e0) / (e1 - e0);
    if (t <= 0.0 || t >= 1.0)
        return 0.0;
    return 6.0 * t * (1.0 - t) / (e1 - e0);
}

bool finite(const glm::dvec2& v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}

/// Amplitude and foam strength a ship at speed u lays down (WakeParams::amplitude is for 60 m at 10 m/s;
/// wave resistance theory puts the wave height ~ L Fr^2 ~ U^2 at a given length).
double sternAmplitude(const WakeParams& p, double length, double u) {
    if (u < p.minSpeed)
        return 0.0;
    const double scale = length / 60.0;
    return std::min(p.amplitude * scale * (u / 10.0) * (u / 10.0), 4.0 * p.amplitude * scale);
}

double wakeFoamStrength(double amplitude) {
    return std::min(1.0, amplitude / 0.2);
}

/// The time of the largest amplitude of (1 - e^(-tau/rise)) e^(-b tau): rise ln(1 + 1 / (b rise)).
double explosionPeakTime(const ExplosionParams& p) {
    return p.rise * std::log1p(1.0 / std::max(p.decay * p.rise, 1e-9));
}

} // namespace

const char* toString(EffectKind kind) {
    return kind == EffectKind::Explosion ? "explosion" : "wake";
}

ExplosionParams explosionParams(double strength) {
    if (!std::isfinite(strength) || strength <= 0.0)
        throw std::invalid_argument("explosion strength must be finite and > 0, got " +
                                    std::to_string(strength));
    const double c = std::cbrt(strength);
    ExplosionParams p;
    p.amplitude = 2.0 * c;
    p.wavenumber = 0.2 / c; // 31 m wavelength for the nominal charge
    p.coreRadius = 8.0 * c;
    p.foamLife = 12.0 * std::sqrt(c);
    return p;
}

ExplosionState explosionState(const Explosion& e, double t) {
    ExplosionState s;
    const ExplosionParams& p = e.params;
    s.tau = t - e.startTime;
    if (!(s.tau > 0.0))
        return s; // not yet (or NaN time): flat, nothing to draw
    const double growth = -std::expm1(-s.tau / p.rise);
    s.amplitude = p.amplitude * growth * std::exp(-p.decay * s.tau);
    const double omega = std::sqrt(GRAVITY * p.wavenumber); // deep water: w^2 = g k
    s.phase = std::fmod(omega * s.tau, TWO_PI);
    const double groupSpeed = omega / (2.0 * p.wavenumber);
    s.front = p.coreRadius + groupSpeed * s.tau;
    s.frontWidth = std::numbers::pi / p.wavenumber;
    s.foam = -std::expm1(-s.tau / p.foamRise) * std::exp(-s.tau / p.foamLife);
    s.crownRadius = 1.5 * p.coreRadius + 0.3 * groupSpeed * std::min(s.tau, p.foamLife);
    s.slick = p.slickFoam * -std::expm1(-s.tau / 5.0) * std::exp(-s.tau / p.slickLife);
    s.slickRadius = 2.0 * p.coreRadius * std::sqrt(1.0 + s.tau / 30.0);
    // Where the spreading r0 / s brings the amplitude under the end threshold: s = r0 A / end.
    const double spread = p.coreRadius * s.amplitude / std::max(e.endAmplitude, 1e-6);
    double radius = std::min(s.front + s.frontWidth, spread);
    if (s.foam > 0.01)
        radius = std::max(radius, 2.5 * s.crownRadius);
    if (s.slick > 0.01)
        radius = std::max(radius, 2.5 * s.slickRadius);
    s.radius = std::max(radius, 2.0 * p.coreRadius);
    return s;
}

double effectBandFade(double k, double kMax) {
    return 1.0 - smoothstep(0.5 * kMax, kMax, k);
}

glm::dvec3 explosionWave(const ExplosionParams& p, const ExplosionState& s, const glm::dvec2& q,
                         double kMax) {
    const double band = effectBandFade(p.wavenumber, kMax);
    if (s.radius <= 0.0 || band <= 0.0)
        return glm::dvec3(0.0);
    const double r0 = p.coreRadius;
    const double sr = std::sqrt(glm::dot(q, q) + r0 * r0); // s = sqrt(r^2 + r0^2) >= r0
    const double rim = std::sqrt(s.radius * s.radius + r0 * r0);
    if (sr >= rim)
        return glm::dvec3(0.0);
    const double spread = r0 / sr;
    const double arg = p.wavenumber * (sr - r0) - s.phase;
    const double c = std::cos(arg);
    const double w = 1.0 - smoothstep(s.front - s.frontWidth, s.front + s.frontWidth, sr);
    const double taper = 1.0 - smoothstep(0.8 * rim, rim, sr);
    const double h = band * s.amplitude * spread * w * c * taper;
    // dh/ds, then grad h = dh/ds * q / s (ds/dq = q / s): smooth at r = 0.
    const double dSpread = -r0 / (sr * sr);
    const double dc = -p.wavenumber * std::sin(arg);
    const double dw = -smoothstepDerivative(s.front - s.frontWidth, s.front + s.frontWidth, sr);
    const double dTaper = -smoothstepDerivative(0.8 * rim, rim, sr);
    const double dh = band * s.amplitude *
                      (dSpread * w * c * taper + spread * dw * c * taper + spread * w * dc * taper +
                       spread * w * c * dTaper);
    return {h, dh * q.x / sr, dh * q.y / sr};
}

double explosionFoam(const ExplosionParams& p, const ExplosionState& s, const glm::dvec2& q, double h,
                     double filter2) {
    if (s.radius <= 0.0 || glm::dot(q, q) >= s.radius * s.radius)
        return 0.0;
    const double r2 = s.crownRadius * s.crownRadius + filter2;
    const double crown = s.foam * (s.crownRadius * s.crownRadius / r2) * std::exp(-glm::dot(q, q) / r2);
    const double sr2 = s.slickRadius * s.slickRadius + filter2;
    const double slick = s.slick * (s.slickRadius * s.slickRadius / sr2) * std::exp(-glm::dot(q, q) / sr2);
    // GPU Gems 2 §18.3: alpha = (H - H0) / (Hmax - H0).
    const double h0 = 0.35 * p.amplitude, hMax = 0.8 * p.amplitude;
    const double crest = std::clamp((h - h0) / (hMax - h0), 0.0, 1.0);
    return std::clamp(std::max({crown, slick, crest}), 0.0, 1.0);
}

// ---- Wakes ----------------------------------------------------------------------------------------------

WakeState wakeState(const Ship& ship, const ShipTrail& trail, double t) {
    WakeState s;
    wakeState(ship, trail, t, s);
    return s;
}

void wakeState(const Ship& ship, const ShipTrail& trail, double t, WakeState& s) {
    // Every field from scratch, the vectors emptied with their capacity kept.
    for (std::vector<double>* v : {&s.sigma, &s.age, &s.amplitude, &s.k0})
        v->clear();
    s.offsets.clear();
    s.radius = s.peak = s.foamPeak = 0.0;
    s.boxMin = s.boxMax = glm::dvec2(0.0);
    s.ship = trail.history.empty() ? ship.position : trail.history.front().position;
    s.length = std::max(ship.length, 1.0);
    s.beam = s.length / 5.0;
    s.waveLife = trail.params.waveLife;
    s.foamLife = trail.params.foamLife;
    const size_t n = trail.history.size();
    if (n < 2)
        return;
    double sigma = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const WakePoint& pt = trail.history[i];
        // When the head was just frozen into a kept point (EffectsSystem::update, step 4) the two coincide in
        // place and time: a zero-length first segment has no direction, and the path walk would then run
        // the wake near the ship along +x. Leave the copy out.
        if (i > 0 && pt.time == trail.history[i - 1].time && pt.position == trail.history[i - 1].position)
            continue;
        if (i > 0)
            sigma += glm::length(pt.position - trail.history[i - 1].position);
        const double u = pt.speed;
        const double amplitude = sternAmplitude(trail.params, s.length, u);
        s.offsets.push_back(pt.position - s.ship);
        s.sigma.push_back(sigma);
        s.age.push_back(std::max(t - pt.time, 0.0));
        s.amplitude.push_back(amplitude);
        const double us = std::max(u, trail.params.minSpeed);
        s.k0.push_back(GRAVITY / (us * us));
        s.peak = std::max(s.peak, amplitude * std::exp(-s.age.back() / s.waveLife));
        const double foam = wakeFoamStrength(amplitude) * std::exp(-s.age.back() / s.foamLife);
        s.foamPeak = std::max(s.foamPeak, foam);
        // The wedge reaches 0.36 sigma beside the track; the foam strip 3 widths.
        const double reach = glm::length(s.offsets.back()) + std::sqrt(KELVIN_TAN2) * sigma +
                             3.0 * s.beam * (1.0 + sigma / 400.0);
        if (amplitude > 0.0 || foam > 0.0)
            s.radius = std::max(s.radius, reach + 5.0);
    }
    // The box outside which the wake is taken as 0 (the GPU skips the path walk there): the path's bounds
    // widened by the wedge's reach and 3 foam-strip widths (where the strip is down to e^-9).
    const double margin = std::sqrt(KELVIN_TAN2) * sigma + 3.0 * s.beam * (1.0 + sigma / 400.0) + 1.0;
    s.boxMin = s.boxMax = s.offsets.front();
    for (const glm::dvec2& o : s.offsets) {
        s.boxMin = glm::min(s.boxMin, o);
        s.boxMax = glm::max(s.boxMax, o);
    }
    s.boxMin -= margin;
    s.boxMax += margin;
}

WakeCoords wakeCoords(const WakeState& s, const glm::dvec2& q) {
    WakeCoords best;
    double bestDist2 = std::numeric_limits<double>::infinity();
    const size_t n = s.offsets.size();
    for (size_t i = 0; i + 1 < n; ++i) {
        const glm::dvec2 a = s.offsets[i], b = s.offsets[i + 1];
        const glm::dvec2 ab = b - a;
        const double len2 = glm::dot(ab, ab);
        const double u = len2 > 0.0 ? glm::dot(q - a, ab) / len2 : 0.0;
        // Ahead of the ship the first segment's line is extended (negative distance behind).
        const double uc = i == 0 ? std::min(u, 1.0) : std::clamp(u, 0.0, 1.0);
        const glm::dvec2 c = a + uc * ab;
        const double d2 = glm::dot(q - c, q - c);
        // A later (older) segment wins only when clearly closer (relative 1e-4 of d^2): where two parts of
        // the path are equally near (the medial axis, e.g. the centre of a turning circle) the newer one is
        // kept, so float (GPU) and double (CPU) rounding pick the same segment.
        if (d2 < bestDist2 * (1.0 - 1e-4)) {
            bestDist2 = d2;
            const double len = std::sqrt(len2);
            const glm::dvec2 dir = len > 0.0 ? -ab / len : glm::dvec2(1.0, 0.0); // travel direction
            best.direction = dir;
            best.behind = s.sigma[i] + uc * len;
            const double w = std::clamp(uc, 0.0, 1.0);
            best.age = s.age[i] + w * (s.age[i + 1] - s.age[i]);
            best.amplitude = s.amplitude[i] + w * (s.amplitude[i + 1] - s.amplitude[i]);
            best.k0 = s.k0[i] + w * (s.k0[i + 1] - s.k0[i]);
            const glm::dvec2 r = q - c;
            best.lateral = dir.x * r.y - dir.y * r.x; // left of the track positive
        }
    }
    return best;
}

double kelvinPhase(double k0, double x, double y, double t) {
    return k0 * std::sqrt(1.0 + t * t) * (x - std::abs(y) * t);
}

double kelvinHeight(const WakeState& s, const WakeCoords& c, double behind, double lateral, double kMax) {
    return kelvinWave(s, c, behind, lateral, kMax).x;
}

glm::dvec3 kelvinWave(const WakeState& s, const WakeCoords& c, double behind, double lateral, double kMax) {
    // Each factor f carries (f, df/dx, df/dy) with x = behind, y = |lateral| (forward-mode derivatives).
    const double x = behind;
    if (!(x > 0.0) || c.amplitude <= 0.0 || s.sigma.empty())
        return glm::dvec3(0.0);
    const double y = std::abs(lateral);
    const double ta = y / x;
    const glm::dvec2 dta(-ta / x, 1.0 / x);
    const double u = 8.0 * ta * ta; // tan^2 a / tan^2 a_Kelvin
    if (u >= 1.0)
        return glm::dvec3(0.0);
    const glm::dvec2 du = 16.0 * ta * dta;
    const double sd = std::sqrt(1.0 - u);
    // Roots of 2 tan(a) T^2 - T + tan(a) = 0, written so neither divides by a vanishing tan(a); dT/dtan(a) =
    // -(2 T^2 + 1) / (4 tan(a) T - 1) (implicit), and 4 tan(a) T - 1 = -sd, +sd at the two roots.
    const double t1 = 2.0 * ta / (1.0 + sd);
    const double t2raw = (1.0 + sd) / (4.0 * std::max(ta, 1e-6));
    const double t2 = std::min(t2raw, 1000.0);
    const double guard = std::max(sd, 1e-9);
    const double roots[2] = {t1, t2};
    const double dRoots[2] = {(2.0 * t1 * t1 + 1.0) / guard,
                              t2raw < 1000.0 && ta > 1e-6 ? -(2.0 * t2 * t2 + 1.0) / guard : 0.0};
    const double weights[2] = {1.0, 0.6};
    glm::dvec3 sum(0.0);
    for (int j = 0; j < 2; ++j) {
        const double tt = roots[j];
        const glm::dvec2 dt = dRoots[j] * dta;
        const double k = c.k0 * (1.0 + tt * tt);
        const glm::dvec2 dk = 2.0 * c.k0 * tt * dt;
        const double decay = TWO_PI * KELVIN_DECAY_WAVELENGTHS;
        const double band = effectBandFade(k, kMax), e = std::exp(-x * k / decay);
        const double fade = band * e; // short waves fade first (Effects.h)
        if (fade <= 0.0)
            continue;
        const double dBand = -smoothstepDerivative(0.5 * kMax, kMax, k);
        const glm::dvec2 dFade = dBand * dk * e - fade * (glm::dvec2(k, 0.0) + x * dk) / decay;
        const double phase = kelvinPhase(c.k0, x, y, tt);
        // The phase is stationary in T at the roots: its gradient is the wave vector's, T held.
        const double kk = c.k0 * std::sqrt(1.0 + tt * tt);
        const glm::dvec2 dPhase(kk, -kk * tt);
        const double cp = std::cos(phase), sp = std::sin(phase);
        sum += weights[j] * glm::dvec3(fade * cp, dFade * cp - fade * sp * dPhase);
    }
    const double lambda0 = TWO_PI / c.k0;
    const double start = smoothstep(0.0, 0.5 * lambda0, x);
    const double dStart = smoothstepDerivative(0.0, 0.5 * lambda0, x);
    const double cusp = 1.0 - smoothstep(0.8, 1.0, u);
    const glm::dvec2 dCusp = -smoothstepDerivative(0.8, 1.0, u) * du;
    const double sigmaMax = s.sigma.back();
    const double end = 1.0 - smoothstep(0.85 * sigmaMax, sigmaMax, x);
    const double dEnd = -smoothstepDerivative(0.85 * sigmaMax, sigmaMax, x);
    const double a = c.amplitude * std::exp(-c.age / s.waveLife) / std::sqrt(1.0 + x / s.length);
    const double dA = -a / (2.0 * (s.length + x));
    // The envelope a * start * cusp * end and its gradient (x-only factors carry no y derivative).
    const double env = a * start * cusp * end;
    const glm::dvec2 dEnv = glm::dvec2((dA * start * end + a * dStart * end + a * start * dEnd) * cusp, 0.0) +
                            a * start * end * dCusp;
    const glm::dvec2 dH = dEnv * sum.x + env * glm::dvec2(sum.y, sum.z);
    const double side = lateral > 0.0 ? 1.0 : lateral < 0.0 ? -1.0 : 0.0; // d|lateral| / d lateral
    return {env * sum.x, dH.x, side * dH.y};
}

bool insideWakeBox(const WakeState& s, const glm::dvec2& q) {
    return s.radius > 0.0 && glm::dot(q, q) < s.radius * s.radius && q.x > s.boxMin.x && q.y > s.boxMin.y &&
           q.x < s.boxMax.x && q.y < s.boxMax.y;
}

glm::dvec3 wakeWave(const WakeState& s, const glm::dvec2& q, double kMax) {
    if (!insideWakeBox(s, q))
        return glm::dvec3(0.0);
    return wakeWaveAt(s, wakeCoords(s, q), kMax);
}

glm::dvec3 wakeWaveAt(const WakeState& s, const WakeCoords& c, double kMax) {
    // The slope in the path's frame turned into world axes: d(behind)/dq = -direction, d(lateral)/dq = the
    // left normal.
    const glm::dvec3 w = kelvinWave(s, c, c.behind, c.lateral, kMax);
    const glm::dvec2 left(-c.direction.y, c.direction.x);
    const glm::dvec2 g = -w.y * c.direction + w.z * left;
    return {w.x, g.x, g.y};
}

namespace {

/// A band exp(-(d / w)^2) across a line, prefiltered by filter2 (strength w / sqrt(w^2 + F^2)), cut at 3
/// widths (e^-9: the GPU's tiles beyond hold no foam, EffectsGpu.cpp).
double foamBand(double d, double w, double filter2) {
    const double width2 = w * w + filter2;
    return d * d < 9.0 * width2 ? std::sqrt(w * w / width2) * std::exp(-(d * d) / width2) : 0.0;
}

} // namespace

double wakeFoam(const WakeState& s, const WakeCoords& c, double filter2) {
    if (s.sigma.empty() || c.amplitude <= 0.0)
        return 0.0;
    const double L = s.length, B = s.beam;
    const double strength = wakeFoamStrength(c.amplitude) * std::exp(-c.age / s.foamLife);
    const double sigmaMax = s.sigma.back();
    const double end = 1.0 - smoothstep(0.85 * sigmaMax, sigmaMax, c.behind);
    // Behind the stern (the hull is centred on the ship's position): the wash, the strip, the stern foam.
    const double xs = c.behind - 0.5 * L;
    const double aft = smoothstep(-0.05 * L, 0.05 * L, xs);
    const double past = std::max(xs, 0.0);
    const double wash = foamBand(c.lateral, WAKE_WASH_WIDTH * B * std::sqrt(1.0 + past / (2.0 * L)), filter2);
    const double strip = WAKE_STRIP_SHARE * foamBand(c.lateral, B * (1.0 + past / 400.0), filter2);
    const double stern =
        std::exp(-past / (WAKE_STERN_LENGTH * L)) * foamBand(c.lateral, WAKE_STERN_WIDTH * B, filter2);
    // The bow wave: from each bow shoulder, spreading at the Kelvin angle; Froude number U / sqrt(g L) with
    // U^2 = g / k0.
    const double xb = c.behind + 0.5 * L;
    const double froude = 1.0 / std::sqrt(std::max(c.k0, 1e-9) * L);
    const double bowPast = std::max(xb, 0.0);
    const double bow = smoothstep(WAKE_BOW_FROUDE_START, WAKE_BOW_FROUDE_FULL, froude) *
                       smoothstep(-0.02 * L, 0.02 * L, xb) * std::exp(-bowPast / (WAKE_BOW_LENGTH * L)) *
                       (1.0 - smoothstep(0.6 * WAKE_BOW_END * L, WAKE_BOW_END * L, bowPast)) *
                       foamBand(std::abs(c.lateral) - (0.5 * B + std::sqrt(KELVIN_TAN2) * bowPast),
                                WAKE_BOW_WIDTH * B + WAKE_BOW_WIDTH_GROWTH * bowPast, filter2);
    const double white = std::max(aft * std::max({wash, strip, stern}), bow);
    return std::clamp(strength * white * end, 0.0, 1.0);
}

// ---- Whole field ----------------------------------------------------------------------------------------

namespace {

struct FieldSample {
    glm::dvec3 wave{0.0}; // summed (h, dh/dx, dh/dy) before saturation
    double foam = 0.0;
};

FieldSample sampleEffects(const EffectsView& effects, const glm::dvec2& xy, double t, double kMax,
                          double filter2 = 0.0) {
    FieldSample f;
    for (const Explosion& e : effects.explosions) {
        const ExplosionState s = explosionState(e, t);
        const glm::dvec2 q = xy - e.center;
        const glm::dvec3 w = explosionWave(e.params, s, q, kMax);
        f.wave += w;
        f.foam = std::max(f.foam, explosionFoam(e.params, s, q, w.x, filter2));
    }
    for (const WakeRef& wake : effects.wakes) {
        if (!wake.trail->active)
            continue;
        const WakeState s = wakeState(*wake.ship, *wake.trail, t);
        const glm::dvec2 q = xy - s.ship;
        if (!insideWakeBox(s, q))
            continue;
        const WakeCoords c = wakeCoords(s, q); // one path walk for both
        f.wave += wakeWaveAt(s, c, kMax);
        f.foam = std::max(f.foam, wakeFoam(s, c, filter2));
    }
    return f;
}

/// Soft saturation E = L tanh(sum / L); its slope scales by 1 - tanh^2.
glm::dvec3 saturate(const glm::dvec3& sum) {
    const double th = std::tanh(sum.x / EFFECT_HEIGHT_LIMIT);
    const double slope = 1.0 - th * th;
    return {EFFECT_HEIGHT_LIMIT * th, sum.y * slope, sum.z * slope};
}

} // namespace

glm::dvec3 effectsAt(const EffectsView& effects, const glm::dvec2& xy, double t, double kMax) {
    return saturate(sampleEffects(effects, xy, t, kMax).wave);
}

void EffectsSnapshot::update(const EffectsView& effects, double t) {
    mView = effects;
    mTime = t;
    mExplosions.resize(effects.explosions.size());
    for (size_t i = 0; i < mExplosions.size(); ++i)
        mExplosions[i] = explosionState(effects.explosions[i], t);
    mWakes.resize(effects.wakes.size());
    for (size_t i = 0; i < mWakes.size(); ++i)
        if (effects.wakes[i].trail->active)
            wakeState(*effects.wakes[i].ship, *effects.wakes[i].trail, t, mWakes[i]);
}

glm::dvec3 EffectsSnapshot::at(const glm::dvec2& xy, double kMax) const {
    // sampleEffects()'s wave sum, the states made once.
    glm::dvec3 wave(0.0);
    for (size_t i = 0; i < mExplosions.size(); ++i) {
        const Explosion& e = mView.explosions[i];
        wave += explosionWave(e.params, mExplosions[i], xy - e.center, kMax);
    }
    for (size_t i = 0; i < mWakes.size(); ++i) {
        if (!mView.wakes[i].trail->active)
            continue;
        const WakeState& s = mWakes[i];
        const glm::dvec2 q = xy - s.ship;
        if (!insideWakeBox(s, q))
            continue;
        wave += wakeWaveAt(s, wakeCoords(s, q), kMax);
    }
    return saturate(wave);
}

double effectsFoamAt(const EffectsView& effects, const glm::dvec2& xy, double t) {
    return sampleEffects(effects, xy, t, EFFECT_K_MAX).foam;
}

glm::dvec4 effectsFieldAt(const EffectsView& effects, const glm::dvec2& xy, double t, double kMax,
                          double foamFilter2) {
    const FieldSample f = sampleEffects(effects, xy, t, kMax, foamFilter2);
    return glm::dvec4(saturate(f.wave), f.foam);
}

RegistryEffects::RegistryEffects(ecs::Registry& registry) {
    // What EffectsSystem::update() rejects (a ship's NaN position: a lost track) is left out here too, so one
    // bad value costs that effect its frame, not the whole frame (render() refuses a non-finite scene).
    registry.view<Explosion>().each([&](ecs::Entity, Explosion& e) {
        if (finite(e.center) && std::isfinite(e.startTime))
            mExplosions.push_back(e);
    });
    registry.view<Ship, ShipTrail>().each([&](ecs::Entity, Ship& ship, ShipTrail& trail) {
        if (finite(ship.position))
            mWakes.push_back({&ship, &trail});
    });
}

glm::dvec3 effectsAt(ecs::Registry& registry, const glm::dvec2& xy, double t, double kMax) {
    return effectsAt(RegistryEffects(registry).view(), xy, t, kMax);
}

double effectsFoamAt(ecs::Registry& registry, const glm::dvec2& xy, double t) {
    return effectsFoamAt(RegistryEffects(registry).view(), xy, t);
}

glm::dvec4 effectsFieldAt(ecs::Registry& registry, const glm::dvec2& xy, double t, double kMax,
                          double foamFilter2) {
    return effectsFieldAt(RegistryEffects(registry).view(), xy, t, kMax, foamFilter2);
}

// ---- The effects field ----------------------------------------------------------------------------------

void validate(const EffectFieldDesc& d) {
    if (d.size < 16 || d.size > 2048 || d.size % 8 != 0)
        throw std::invalid_argument("EffectFieldDesc.size must be a multiple of 8 in 16..2048, got " +
                                    std::to_string(d.size));
    if (d.levels < 1 || d.levels > 16)
        throw std::invalid_argument("EffectFieldDesc.levels must be in 1..16, got " +
                                    std::to_string(d.levels));
    if (!(d.finestTexel >= 0.01 && d.finestTexel <= 100.0))
        throw std::invalid_argument("EffectFieldDesc.finestTexel must be in 0.01..100 m");
}

EffectFieldLayout::EffectFieldLayout(const EffectFieldDesc& desc, const glm::dvec2& cameraWorld,
                                     double finestUseful)
    : mDesc(desc) {
    validate(desc);
    double texel = desc.finestTexel;
    while (std::isfinite(finestUseful) && texel * 2.0 <= finestUseful && texel < 1e6)
        texel *= 2.0;
    for (int l = 0; l < desc.levels; ++l, texel *= 2.0) {
        EffectFieldLevel level;
        level.texel = texel;
        // Snapped to the texel grid: the texels stay put in the world while the camera moves.
        level.centre = glm::floor(cameraWorld / texel) * texel;
        level.kMax = std::min(EFFECT_K_MAX, TWO_PI / (4.0 * texel));
        level.inner = (0.5 * desc.size - 2.0) * texel;
        level.band = desc.size / 8.0 * texel;
        level.foamFilter2 = texel * texel / 6.0;
        mLevels.push_back(level);
    }
}

glm::dvec2 EffectFieldLayout::texelCentre(int l, int i, int j) const {
    const EffectFieldLevel& level = mLevels[static_cast<size_t>(l)];
    const double half = 0.5 * mDesc.size;
    return level.centre + glm::dvec2(i + 0.5 - half, j + 0.5 - half) * level.texel;
}

EffectFieldLayout::Pick EffectFieldLayout::pick(const glm::dvec2& world) const {
    for (int l = 0; l < levels(); ++l) {
        const EffectFieldLevel& level = mLevels[static_cast<size_t>(l)];
        const glm::dvec2 d = glm::abs(world - level.centre);
        const double a = std::max(d.x, d.y);
        if (a < level.inner)
            return {l, std::clamp((a - (level.inner - level.band)) / level.band, 0.0, 1.0)};
    }
    return {};
}

namespace {

/// Level l read bilinearly at `world` from texel values computed on the CPU (effects.glsl's
/// effectFieldLevel()).
glm::dvec4 bilinear(const EffectsView& effects, const EffectFieldLayout& layout, int l,
                    const glm::dvec2& world, double t) {
    const EffectFieldLevel& level = layout.level(l);
    const int size = layout.desc().size;
    const glm::dvec2 u = (world - level.centre) / level.texel + 0.5 * size - 0.5;
    const glm::dvec2 f = glm::floor(u);
    const glm::dvec2 w = u - f;
    const int i = std::clamp(static_cast<int>(f.x), 0, size - 2);
    const int j = std::clamp(static_cast<int>(f.y), 0, size - 2);
    auto at = [&](int di, int dj) {
        return effectsFieldAt(effects, layout.texelCentre(l, i + di, j + dj), t, level.kMax,
                              level.foamFilter2);
    };
    return glm::mix(glm::mix(at(0, 0), at(1, 0), w.x), glm::mix(at(0, 1), at(1, 1), w.x), w.y);
}

} // namespace

glm::dvec4 sampleEffectField(const EffectsView& effects, const EffectFieldLayout& layout,
                             const glm::dvec2& xy, double t) {
    const EffectFieldLayout::Pick p = layout.pick(xy);
    if (p.level < 0)
        return glm::dvec4(0.0);
    glm::dvec4 v = bilinear(effects, layout, p.level, xy, t);
    if (p.blend > 0.0) {
        const glm::dvec4 next =
            p.level + 1 < layout.levels() ? bilinear(effects, layout, p.level + 1, xy, t) : glm::dvec4(0.0);
        v = glm::mix(v, next, p.blend);
    }
    return v;
}

glm::dvec4 sampleEffectField(ecs::Registry& registry, const EffectFieldLayout& layout, const glm::dvec2& xy,
                             double t) {
    return sampleEffectField(RegistryEffects(registry).view(), layout, xy, t);
}

double oceanHeightAt(ecs::Registry& registry, ecs::Entity ocean, const glm::dvec2& xy, double t) {
    const OceanComponent* c = registry.tryGet<OceanComponent>(ocean);
    if (!c || !c->surface)
        throw std::invalid_argument("oceanHeightAt(): entity " + ecs::toString(ocean) +
                                    " has no OceanComponent");
    return c->surface->heightAt(xy, t) + effectsAt(registry, xy, t).x;
}

// ---- System ---------------------------------------------------------------------------------------------

EffectsSystem::EffectsSystem(ecs::Registry& registry, ecs::EventQueue& events, EffectsDesc desc)
    : mRegistry(registry), mEvents(events), mDesc(desc) {
    if (desc.maxExplosions < 0 || desc.maxWakes < 0)
        throw std::invalid_argument("EffectsDesc: maxExplosions and maxWakes must be >= 0");
    if (!std::isfinite(desc.endAmplitude) || desc.endAmplitude <= 0.0)
        throw std::invalid_argument("EffectsDesc::endAmplitude must be finite and > 0");
    mSubExplosion = mEvents.subscribe<SpawnExplosion>(
        [this](const SpawnExplosion& e) { mPendingExplosions.push_back(e); });
    mSubTrail =
        mEvents.subscribe<AttachShipTrail>([this](const AttachShipTrail& e) { mPendingTrails.push_back(e); });
}

EffectsSystem::~EffectsSystem() {
    mEvents.unsubscribe(mSubExplosion);
    mEvents.unsubscribe(mSubTrail);
}

namespace {

/// The most an explosion will still show: its largest amplitude from now on, times its extent over its
/// distance (the size it subtends).
double explosionVisibility(const Explosion& e, double t, const glm::dvec2& camera, double cameraHeight) {
    const double peakTime = explosionPeakTime(e.params);
    Explosion probe = e;
    const ExplosionState s = explosionState(probe, std::max(t, e.startTime + peakTime));
    const double extent = std::max(s.radius, 10.0 * e.params.coreRadius);
    const glm::dvec2 d = e.center - camera;
    const double dist = std::sqrt(glm::dot(d, d) + cameraHeight * cameraHeight);
    return s.amplitude * extent / std::max(dist, extent);
}

/// Why a spawn cannot be an explosion (nullptr: it can). Beyond finiteness, values no scene means: a centre
/// farther than MAX_EFFECT_DISTANCE from the origin (the float offsets the GPU sees would overflow), a
/// strength above MAX_EXPLOSION_STRENGTH, a start more than MAX_SPAWN_LEAD after the frame (it would hold a
/// place under the cap, flat, for that long).
const char* spawnProblem(const SpawnExplosion& sp, double now) {
    if (!finite(sp.position) || !std::isfinite(sp.time) || !std::isfinite(sp.strength) || sp.strength <= 0.0)
        return "all must be finite, strength > 0";
    if (std::abs(sp.position.x) > MAX_EFFECT_DISTANCE || std::abs(sp.position.y) > MAX_EFFECT_DISTANCE)
        return "position beyond 1e9 m of the origin";
    if (sp.strength > MAX_EXPLOSION_STRENGTH)
        return "strength above 1e6 (a 500 kt charge)";
    if (sp.time > now + MAX_SPAWN_LEAD)
        return "starts more than an hour after the frame";
    return nullptr;
}

} // namespace

namespace {

/// The ship's path: the newest point follows the ship; a point is kept when the ship has moved a segment,
/// turned 8 degrees, or 10 s have passed. h[0] is the head (the ship now), h[1] the newest kept point.
/// Speeds are over the segment from the next-older point (inherited when the head has barely moved on).
void recordPath(std::vector<WakePoint>& h, const glm::dvec2& position, double time, double segment) {
    WakePoint now{position, time, 0.0};
    bool keep = false;
    if (!h.empty()) {
        const WakePoint& last = h.size() >= 2 ? h[1] : h[0];
        const glm::dvec2 d = position - last.position;
        const double dist = glm::length(d);
        const double dt = time - last.time;
        now.speed = dt > 0.05 ? dist / dt : (h.size() >= 2 ? h[1].speed : 0.0);
        keep = dist >= segment || dt >= 10.0;
        if (!keep && h.size() >= 3 && dist >= 2.0) {
            const glm::dvec2 prev = last.position - h[2].position;
            const double pl = glm::length(prev);
            if (pl > 0.0)
                keep = glm::dot(d / dist, prev / pl) < std::cos(8.0 * std::numbers::pi / 180.0);
        }
    }
    if (h.size() < 2) {
        h.insert(h.begin(), now); // the first point stays as the newest kept one
    } else if (keep) {
        h.front() = now; // freeze the head here and start a new one
        h.insert(h.begin(), now);
    } else {
        h.front() = now;
    }
}

/// Forgets the points too long ago or too far back (and beyond MAX_WAKE_POINTS).
void trimPath(std::vector<WakePoint>& h, const WakeParams& params, double time) {
    const double maxAge = 6.0 * std::max(params.waveLife, params.foamLife);
    double sigma = 0.0;
    size_t keepCount = h.size();
    for (size_t i = 1; i < h.size(); ++i) {
        sigma += glm::length(h[i].position - h[i - 1].position);
        if (sigma > params.maxLength || time - h[i].time > maxAge) {
            keepCount = i + 1;
            break;
        }
    }
    h.resize(std::min(keepCount, static_cast<size_t>(MAX_WAKE_POINTS)));
}

} // namespace

void EffectsSystem::update(double time, const glm::dvec3& cameraWorld) {
    mCounters = {};
    const glm::dvec2 camera(cameraWorld);
    const double camHeight = std::isfinite(cameraWorld.z) ? std::abs(cameraWorld.z) : 0.0;
    applySpawns(time, camera, camHeight);
    attachTrails();
    endFadedExplosions(time);
    updateWakes(time, camera, camHeight);
    mCounters.totalDroppedExplosions = mTotalDropped;
}

/// 1. Spawns, with the cap: when full, the least visible of the active ones and the newcomer is dropped.
/// Within one update every visibility is fixed (one time, one camera), so each is computed once: the active
/// explosions go into a heap, least visible on top, the first time a spawn finds the cap reached; each
/// further spawn then costs O(log n), not a scan of the active ones (10 000 spawns in one second with 1024
/// active took 55 ms in one frame's update here with the scan).
void EffectsSystem::applySpawns(double time, const glm::dvec2& camera, double camHeight) {
    std::vector<SpawnExplosion> spawns;
    spawns.swap(mPendingExplosions);
    if (spawns.empty())
        return;
    size_t count = 0;
    mRegistry.view<Explosion>().each([&](ecs::Entity, Explosion&) { ++count; });
    struct Candidate {
        double visibility;
        ecs::Entity entity;
    };
    const auto moreVisible = [](const Candidate& a, const Candidate& b) {
        return a.visibility > b.visibility;
    };
    std::vector<Candidate> heap; // a min-heap on visibility once built
    bool heapBuilt = false;
    const size_t cap = static_cast<size_t>(mDesc.maxExplosions);
    for (const SpawnExplosion& sp : spawns) {
        if (const char* why = spawnProblem(sp, time)) {
            ++mCounters.rejected;
            logWarning("effects: explosion spawn rejected: position (" + std::to_string(sp.position.x) +
                       ", " + std::to_string(sp.position.y) + "), time " + std::to_string(sp.time) +
                       ", strength " + std::to_string(sp.strength) + ": " + why);
            continue;
        }
        Explosion e;
        e.center = sp.position;
        e.startTime = sp.time;
        e.strength = sp.strength;
        e.params = explosionParams(sp.strength);
        e.endAmplitude = mDesc.endAmplitude;
        const double visibility = explosionVisibility(e, time, camera, camHeight);
        if (count >= cap) {
            if (!heapBuilt) {
                mRegistry.view<Explosion>().each([&](ecs::Entity ent, Explosion& other) {
                    heap.push_back({explosionVisibility(other, time, camera, camHeight), ent});
                });
                std::make_heap(heap.begin(), heap.end(), moreVisible);
                heapBuilt = true;
            }
            ++mCounters.droppedExplosions;
            ++mTotalDropped;
            if (heap.empty() || visibility <= heap.front().visibility) { // the newcomer is the least visible
                mEvents.enqueue(EffectEnded{EffectKind::Explosion, ecs::Entity{}, time, true});
                continue;
            }
            std::pop_heap(heap.begin(), heap.end(), moreVisible);
            mRegistry.destroy(heap.back().entity);
            mEvents.enqueue(EffectEnded{EffectKind::Explosion, heap.back().entity, time, true});
            heap.pop_back();
            --count;
        }
        const ecs::Entity ent = mRegistry.create();
        mRegistry.emplace<Explosion>(ent, e);
        ++mCounters.spawned;
        ++count;
        if (heapBuilt) {
            heap.push_back({visibility, ent});
            std::push_heap(heap.begin(), heap.end(), moreVisible);
        }
    }
}

/// 2. Trails attached by events.
void EffectsSystem::attachTrails() {
    std::vector<AttachShipTrail> attaches;
    attaches.swap(mPendingTrails);
    for (const AttachShipTrail& a : attaches) {
        if (!mRegistry.valid(a.ship) || !mRegistry.has<Ship>(a.ship)) {
            ++mCounters.rejected;
            logWarning("effects: AttachShipTrail for entity " + ecs::toString(a.ship) + " without a Ship");
            continue;
        }
        ShipTrail trail;
        trail.params = a.params;
        mRegistry.emplaceOrReplace<ShipTrail>(a.ship, trail);
    }
}

/// 3. Explosions that faded end.
void EffectsSystem::endFadedExplosions(double time) {
    std::vector<ecs::Entity> ended;
    mRegistry.view<Explosion>().each([&](ecs::Entity ent, Explosion& e) {
        const ExplosionState s = explosionState(e, time);
        const bool grown = s.tau > 3.0 * e.params.rise + explosionPeakTime(e.params);
        if (grown && s.amplitude < mDesc.endAmplitude && s.foam < 0.01 && s.slick < 0.01)
            ended.push_back(ent);
        else if (s.tau > 0.0)
            ++mCounters.activeExplosions;
    });
    for (ecs::Entity ent : ended) {
        mRegistry.destroy(ent);
        mEvents.enqueue(EffectEnded{EffectKind::Explosion, ent, time, false});
        ++mCounters.ended;
    }
}

/// 4. The ships' paths, trails that went quiet end; 5. the wake cap: the most visible are drawn.
void EffectsSystem::updateWakes(double time, const glm::dvec2& camera, double camHeight) {
    struct Candidate {
        ecs::Entity entity;
        double visibility;
    };
    std::vector<Candidate> wakes;
    mRegistry.view<Ship, ShipTrail>().each([&](ecs::Entity ent, Ship& ship, ShipTrail& trail) {
        if (!finite(ship.position)) {
            ++mCounters.rejected;
            return; // keep the path as it was; a NaN position never enters the history
        }
        if (trail.history.empty() || time > trail.history.front().time) {
            recordPath(trail.history, ship.position, time, trail.params.maxLength / (MAX_WAKE_POINTS - 2));
            trimPath(trail.history, trail.params, time);
        }
        const WakeState s = wakeState(ship, trail, time);
        const bool alive = s.radius > 0.0 && (s.peak >= mDesc.endAmplitude || s.foamPeak >= 0.01);
        if (!alive) {
            if (trail.active) {
                mEvents.enqueue(EffectEnded{EffectKind::Wake, ent, time, false});
                ++mCounters.ended;
            }
            trail.active = false;
            return;
        }
        const glm::dvec2 d = s.ship - camera;
        const double dist = std::sqrt(glm::dot(d, d) + camHeight * camHeight);
        wakes.push_back({ent, std::max(s.peak, 0.1) * s.radius / std::max(dist, s.radius)});
        trail.active = true;
    });
    std::sort(wakes.begin(), wakes.end(), [](const Candidate& a, const Candidate& b) {
        return a.visibility > b.visibility ||
               (a.visibility == b.visibility && a.entity.index < b.entity.index);
    });
    for (size_t i = 0; i < wakes.size(); ++i) {
        if (static_cast<int>(i) < mDesc.maxWakes) {
            ++mCounters.activeWakes;
        } else {
            mRegistry.get<ShipTrail>(wakes[i].entity).active = false;
            ++mCounters.droppedWakes;
        }
    }
}

EffectsTimeline::EffectsTimeline(ecs::Registry& registry, ecs::EventQueue& events, EffectsSystem& system)
    : mRegistry(registry), mEvents(events), mSystem(system) {}

ecs::Entity EffectsTimeline::addShip(const glm::dvec2& position, double length, Track track,
                                     WakeParams wake) {
    const ecs::Entity e = mRegistry.create();
    mRegistry.emplace<Ship>(e, Ship{position, length});
    mEvents.enqueue(AttachShipTrail{e, wake});
    mShips.push_back(e);
    mTracks.push_back(std::move(track));
    return e;
}

void EffectsTimeline::scheduleExplosions(std::vector<SpawnExplosion> explosions) {
    std::stable_sort(explosions.begin(), explosions.end(),
                     [](const SpawnExplosion& a, const SpawnExplosion& b) { return a.time < b.time; });
    mExplosions = std::move(explosions);
    mNextExplosion = 0;
}

void EffectsTimeline::step(double time, const glm::dvec3& cameraWorld) {
    for (size_t i = 0; i < mShips.size(); ++i)
        mRegistry.get<Ship>(mShips[i]).position = mTracks[i](time);
    for (; mNextExplosion < mExplosions.size() && mExplosions[mNextExplosion].time <= time; ++mNextExplosion)
        mEvents.enqueue(mExplosions[mNextExplosion]);
    mEvents.dispatch();
    mSystem.update(time, cameraWorld);
}

void EffectsTimeline::warmUp(double from, double to, const glm::dvec3& cameraWorld,
                             const std::function<void(double)>& beforeStep) {
    for (double t = from; t < to; t += WARM_UP_STEP) {
        if (beforeStep)
            beforeStep(t);
        step(t, cameraWorld);
    }
}

} // namespace pacifica::ocean
