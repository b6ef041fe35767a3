// Unit tests of SeaQuery (ocean/SeaQuery.h), the batched sea queries, for every model:
// - the octave and Gerstner paths equal the model's own CPU queries bit for bit (height, normal, the grid
//   point under the point), also 10^7 m from the origin at t = 10^6 s; the FFT's sampled path stays within
//   its interpolation's bound of the direct sum (the reference) there;
// - velocity, normal and height over time agree with the kinematic surface condition dh/dt|x = w - u . grad h
//   (an independent check of the three together), for the FFT's spectral time derivative too;
// - the effects' height and slopes are added;
// - the thread count changes no bit; no allocation once warm (a counting operator new in this binary);
// - hard cases: 0 points, 10^6 points, NaN points (answered NaN and counted, the others answered), a point
//   under a Gerstner crest at the steepness limit; bad calls refused with a message.
#include "ocean/SeaQuery.h"

#include "engine/Ecs.h"
#include "ocean/Effects.h"
#include "ocean/FftOcean.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <random>
#include <vector>

using namespace pacifica;
using namespace pacifica::ocean;

// ---- A counting allocator for this binary -----------------------------------------------------------------
// Replacing the global operator new/delete pair is standard C++; GCC 12 still warns that the inlined delete
// frees what "new" returned (its -Wmismatched-new-delete does not see the replacement), hence the pragma.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<long> gAllocations{0};
} // namespace

void* operator new(std::size_t size) {
    ++gAllocations;
    if (void* p = std::malloc(size ? size : 1))
        return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}

namespace {

OceanComponent makeSea(SurfaceKind model) {
    OceanDesc desc;
    desc.model = model;
    OceanComponent ocean;
    const Status s = makeOcean(desc, ocean);
    EXPECT_TRUE(s.ok()) << s.message;
    return ocean;
}

std::vector<glm::dvec2> randomPoints(size_t count, const glm::dvec2& origin, double spread,
                                     unsigned seed = 5) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-spread, spread);
    std::vector<glm::dvec2> points(count);
    for (glm::dvec2& p : points)
        p = origin + glm::dvec2(u(rng), u(rng));
    return points;
}

SeaQuery makeQuery(const OceanComponent& ocean, double t, SeaQueryDesc desc = {}, const EffectsView& e = {}) {
    SeaQuery q;
    Status s = q.init(ocean, desc);
    EXPECT_TRUE(s.ok()) << s.message;
    s = q.update(t, e);
    EXPECT_TRUE(s.ok()) << s.message;
    return q;
}

} // namespace

TEST(SeaQuery, OctavesAndGerstnerEqualTheModelBitForBitNearAndFar) {
    for (SurfaceKind model : {SurfaceKind::Octaves, SurfaceKind::Gerstner}) {
        const OceanComponent ocean = makeSea(model);
        for (const auto& [origin, t] :
             {std::pair{glm::dvec2(0.0), 37.5}, std::pair{glm::dvec2(1e7, -1e7), 1e6}}) {
            SeaQuery q;
            ASSERT_TRUE(q.init(ocean, {.fields = SeaField::All}).ok());
            ASSERT_TRUE(q.update(t).ok());
            const std::vector<glm::dvec2> points = randomPoints(300, origin, 2000.0);
            std::vector<SeaSample> out(points.size());
            ASSERT_TRUE(q.sample(points, out, SeaField::All).ok());
            for (size_t i = 0; i < points.size(); ++i) {
                SCOPED_TRACE(std::string(toString(model)) + " point " + std::to_string(i));
                glm::dvec3 d;
                const glm::dvec2 x0 = ocean.surface->lagrangianPointAt(points[i], t, &d);
                EXPECT_EQ(out[i].height, ocean.surface->heightAt(points[i], t));
                EXPECT_EQ(out[i].normal, ocean.surface->normalAt(x0, t));
                EXPECT_EQ(out[i].displacement, glm::dvec2(d));
                EXPECT_LT(glm::length(x0 + out[i].displacement - points[i]), 1e-8); // the image is the point
                EXPECT_EQ(out[i].velocity, ocean.surface->velocityAt(x0, t));
            }
        }
    }
}

