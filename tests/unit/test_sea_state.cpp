// SeaState (ocean/SeaState.h): the published anchors, the Gaussian foam coverage against numerical
// integration, and applySeaState() giving every surface model the wind's wave height and the octave sea the
// whitecap coverage of Monahan & O'Muircheartaigh (1980), checked by sampling the CPU surface.
#include "ocean/HeightOctaves.h"
#include "ocean/Lighting.h"
#include "ocean/Ocean.h"
#include "ocean/OceanHost.h"
#include "ocean/SeaState.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

using namespace pacifica::ocean;

TEST(SeaState, PublishedAnchors) {
    EXPECT_NEAR(pmSignificantWaveHeight(10.0), 0.21 * 100.0 / 9.81, 1e-12); // 2.14 m
    EXPECT_NEAR(monahanWhitecapCoverage(10.0), 3.84e-6 * std::pow(10.0, 3.41), 1e-15);
    EXPECT_NEAR(monahanWhitecapCoverage(10.0), 0.00987, 1e-5); // ~1 % at 10 m/s
    EXPECT_NEAR(coxMunkSlopeVariance(10.0), 0.0542, 1e-12);
    EXPECT_DOUBLE_EQ(beaufortWindSpeed(0), 0.25);
    EXPECT_DOUBLE_EQ(beaufortWindSpeed(6), 0.5 * (10.8 + 13.9));
    EXPECT_DOUBLE_EQ(beaufortWindSpeed(12), 32.7);
    EXPECT_THROW(beaufortWindSpeed(13), std::invalid_argument);
    EXPECT_THROW(beaufortWindSpeed(-1), std::invalid_argument);
}

TEST(SeaState, GaussianFoamCoverageMatchesNumericalIntegration) {
    for (double sigma : {0.3, 1.0, 2.5})
        for (double h0 : {-1.0, 0.0, 0.7, 2.0}) {
            const double h1 = h0 + 0.8 * sigma;
            double sum = 0.0;
            const int n = 200000;
            const double lo = -10.0 * sigma, step = 20.0 * sigma / n;
            for (int i = 0; i < n; ++i) {
                const double h = lo + (i + 0.5) * step;
                const double a = std::clamp((h - h0) / (h1 - h0), 0.0, 1.0);
                sum += a * std::exp(-0.5 * h * h / (sigma * sigma)) / (sigma * std::sqrt(2.0 * M_PI)) * step;
            }
            EXPECT_NEAR(gaussianFoamCoverage(sigma, h0, h1), sum, 1e-6) << sigma << " " << h0;
        }
}

TEST(SeaState, EveryModelGetsTheWindsWaveHeight) {
    for (double u : {6.0, 12.0, 20.0}) {
        const OceanDesc d = applySeaState({}, {u, 45.0});
        EXPECT_EQ(d.fft.windSpeed, u);
        EXPECT_EQ(d.fft.windDirectionDeg, 45.0);
        EXPECT_EQ(d.octaves.windDirectionDeg, 45.0);
        // Heights scale as Hs ~ U^2 from the reference wind (the default seas): the displaced octaves'
        // amplitudes. The octave sea gains detail octaves down to SEA_STATE_FINEST_TILE, each
        // SEA_STATE_DETAIL_RATIO finer than the last (their amplitudes set by the slope budget, below).
        const double scale = (u * u) / (SEA_STATE_REFERENCE_WIND * SEA_STATE_REFERENCE_WIND);
        const OceanDesc base;
        ASSERT_EQ(d.octaves.octaves.size(), static_cast<size_t>(SEA_STATE_OCTAVES));
        for (int i = 0; i < base.octaves.displacedOctaves; ++i)
            EXPECT_NEAR(d.octaves.octaves[i].amplitude, base.octaves.octaves[i].amplitude * scale, 1e-12);
        for (size_t i = base.octaves.octaves.size(); i < d.octaves.octaves.size(); ++i) {
            EXPECT_NEAR(d.octaves.octaves[i].tileSize * SEA_STATE_DETAIL_RATIO,
                        d.octaves.octaves[i - 1].tileSize, 1e-9);
            EXPECT_GE(d.octaves.octaves[i].tileSize, SEA_STATE_FINEST_TILE);
        }
        OceanDesc octaves = d, gerstner = d, reference = applySeaState({}, {SEA_STATE_REFERENCE_WIND, 45.0});
        gerstner.model = SurfaceKind::Gerstner;
        reference.model = SurfaceKind::Gerstner;
        EXPECT_NEAR(makeOcean(gerstner).surface->significantWaveHeight() /
                        makeOcean(reference).surface->significantWaveHeight(),
                    scale, 1e-9);
        reference.model = SurfaceKind::Octaves;
        EXPECT_NEAR(makeOcean(octaves).surface->significantWaveHeight() /
                        makeOcean(reference).surface->significantWaveHeight(),
                    scale, 1e-9);
        validateLighting(d.lighting); // the foam thresholds are valid
    }
    EXPECT_THROW(applySeaState({}, {0.0, 0.0}), std::invalid_argument);
    EXPECT_THROW(applySeaState({}, {NAN, 0.0}), std::invalid_argument);
    EXPECT_THROW(applySeaState({}, {12.0, INFINITY}), std::invalid_argument);
}