TEST(SeaQuery, FftSampledPathStaysWithinItsBoundOfTheDirectSumNearAndFar) {
    const OceanComponent ocean = makeSea(SurfaceKind::Fft);
    const double hs = ocean.surface->significantWaveHeight();
    for (const auto& [origin, t] :
         {std::pair{glm::dvec2(0.0), 12.5}, std::pair{glm::dvec2(1e7, -1e7), 1e6}}) {
        SeaQuery sampled = makeQuery(ocean, t, {.fields = SeaField::All});
        SeaQuery direct = makeQuery(ocean, t, {.fields = SeaField::All, .fftDirectSum = true});
        const std::vector<glm::dvec2> points = randomPoints(12, origin, 3000.0);
        std::vector<SeaSample> a(points.size()), b(points.size());
        ASSERT_TRUE(sampled.sample(points, a, SeaField::All).ok());
        ASSERT_TRUE(direct.sample(points, b, SeaField::All).ok());
        for (size_t i = 0; i < points.size(); ++i) {
            SCOPED_TRACE("point " + std::to_string(i) + " at t = " + std::to_string(t));
            EXPECT_EQ(b[i].height, ocean.surface->heightAt(points[i], t)); // the direct path is the model's
            // Bicubic: RMS 2.8 mm, max 10.6 mm over 20 000 points at this Hs (docs/ACCURACY.md).
            EXPECT_LT(std::abs(a[i].height - b[i].height), 0.006 * hs);
            EXPECT_LT(glm::length(a[i].displacement - b[i].displacement), 0.006 * hs);
            // The normal from the interpolant's slopes: the finest cascade's waves near its Nyquist (0.5 m
            // long) are the slopes' largest part and the interpolant's derivative is poorest there: measured
            // 0.3-2.4 degrees here (docs/ACCURACY.md).
            EXPECT_GT(glm::dot(a[i].normal, b[i].normal), std::cos(3.0 * M_PI / 180.0));
            // The velocity likewise (the short waves are the fastest for their height): measured up to 0.028
            // m/s of an RMS dh/dt of 0.89 m/s.
            EXPECT_LT(glm::length(a[i].velocity - b[i].velocity), 0.05);
        }
    }
}

TEST(SeaQuery, VelocityNormalAndHeightObeyTheKinematicSurfaceCondition) {
    // A surface point moves with the water: dh/dt at a fixed world point = w - u dh/dx - v dh/dy, with
    // grad h = -(n_x, n_y) / n_z. Checks the velocity against the heights' change and the normal.
    for (SurfaceKind model : {SurfaceKind::Gerstner, SurfaceKind::Fft, SurfaceKind::Octaves}) {
        const OceanComponent ocean = makeSea(model);
        const double t = 20.0, dt = 1e-3;
        SeaQuery q = makeQuery(ocean, t, {.fields = SeaField::All});
        const std::vector<glm::dvec2> points = randomPoints(400, {300.0, -200.0}, 1500.0);
        std::vector<SeaSample> now(points.size());
        std::vector<double> before(points.size()), after(points.size());
        ASSERT_TRUE(q.sample(points, now, SeaField::All).ok());
        ASSERT_TRUE(q.update(t - dt).ok());
        ASSERT_TRUE(q.heights(points, before).ok());
        ASSERT_TRUE(q.update(t + dt).ok());
        ASSERT_TRUE(q.heights(points, after).ok());
        double residual2 = 0.0, rate2 = 0.0;
        for (size_t i = 0; i < points.size(); ++i) {
            const double rate = (after[i] - before[i]) / (2.0 * dt);
            const glm::dvec3 n = now[i].normal, v = now[i].velocity;
            const double expected = v.z + (v.x * n.x + v.y * n.y) / n.z;
            residual2 += (rate - expected) * (rate - expected);
            rate2 += rate * rate;
        }
        const double relative = std::sqrt(residual2 / rate2);
        std::printf("%s: RMS dh/dt %.4f m/s, kinematic residual %.2e of it\n", toString(model),
                    std::sqrt(rate2 / points.size()), relative);
        EXPECT_GT(rate2 / points.size(), 1e-4); // the sea moves
        // Measured: Gerstner 2e-7, octaves 0 (no horizontal motion), FFT 1.6e-2 (the normal leaves out the
        // aperiodic mix's own gradient, as the GPU's does).
        EXPECT_LT(relative, model == SurfaceKind::Fft ? 0.05 : 1e-4) << toString(model);
    }
}