TEST(SeaState, OctaveSeaFoamCoverageFollowsMonahan) {
    // The thresholds are solved on a low-discrepancy set of the model's heights; 12000 random points and
    // times over 8 km x 8 km must give the Monahan coverage within 35 %, and more wind, more foam.
    double last = 0.0;
    for (double u : {8.0, 12.0, 16.0, 20.0}) {
        const OceanDesc d = applySeaState({}, {u, 60.0});
        const OceanComponent c = makeOcean(d);
        double sum = 0.0;
        int n = 0;
        std::mt19937_64 rng(17);
        std::uniform_real_distribution<double> pos(-4000.0, 4000.0), time(0.0, 100.0);
        for (int k = 0; k < 12000; ++k) {
            const double h = c.surface->foamHeightAt({pos(rng), pos(rng)}, time(rng)); // living whitecaps
            sum += meanFoamOpacity(foamAlpha(h, d.lighting)); // the share the rendered foam covers
            ++n;
        }
        const double coverage = sum / n, w = monahanWhitecapCoverage(u);
        std::printf("U = %4.1f m/s: foam coverage %.5f, Monahan W %.5f (ratio %.3f)\n", u, coverage, w,
                    coverage / w);
        EXPECT_NEAR(coverage / w, 1.0, 0.35) << "U = " << u << ": coverage " << coverage << " vs W " << w;
        EXPECT_GT(coverage, last);
        last = coverage;
    }
}

TEST(SeaState, ModelSlopesPlusMicroSlopesAreCoxAndMunks) {
    // The model's slope variance, sampled at other points and times, plus the sub-model variance the sea
    // state sets, equals Cox & Munk's total within 10 % (where the floor does not bind).
    for (SurfaceKind kind : {SurfaceKind::Octaves, SurfaceKind::Gerstner}) {
        double lastMicro = -1.0;
        for (double u : {6.0, 12.0, 20.0}) {
            OceanDesc base;
            base.model = kind;
            const OceanDesc d = applySeaState(base, {u, 60.0});
            const OceanComponent c = makeOcean(d);
            // The octave sea's slopes as the GPU lights them: per octave over its texels (LEAN's total);
            // bilinear sampling at random points would smooth them (checked below against texel centres).
            const auto* octaves = dynamic_cast<const HeightOctaves*>(c.surface.get());
            std::mt19937_64 rng(5);
            std::uniform_real_distribution<double> pos(-4000.0, 4000.0), time(0.0, 100.0);
            double sx = 0.0, sy = 0.0, ss = 0.0;
            const int n = 6000;
            for (int k = 0; k < n; ++k) {
                const glm::dvec3 nrm = c.surface->normalAt({pos(rng), pos(rng)}, time(rng));
                const double gx = -nrm.x / nrm.z, gy = -nrm.y / nrm.z;
                sx += gx;
                sy += gy;
                ss += gx * gx + gy * gy;
            }
            double model = ss / n - (sx * sx + sy * sy) / (double(n) * n);
            if (octaves) {
                model = 0.0;
                for (int i = 0; i < static_cast<int>(d.octaves.octaves.size()); ++i)
                    model += octaves->octaveSlopeVariance(i);
            }
            const double micro = d.lighting.microSlopeVariance, total = coxMunkSlopeVariance(u);
            std::printf("%s U = %4.1f: model slopes %.4f + micro %.4f = %.4f, Cox-Munk %.4f\n",
                        toString(kind), u, model, micro, model + micro, total);
            if (micro > MIN_MICRO_SLOPE_VARIANCE * 1.01) {
                EXPECT_NEAR((model + micro) / total, 1.0, 0.10) << toString(kind) << " U = " << u;
            } else {
                EXPECT_GE(model + micro, total * 0.9) << toString(kind) << " U = " << u;
            }
            // The octave sea resolves SEA_STATE_RESOLVED_SLOPES of the total in its own octaves (the
            // rest is its BRDF), so near the camera the sun meets facets.
            if (kind == SurfaceKind::Octaves) {
                EXPECT_NEAR(model / total, SEA_STATE_RESOLVED_SLOPES, 0.08) << "U = " << u;
            }
            EXPECT_GE(micro, MIN_MICRO_SLOPE_VARIANCE);
            lastMicro = micro;
        }
        EXPECT_GE(lastMicro, MIN_MICRO_SLOPE_VARIANCE);
    }
}

// HeightOctaves::octaveSlopeVariance against the surface itself: the finest octave's gradient (the sum of
// octaves [0, i] minus [0, i - 1]) at every texel centre of every time slice, where the bilinear sampling is
// the texel, has that variance.
TEST(SeaState, OctaveSlopeVarianceIsTheVarianceOverTexels) {
    const OceanDesc d = applySeaState({}, {9.0, 60.0});
    const OceanComponent c = makeOcean(d);
    const auto* octaves = dynamic_cast<const HeightOctaves*>(c.surface.get());
    ASSERT_NE(octaves, nullptr);
    const int i = static_cast<int>(d.octaves.octaves.size()) - 1;
    const OctaveDesc& o = d.octaves.octaves[static_cast<size_t>(i)];
    const int size = d.octaves.mapSize, frames = d.octaves.frames;
    double sx = 0.0, sy = 0.0, ss = 0.0;
    for (int f = 0; f < frames; ++f)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::dvec2 p = (glm::dvec2(x, y) + 0.5) / double(size) * o.tileSize;
                const double t = (f + 1e-9) / frames * o.loopPeriod;
                const glm::dvec3 g =
                    octaves->heightAndGradient(p, t, i + 1) - octaves->heightAndGradient(p, t, i);
                sx += g.y;
                sy += g.z;
                ss += g.y * g.y + g.z * g.z;
            }
    const double n = double(frames) * size * size;
    const double sampled = ss / n - (sx * sx + sy * sy) / (n * n);
    std::printf("octave %d (%.3f m tile): slope variance over texels %.6f, octaveSlopeVariance %.6f\n", i,
                o.tileSize, sampled, octaves->octaveSlopeVariance(i));
    EXPECT_NEAR(sampled / octaves->octaveSlopeVariance(i), 1.0, 1e-3);
}

TEST(SeaState, BadMicroSlopeVarianceIsRejectedNamingTheField) {
    LightingDesc l;
    for (float bad : {-0.01f, 1.5f, NAN}) {
        l.microSlopeVariance = bad;
        try {
            validateLighting(l);
            ADD_FAILURE() << "accepted " << bad;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("microSlopeVariance"), std::string::npos) << e.what();
        }
    }
}