TEST(SeaQuery, EffectsAddTheirHeightSlopesAndRate) {
    const OceanComponent ocean = makeSea(SurfaceKind::Gerstner);
    Explosion e;
    e.center = {120.0, 40.0};
    e.startTime = 10.0;
    e.strength = 1.0;
    e.params = explosionParams(1.0);
    const std::vector<Explosion> explosions{e};
    const EffectsView effects{explosions, {}};
    const double t = 16.0;
    SeaQuery with = makeQuery(ocean, t, {.fields = SeaField::All}, effects);
    SeaQuery without = makeQuery(ocean, t, {.fields = SeaField::All});
    const std::vector<glm::dvec2> points = randomPoints(200, e.center, 60.0);
    std::vector<SeaSample> a(points.size()), b(points.size());
    ASSERT_TRUE(with.sample(points, a, SeaField::All).ok());
    ASSERT_TRUE(without.sample(points, b, SeaField::All).ok());
    double largest = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3 f = effectsAt(effects, points[i], t);
        largest = std::max(largest, std::abs(f.x));
        EXPECT_DOUBLE_EQ(a[i].height, b[i].height + f.x);
        EXPECT_EQ(a[i].displacement, b[i].displacement);
        // The slopes add: grad h = -(n_x, n_y) / n_z.
        const glm::dvec2 slopeA = -glm::dvec2(a[i].normal) / a[i].normal.z;
        const glm::dvec2 slopeB = -glm::dvec2(b[i].normal) / b[i].normal.z;
        EXPECT_NEAR(slopeA.x, slopeB.x + f.y, 1e-9);
        EXPECT_NEAR(slopeA.y, slopeB.y + f.z, 1e-9);
        const double rate =
            (effectsAt(effects, points[i], t + 1e-3).x - effectsAt(effects, points[i], t - 1e-3).x) / 2e-3;
        EXPECT_NEAR(a[i].velocity.z, b[i].velocity.z + rate, 1e-9);
    }
    EXPECT_GT(largest, 0.1); // the explosion is there
}

TEST(SeaQuery, TheThreadCountChangesNoBit) {
    for (SurfaceKind model : {SurfaceKind::Octaves, SurfaceKind::Gerstner, SurfaceKind::Fft}) {
        const OceanComponent ocean = makeSea(model);
        const std::vector<glm::dvec2> points = randomPoints(5000, {-4e6, 2e6}, 4000.0);
        std::vector<SeaSample> one(points.size()), three(points.size());
        SeaQuery a = makeQuery(ocean, 99.25, {.fields = SeaField::All, .threads = 1});
        SeaQuery b = makeQuery(ocean, 99.25, {.fields = SeaField::All, .threads = 3, .pointsPerJob = 97});
        ASSERT_TRUE(a.sample(points, one, SeaField::All).ok());
        ASSERT_TRUE(b.sample(points, three, SeaField::All).ok());
        EXPECT_EQ(std::memcmp(one.data(), three.data(), one.size() * sizeof(SeaSample)), 0)
            << toString(model);
    }
}

TEST(SeaQuery, NoAllocationOnceWarm) {
    for (SurfaceKind model : {SurfaceKind::Octaves, SurfaceKind::Gerstner, SurfaceKind::Fft}) {
        const OceanComponent ocean = makeSea(model);
        const std::vector<glm::dvec2> points = randomPoints(3000, {0.0, 0.0}, 4000.0);
        std::vector<SeaSample> out(points.size());
        std::vector<double> heights(points.size());
        SeaQuery q = makeQuery(ocean, 5.0, {.fields = SeaField::All, .threads = 2, .pointsPerJob = 100});
        ASSERT_TRUE(q.sample(points, out, SeaField::All).ok()); // warm
        const long before = gAllocations.load();
        for (int step = 1; step <= 3; ++step) {
            const Status u = q.update(5.0 + step / 60.0);
            const Status s = q.sample(points, out, SeaField::All);
            const Status h = q.heights(points, heights);
            EXPECT_TRUE(u.ok() && s.ok() && h.ok());
        }
        EXPECT_EQ(gAllocations.load() - before, 0) << toString(model);
    }
}

TEST(SeaQuery, HardCasesZeroManyAndNaNPoints) {
    const OceanComponent ocean = makeSea(SurfaceKind::Octaves);
    SeaQuery q = makeQuery(ocean, 3.0, {.fields = SeaField::Height | SeaField::Normal, .threads = 0});
    EXPECT_TRUE(q.sample({}, {}, SeaField::Height).ok()); // 0 points
    EXPECT_TRUE(q.heights({}, {}).ok());
    const std::vector<glm::dvec2> many = randomPoints(1000000, {0.0, 0.0}, 20000.0);
    std::vector<double> h(many.size(), NAN);
    ASSERT_TRUE(q.heights(many, h).ok());
    const double hs = ocean.surface->significantWaveHeight();
    for (size_t i = 0; i < many.size(); i += 997)
        EXPECT_EQ(h[i], ocean.surface->heightAt(many[i], 3.0));
    size_t finite = 0;
    for (double v : h)
        finite += std::isfinite(v) && std::abs(v) < 4.0 * hs;
    EXPECT_EQ(finite, many.size());
    EXPECT_EQ(q.counters().points, many.size());

    std::vector<glm::dvec2> some = randomPoints(100, {0.0, 0.0}, 500.0);
    some[7].x = NAN;
    some[40].y = INFINITY;
    some[93] = glm::dvec2(NAN);
    std::vector<SeaSample> out(some.size());
    const Status s = q.sample(some, out, SeaField::Height | SeaField::Normal);
    EXPECT_EQ(s.code, ErrorCode::InvalidArgument);
    EXPECT_NE(s.message.find("3 of 100 points are not finite (the first: points[7])"), std::string::npos)
        << s.message;
    for (size_t i = 0; i < some.size(); ++i) {
        const bool bad = i == 7 || i == 40 || i == 93;
        EXPECT_EQ(std::isnan(out[i].height), bad) << i;
        EXPECT_EQ(std::isnan(out[i].normal.z), bad) << i;
        if (!bad) {
            EXPECT_EQ(out[i].height, ocean.surface->heightAt(some[i], 3.0));
        }
    }
    EXPECT_EQ(q.counters().rejected, 3u);

    // One job for any count (pointsPerJob at its largest: no overflow in the job count).
    SeaQuery whole = makeQuery(ocean, 3.0, {.fields = SeaField::Height, .pointsPerJob = SIZE_MAX});
    std::vector<double> w(some.size(), NAN);
    some[7] = some[40] = some[93] = glm::dvec2(0.0);
    ASSERT_TRUE(whole.heights(some, w).ok());
    EXPECT_EQ(w[50], ocean.surface->heightAt(some[50], 3.0));
    EXPECT_EQ(whole.counters().points, some.size());
}

TEST(SeaQuery, UnderACrestAtTheSteepnessLimit) {
    // One Gerstner wave with Q = 1: the crest is a cusp where the horizontal map's Jacobian reaches 0, the
    // hardest point for the Eulerian solve. Along a line across the crests every answer is finite, the
    // normals are unit, and the highest height found is the crest's, A.
    OceanDesc desc;
    desc.model = SurfaceKind::Gerstner;
    desc.gerstner.waves = {GerstnerWave{1.5, 40.0, 90.0, 1.0, 0.3}};
    OceanComponent ocean;
    ASSERT_TRUE(makeOcean(desc, ocean).ok());
    SeaQuery q = makeQuery(ocean, 1e6, {.fields = SeaField::All});
    std::vector<glm::dvec2> line(4001);
    for (size_t i = 0; i < line.size(); ++i)
        line[i] = glm::dvec2(1e7 + 0.01 * static_cast<double>(i), 5.0); // 40 m: one wavelength, 1 cm apart
    std::vector<SeaSample> out(line.size());
    ASSERT_TRUE(q.sample(line, out, SeaField::All).ok());
    double highest = -1e9;
    for (const SeaSample& s : out) {
        ASSERT_TRUE(std::isfinite(s.height) && std::isfinite(s.velocity.x) &&
                    std::isfinite(s.displacement.x));
        EXPECT_NEAR(glm::length(s.normal), 1.0, 1e-12);
        highest = std::max(highest, s.height);
    }
    EXPECT_NEAR(highest, 1.5, 0.01);
}

TEST(SeaQuery, BadCallsAreRefusedWithAMessage) {
    SeaQuery q;
    std::vector<glm::dvec2> points(4);
    std::vector<double> heights(4);
    EXPECT_EQ(q.heights(points, heights).code, ErrorCode::InvalidArgument); // no init
    EXPECT_EQ(q.init(OceanComponent{}).code, ErrorCode::InvalidArgument);   // no surface
    const OceanComponent ocean = makeSea(SurfaceKind::Gerstner);
    Status s = q.init(ocean, {.fields = 0});
    EXPECT_NE(s.message.find("SeaQueryDesc.fields"), std::string::npos) << s.message;
    ASSERT_TRUE(q.init(ocean, {.fields = SeaField::Height}).ok());
    s = q.heights(points, heights);
    EXPECT_NE(s.message.find("update() first"), std::string::npos) << s.message;
    s = q.update(NAN);
    EXPECT_NE(s.message.find("time must be finite"), std::string::npos) << s.message;
    ASSERT_TRUE(q.update(1.0).ok());
    std::vector<SeaSample> out(4);
    s = q.sample(points, out, SeaField::Velocity); // not in the desc
    EXPECT_NE(s.message.find("not a non-empty subset"), std::string::npos) << s.message;
    std::vector<double> short3(3);
    s = q.heights(points, short3);
    EXPECT_NE(s.message.find("4 points but 3 heights"), std::string::npos) << s.message;
    EXPECT_TRUE(q.heights(points, heights).ok());
}

TEST(SeaQuery, FftExtrapolatedBetweenTransformsStaysWithinItsBound) {
    // SeaQueryDesc::fftResampleInterval: within it of the last transform the tiles are extrapolated by their
    // time derivative; against tiles transformed at that very time the error grows as a dt^2 / 2.
    const OceanComponent ocean = makeSea(SurfaceKind::Fft);
    const std::vector<glm::dvec2> points = randomPoints(500, {1e7, 1e7}, 2000.0);
    const double t0 = 1e6 + 40.0;
    SeaQuery extrapolated = makeQuery(ocean, t0, {.fields = SeaField::Height, .fftResampleInterval = 0.25});
    std::vector<double> a(points.size()), b(points.size());
    for (double dt : {1.0 / 60.0, 0.1, 0.2}) {
        ASSERT_TRUE(extrapolated.update(t0 + dt).ok());
        ASSERT_TRUE(extrapolated.heights(points, a).ok());
        SeaQuery exact = makeQuery(ocean, t0 + dt, {.fields = SeaField::Height});
        ASSERT_TRUE(exact.heights(points, b).ok());
        double worst = 0.0, sum = 0.0;
        for (size_t i = 0; i < points.size(); ++i) {
            worst = std::max(worst, std::abs(a[i] - b[i]));
            sum += (a[i] - b[i]) * (a[i] - b[i]);
        }
        std::printf("fft extrapolated %.4f s: RMS %.2e m, max %.2e m\n", dt, std::sqrt(sum / points.size()),
                    worst);
        // Measured (Hs 3.63 m): 1/60 s RMS 0.27 mm, max 0.72 mm; 0.1 s 9.3 / 33 mm; 0.2 s 35 / 115 mm (the
        // sea's shortest waves, w ~ 11 rad/s, bend fastest).
        const double bound = dt < 0.05 ? 0.002 : dt < 0.15 ? 0.05 : 0.2;
        EXPECT_LT(worst, bound) << dt;
        EXPECT_LT(std::sqrt(sum / points.size()), bound / 3.0) << dt;
    }
    // Past the interval it transforms again: the same bits as a fresh query.
    ASSERT_TRUE(extrapolated.update(t0 + 0.3).ok());
    ASSERT_TRUE(extrapolated.heights(points, a).ok());
    SeaQuery exact = makeQuery(ocean, t0 + 0.3, {.fields = SeaField::Height});
    ASSERT_TRUE(exact.heights(points, b).ok());
    EXPECT_EQ(a, b);
}

TEST(SeaQuery, AWakeIsInTheAnswersBitForBitAndAllocatesNothing) {
    // A ship's Kelvin wake (the costliest effect: its state walks the ship's path) through the query's
    // snapshot of the effects, made once per update(): the same bits as effectsAt() per point, and no
    // allocation per query or per update once warm.
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    const ecs::Entity ship = reg.create();
    reg.emplace<Ship>(ship, Ship{{0.0, 0.0}, 120.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    for (int i = 0; i <= 600; ++i) { // 60 s east at 10 m/s, recorded at 10 Hz
        reg.get<Ship>(ship).position = {static_cast<double>(i), 0.0};
        events.dispatch();
        fx.update(0.1 * i, {0.0, 0.0, 100.0});
    }
    const RegistryEffects gathered(reg);
    const EffectsView effects = gathered.view();
    ASSERT_EQ(effects.wakes.size(), 1u);
    const OceanComponent ocean = makeSea(SurfaceKind::Gerstner);
    const double t = 60.0;
    SeaQuery q = makeQuery(ocean, t, {.fields = SeaField::All, .threads = 2, .pointsPerJob = 64}, effects);
    const std::vector<glm::dvec2> points = randomPoints(1000, {450.0, 0.0}, 150.0);
    std::vector<SeaSample> out(points.size());
    ASSERT_TRUE(q.sample(points, out, SeaField::All).ok());
    double largest = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
        const double e = effectsAt(effects, points[i], t).x;
        largest = std::max(largest, std::abs(e));
        ASSERT_EQ(out[i].height, ocean.surface->heightAt(points[i], t) + e) << i;
    }
    EXPECT_GT(largest, 0.05); // the wake is there
    const long before = gAllocations.load();
    for (int step = 1; step <= 3; ++step) {
        EXPECT_TRUE(q.update(t + step / 60.0, effects).ok());
        EXPECT_TRUE(q.sample(points, out, SeaField::All).ok());
    }
    EXPECT_EQ(gAllocations.load() - before, 0);
}
