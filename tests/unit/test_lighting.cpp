// Unit tests of the shading's CPU side (ocean/include/ocean/Lighting.h), which the shaders mirror: the
// environment-map validation and lat-long convention, the fog optical depth with height falloff against a
// numerical integral, the §18.3 foam alpha, LightingDesc validation, and the procedural textures (range,
// tiling). No GL.
#include "ocean/Lighting.h"
#include "ocean/OceanConstants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <utility>

using namespace pacifica::ocean;

namespace {

std::vector<float> grey(int w, int h, float v = 0.5f) {
    return std::vector<float>(static_cast<size_t>(w) * h * 3, v);
}

/// Composite Simpson's rule of rho0 e^(-z(s)/H) along the straight segment, z linear in s.
double integratedDepth(double z0, double z1, double d, const LightingDesc& l, int intervals = 200000) {
    auto rho = [&](double s) {
        const double z = z0 + (z1 - z0) * s / d;
        return l.fogHeightFalloff > 0.0f ? l.fogDensity * std::exp(-z / l.fogHeightFalloff)
                                         : static_cast<double>(l.fogDensity);
    };
    const double h = d / intervals;
    double sum = rho(0.0) + rho(d);
    for (int i = 1; i < intervals; ++i)
        sum += rho(i * h) * (i % 2 ? 4.0 : 2.0);
    return sum * h / 3.0;
}

LightingDesc fog(double rho0, double scaleHeight) {
    LightingDesc l;
    l.fogDensity = static_cast<float>(rho0);
    l.fogHeightFalloff = static_cast<float>(scaleHeight);
    return l;
}

} // namespace

// ---- environment map ---------------------------------------------------------------------------------

TEST(EnvironmentMap, AcceptsFiniteNonNegativeData) {
    const EnvironmentMap m = makeEnvironmentMap(8, 4, grey(8, 4));
    EXPECT_EQ(m.width, 8);
    EXPECT_EQ(m.height, 4);
    EXPECT_EQ(m.rgb.size(), 8u * 4u * 3u);
    EXPECT_EQ(m.intensity, 1.0f);
}

TEST(EnvironmentMap, NamesTheFirstNanPixel) {
    std::vector<float> rgb = grey(8, 4);
    rgb[(2 * 8 + 5) * 3 + 1] = std::numeric_limits<float>::quiet_NaN(); // x = 5, y = 2, green
    rgb[(3 * 8 + 0) * 3 + 0] = std::numeric_limits<float>::quiet_NaN(); // a later one
    try {
        makeEnvironmentMap(8, 4, rgb);
        FAIL() << "NaN accepted";
    } catch (const EnvironmentMapError& e) {
        EXPECT_STREQ(e.what(), "makeEnvironmentMap(): pixel (5,2) is NaN");
        EXPECT_EQ(e.problem(), "pixel (5,2) is NaN");
        EXPECT_EQ(e.x(), 5);
        EXPECT_EQ(e.y(), 2);
    }
    // It is a std::invalid_argument for callers that do not know the type.
    EXPECT_THROW(makeEnvironmentMap(8, 4, rgb), std::invalid_argument);
}

TEST(EnvironmentMap, RejectsInfinityNegativesAndWrongSizes) {
    std::vector<float> rgb = grey(4, 2);
    rgb[3 * 3 + 2] = std::numeric_limits<float>::infinity();
    EXPECT_THROW(
        try { makeEnvironmentMap(4, 2, rgb); } catch (const EnvironmentMapError& e) {
            EXPECT_EQ(e.problem(), "pixel (3,0) is infinite");
            throw;
        },
        EnvironmentMapError);
    rgb = grey(4, 2);
    rgb[4 * 3] = -0.5f;
    EXPECT_THROW(
        try { makeEnvironmentMap(4, 2, rgb); } catch (const EnvironmentMapError& e) {
            EXPECT_EQ(e.problem(), "pixel (0,1) is negative (-0.5)");
            throw;
        },
        EnvironmentMapError);
    EXPECT_THROW(makeEnvironmentMap(4, 2, grey(4, 3)), EnvironmentMapError);
    EXPECT_THROW(makeEnvironmentMap(0, 2, {}), EnvironmentMapError);
}

TEST(EnvironmentMap, LatLongConvention) {
    // Centre column looks north, u = 0.75 east, the seam (u = 0) south; top row up.
    auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 1e-12; };
    EXPECT_TRUE(near(environmentDirection(0.5, 0.5), {0, 1, 0}));
    EXPECT_TRUE(near(environmentDirection(0.75, 0.5), {1, 0, 0}));
    EXPECT_TRUE(near(environmentDirection(0.25, 0.5), {-1, 0, 0}));
    EXPECT_TRUE(near(environmentDirection(0.0, 0.5), {0, -1, 0}));
    EXPECT_NEAR(environmentDirection(0.3, 0.0).z, 1.0, 1e-12);
    EXPECT_NEAR(environmentDirection(0.3, 1.0).z, -1.0, 1e-12);
    // Round trip away from the poles.
    for (double u : {0.01, 0.2, 0.5, 0.77, 0.99})
        for (double v : {0.05, 0.3, 0.5, 0.9}) {
            const glm::dvec2 uv = environmentUv(environmentDirection(u, v));
            EXPECT_NEAR(uv.x, u, 1e-12);
            EXPECT_NEAR(uv.y, v, 1e-12);
        }
}

TEST(EnvironmentMap, BrightestDirectionFindsTheSun) {
    const int w = 64, h = 32;
    std::vector<float> rgb = grey(w, h, 0.2f);
    const int sx = 40, sy = 10; // heading ~45 deg east of north, elevation ~33.75 deg
    for (int c = 0; c < 3; ++c)
        rgb[(static_cast<size_t>(sy) * w + sx) * 3 + c] = 1000.0f;
    const glm::dvec3 d = environmentBrightestDirection(makeEnvironmentMap(w, h, rgb));
    const glm::dvec3 expected = environmentDirection((sx + 0.5) / w, (sy + 0.5) / h);
    EXPECT_GT(glm::dot(d, expected), std::cos(1e-9 + 1e-6));
}

// ---- fog ---------------------------------------------------------------------------------------------

TEST(Fog, OpticalDepthMatchesTheNumericalIntegral) {
    struct Ray {
        const char* name;
        double z0, z1, d;
    };
    // Horizontal at 0.5 m to 40 km; a steep climb; from 15 km down to the sea at 30 degrees (30 km); a
    // shallow descent from 3 km; and the reverse of the 15 km ray (the formula is symmetric).
    const Ray rays[] = {{"horizontal", 0.5, 0.5, 40000.0},
                        {"steep", 0.5, 3000.0, 3500.0},
                        {"15km_down_30deg", 15000.0, 0.0, 30000.0},
                        {"shallow_descent", 3000.0, 1.0, 60000.0},
                        {"sea_up_to_15km", 0.0, 15000.0, 30000.0}};
    for (const LightingDesc& l : {fog(1.0 / 8000.0, 1000.0), fog(1.0 / 20.0, 6.0), fog(1e-4, 80.0)})
        for (const Ray& r : rays) {
            const double closed = fogOpticalDepth(r.z0, r.z1, r.d, l);
            const double numeric = integratedDepth(r.z0, r.z1, r.d, l);
            EXPECT_NEAR(closed, numeric, 1e-6 * numeric)
                << r.name << " H=" << l.fogHeightFalloff << " rho0=" << l.fogDensity;
        }
}

TEST(Fog, HorizontalLimitAndUniformFog) {
    const LightingDesc l = fog(1.0 / 8000.0, 1000.0);
    // z1 -> z0: rho0 e^(-z0/H) d, continuous across the series/closed-form switch.
    const double limit = l.fogDensity * std::exp(-0.5 / 1000.0) * 40000.0;
    EXPECT_NEAR(fogOpticalDepth(0.5, 0.5, 40000.0, l), limit, 1e-12 * limit);
    const double below = fogOpticalDepth(0.5, 0.5 + 0.0999, 40000.0, l); // delta < 1e-4: series
    const double above = fogOpticalDepth(0.5, 0.5 + 0.1001, 40000.0, l); // delta > 1e-4: expm1
    EXPECT_NEAR(below, above, 1e-6 * limit);
    EXPECT_LT(above, below);
    // H = 0: uniform fog, rho0 d whatever the altitudes.
    const LightingDesc u = fog(1.0 / 8000.0, 0.0);
    EXPECT_DOUBLE_EQ(fogOpticalDepth(15000.0, 0.0, 30000.0, u), 30000.0 * u.fogDensity);
}

TEST(Fog, ThinsWithAltitudeAndNeverOverflows) {
    // A 6 m-deep sea fog: opaque along the surface, nearly transparent looking down from 15 km.
    const LightingDesc l = fog(1.0 / 20.0, 6.0);
    EXPECT_GT(fogOpticalDepth(0.5, 0.5, 200.0, l), 9.0);
    const double fromAbove = fogOpticalDepth(15000.0, 0.0, 30000.0, l);
    EXPECT_NEAR(fromAbove, 0.6, 1e-3); // rho0 H / sin(30 deg)
    // 15 km above a 1 m scale height: e^(-15000) underflows, e^(+15000) would overflow; the result is
    // finite and equals rho0 H d / |dz| (everything comes from the bottom of the path).
    const LightingDesc thin = fog(1.0 / 20.0, 1.0);
    const double t = fogOpticalDepth(15000.0, 0.0, 30000.0, thin);
    EXPECT_TRUE(std::isfinite(t));
    EXPECT_NEAR(t, thin.fogDensity * 1.0 * 2.0, 1e-12);
    EXPECT_EQ(fogOpticalDepth(15000.0, 14000.0, 5000.0, thin), 0.0);
}

// ---- foam --------------------------------------------------------------------------------------------

TEST(Foam, HeightAlphaRampsFromStartToFull) {
    LightingDesc l;
    l.foamHeightStart = 1.0f;
    l.foamHeightFull = 3.0f;
    EXPECT_EQ(foamAlpha(1.0, l), 0.0);
    EXPECT_DOUBLE_EQ(foamAlpha(2.0, l), 0.5);
    EXPECT_DOUBLE_EQ(foamAlpha(2.5, l), 0.75);
    EXPECT_EQ(foamAlpha(3.0, l), 1.0);
    EXPECT_EQ(foamAlpha(10.0, l), 1.0);   // beyond Hmax: clamped
    EXPECT_EQ(foamAlpha(-5.0, l), 0.0);   // below H0
    l.foamHeightFull = l.foamHeightStart; // degenerate: a step (validateLighting rejects it)
    EXPECT_EQ(foamAlpha(0.999, l), 0.0);
    EXPECT_EQ(foamAlpha(1.0, l), 1.0);
}

TEST(Foam, JacobianAlphaIsFullWhereTheSurfaceFolds) {
    LightingDesc l;
    l.foamJacobianThreshold = 0.4f;
    EXPECT_EQ(foamAlphaJacobian(1.0, l), 0.0);
    EXPECT_EQ(foamAlphaJacobian(l.foamJacobianThreshold, l), 0.0); // (the float threshold exactly)
    EXPECT_DOUBLE_EQ(foamAlphaJacobian(0.5 * l.foamJacobianThreshold, l), 0.5);
    EXPECT_EQ(foamAlphaJacobian(0.0, l), 1.0);
    EXPECT_EQ(foamAlphaJacobian(-0.7, l), 1.0);
    l.foamJacobianThreshold = 0.0f;
    EXPECT_EQ(foamAlphaJacobian(-1.0, l), 0.0);
}

// ---- validation --------------------------------------------------------------------------------------

TEST(LightingValidation, NamesTheField) {
    auto message = [](const LightingDesc& l) {
        try {
            validateLighting(l);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_EQ(message(LightingDesc{}), "(accepted)");
    LightingDesc l;
    l.foamHeightFull = l.foamHeightStart - 1.0f;
    EXPECT_NE(message(l).find("OceanDesc.lighting.foamHeightFull"), std::string::npos) << message(l);
    l = {};
    l.waterColor = {0.01f, -0.1f, 0.02f};
    EXPECT_NE(message(l).find("OceanDesc.lighting.waterColor"), std::string::npos) << message(l);
    l = {};
    l.fogNoise = 2.0f;
    EXPECT_NE(message(l).find("OceanDesc.lighting.fogNoise"), std::string::npos) << message(l);
    l = {};
    l.subsurface = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(message(l).find("OceanDesc.lighting.subsurface"), std::string::npos) << message(l);
    l = {};
    l.subsurface = 11.0f;
    EXPECT_NE(message(l).find("OceanDesc.lighting.subsurface"), std::string::npos) << message(l);
    l = {};
    l.fogHeightFalloff = -1.0f;
    EXPECT_NE(message(l).find("OceanDesc.lighting.fogHeightFalloff"), std::string::npos) << message(l);
    l = {};
    l.fogColor = glm::vec3(0.5f, std::nanf(""), 0.5f);
    EXPECT_NE(message(l).find("OceanDesc.lighting.fogColor"), std::string::npos) << message(l);
    l = {};
    l.spotScatterSamples = 65;
    EXPECT_EQ(message(l), "OceanDesc.lighting.spotScatterSamples must be in [0, 64], got 65");
    l.spotScatterSamples = -1;
    EXPECT_NE(message(l).find("OceanDesc.lighting.spotScatterSamples"), std::string::npos) << message(l);
    l = {};
    auto bad = std::make_shared<EnvironmentMap>();
    bad->width = 4; // no data: not from makeEnvironmentMap()
    bad->height = 2;
    l.environment = bad;
    EXPECT_NE(message(l).find("OceanDesc.lighting.environment"), std::string::npos) << message(l);
}

// ---- procedural textures -----------------------------------------------------------------------------

TEST(ProceduralTextures, FogNoiseIsInRangeAndTiles) {
    const int n = 32;
    const std::vector<float> v = makeFogNoise(n);
    ASSERT_EQ(v.size(), static_cast<size_t>(n) * n * n);
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    EXPECT_EQ(*lo, 0.0f);
    EXPECT_EQ(*hi, 1.0f);
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    EXPECT_NEAR(mean, 0.5, 0.1);
    // Tiling: the step across the wrap (x = n-1 -> 0) is no larger than the largest step inside.
    auto at = [&](int x, int y, int z) { return v[(static_cast<size_t>(z) * n + y) * n + x]; };
    double inside = 0.0, across = 0.0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x + 1 < n; ++x)
                inside = std::max(inside, double(std::abs(at(x + 1, y, z) - at(x, y, z))));
            across = std::max(across, double(std::abs(at(0, y, z) - at(n - 1, y, z))));
            across = std::max(across, double(std::abs(at(y, 0, z) - at(y, n - 1, z))));
            across = std::max(across, double(std::abs(at(y, z, 0) - at(y, z, n - 1))));
        }
    EXPECT_LE(across, inside * 1.25) << "seam at the wrap";
    EXPECT_LT(inside, 0.2); // smooth (blurred)
}

namespace {

/// Autocorrelation of a size x size periodic field at a lag of `lag` texels along x and along y.
std::pair<double, double> autocorrelation(const std::vector<float>& v, int n, int lag) {
    auto at = [&](int x, int y) { return double(v[static_cast<size_t>((y + n) % n) * n + (x + n) % n]); };
    double along = 0.0, across = 0.0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            along += at(x, y) * at(x + lag, y) / (n * n);
            across += at(x, y) * at(x, y + lag) / (n * n);
        }
    return {along, across};
}

/// The foam patterns' shared contract: a standard normal sample (its sorted values are the normal quantiles
/// of the ranks) that tiles without a seam.
void expectNormalAndTiling(const std::vector<float>& v, int n) {
    ASSERT_EQ(v.size(), static_cast<size_t>(n) * n);
    std::vector<float> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    for (size_t k = 0; k < sorted.size(); ++k)
        ASSERT_FLOAT_EQ(sorted[k], static_cast<float>(normalQuantile((k + 0.5) / static_cast<double>(n * n))))
            << k;
    double mean = 0.0, var = 0.0;
    for (float x : v)
        mean += x / static_cast<double>(v.size());
    for (float x : v)
        var += (x - mean) * (x - mean) / static_cast<double>(v.size());
    EXPECT_NEAR(mean, 0.0, 1e-6);
    EXPECT_NEAR(var, 1.0, 0.01);
    auto at = [&](int x, int y) { return double(v[static_cast<size_t>(y) * n + x]); };
    double inside = 0.0, seam = 0.0;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x + 1 < n; ++x) // steps along both axes: across the streaks they are larger
            inside = std::max({inside, std::abs(at(x + 1, y) - at(x, y)), std::abs(at(y, x + 1) - at(y, x))});
        seam = std::max(seam, std::abs(at(0, y) - at(n - 1, y)));
        seam = std::max(seam, std::abs(at(y, 0) - at(y, n - 1)));
    }
    EXPECT_LE(seam, inside) << "seam at the wrap";
}

} // namespace

// The fine foam layer (lace and bubbles) and the coarse one (streaks) are standard normal and tile; the
// streaks lie along x: at a lag of 8 texels they correlate > 0.6 along x and at least 0.4 less across.
TEST(ProceduralTextures, FoamPatternsAreNormalTileAndStreakAlongTheWind) {
    const int n = 128;
    expectNormalAndTiling(makeFoamPattern(n), n);
    const std::vector<float> streaks = makeFoamStreaks(n);
    expectNormalAndTiling(streaks, n);
    const auto [along, across] = autocorrelation(streaks, n, 8);
    std::printf("streaks' autocorrelation at 8 texels: along %.3f, across %.3f\n", along, across);
    EXPECT_GT(along, 0.6);
    EXPECT_LT(across, along - 0.4);
}

// normalCdf and normalQuantile against std::erfc and each other: within the published bounds (1.5e-7 for
// A&S 7.1.26; Giles' single-precision erfinv ~ 1e-6 relative here).
TEST(ProceduralTextures, NormalCdfAndQuantileMatchTheNormal) {
    double worst = 0.0;
    for (int i = -800; i <= 800; ++i) {
        const double x = i / 100.0;
        worst = std::max(worst, std::abs(normalCdf(x) - 0.5 * std::erfc(-x / std::sqrt(2.0))));
    }
    EXPECT_LT(worst, 2e-7);
    EXPECT_NEAR(normalCdf(0.0), 0.5, 1e-9);
    for (double p : {1e-5, 1e-4, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.9999, 1.0 - 1e-5}) {
        const double x = normalQuantile(p);
        EXPECT_NEAR(0.5 * std::erfc(-x / std::sqrt(2.0)), p, 2e-6 * std::max(p, 1e-3)) << "p = " << p;
    }
    EXPECT_NEAR(normalQuantile(0.975), 1.959964, 1e-5);
    EXPECT_EQ(normalQuantile(0.0), normalQuantile(FOAM_SHARE_MIN)); // clamped, finite
    EXPECT_TRUE(std::isfinite(normalQuantile(1.0)));
}

// foamCover keeps the share at every footprint and softness: a standard normal field split into a resolved
// part of variance v (the pixels' means, normal) and an unresolved part 1 - v gives mean opacity = share;
// a sharp pixel (variance 0) is a step at the threshold; no share is no foam, a full share solid foam.
TEST(ProceduralTextures, FoamCoverKeepsTheShareAtEveryFootprint) {
    for (double softness : {0.0, FOAM_EFFECT_SOFTNESS})
        for (double share : {0.01, 0.05, 0.2, 0.5, 0.9})
            for (double resolved : {0.0, 0.3, 0.7, 0.95, 1.0}) {
                double sum = 0.0;
                constexpr int R = 20000;
                for (int k = 0; k < R; ++k) {
                    const double mean = std::sqrt(resolved) * normalQuantile((k + 0.5) / R);
                    sum += foamCover(mean, 1.0 - resolved, share, softness);
                }
                EXPECT_NEAR(sum / R, share, 2e-3 + 0.02 * share)
                    << "share " << share << ", resolved " << resolved << ", softness " << softness;
            }
    // Softer: a resolved pixel just above the threshold is less than solid foam.
    EXPECT_LT(foamCover(normalQuantile(0.9) + 0.3, 0.0, 0.1, FOAM_EFFECT_SOFTNESS), 0.9);
    const double t = normalQuantile(0.9); // the threshold of a 10 % share
    EXPECT_GT(foamCover(t + 0.05, 0.0, 0.1), 0.99);
    EXPECT_LT(foamCover(t - 0.05, 0.0, 0.1), 0.01);
    EXPECT_EQ(foamCover(5.0, 1.0, 0.0), 0.0);
    EXPECT_EQ(foamCover(-5.0, 1.0, 1.0), 1.0);
}

// meanFoamOpacity is the mean of ocean.frag's threshold clamp((r - 1 + c (1 + e)) / e, 0, 1) over uniform
// ranks r: checked against a numerical mean over 100 000 ranks, and it runs from 0 (no coverage: no foam)
// to 1, increasing.
TEST(ProceduralTextures, MeanFoamOpacityIsTheThresholdsMeanOverRanks) {
    double last = -1.0;
    for (int i = 0; i <= 40; ++i) {
        const double c = i / 40.0;
        double sum = 0.0;
        constexpr int R = 100000;
        for (int k = 0; k < R; ++k) {
            const double r = (k + 0.5) / R;
            sum += std::clamp((r - 1.0 + c * (1.0 + FOAM_EDGE)) / FOAM_EDGE, 0.0, 1.0);
        }
        EXPECT_NEAR(meanFoamOpacity(c), sum / R, 1e-6) << "c = " << c;
        EXPECT_GT(meanFoamOpacity(c), last);
        last = meanFoamOpacity(c);
    }
    EXPECT_EQ(meanFoamOpacity(0.0), 0.0);
    EXPECT_DOUBLE_EQ(meanFoamOpacity(1.0), 1.0);
}

// Spot lights (Lighting.h SpotLight): the seed's falloff saturate(|theta_f / theta| - 1) at its landmarks,
// its limit on the axis (theta = 0, where the seed's expression is undefined), the inverse square law with
// its range window, and bad spots named by field.
TEST(SpotLight, FalloffFollowsTheSeedAndIsFiniteOnTheAxis) {
    const double f = 20.0 * std::numbers::pi / 180.0;
    EXPECT_DOUBLE_EQ(spotFalloff(0.0, f), 1.0); // on the axis: the limit, not inf or NaN
    EXPECT_DOUBLE_EQ(spotFalloff(1e-30, f), 1.0);
    EXPECT_DOUBLE_EQ(spotFalloff(0.25 * f, f), 1.0); // the seed's 3, saturated
    EXPECT_DOUBLE_EQ(spotFalloff(0.5 * f, f), 1.0);
    EXPECT_NEAR(spotFalloff(0.75 * f, f), 1.0 / 3.0, 1e-15);
    EXPECT_DOUBLE_EQ(spotFalloff(f, f), 0.0);
    EXPECT_DOUBLE_EQ(spotFalloff(1.5 * f, f), 0.0);
}

TEST(SpotLight, IrradianceIsTheInverseSquareInsideTheCone) {
    SpotLight s;
    s.position = {1e7, -1e7, 25.0}; // far from the origin: the maths is relative
    s.direction = {0.0, 0.0, -2.0}; // normalised on use
    s.frustumDeg = 20.0;
    s.color = {1.0f, 0.5f, 0.25f};
    s.intensity = 2.0e4f;
    s.range = 5000.0;
    const glm::dvec3 below = s.position - glm::dvec3(0.0, 0.0, 25.0);
    const double q = 25.0 / 5000.0, window = (1.0 - q * q * q * q) * (1.0 - q * q * q * q);
    const glm::dvec3 e = spotIrradiance(s, below); // theta = 0 exactly
    EXPECT_NEAR(e.x, 2.0e4 / 625.0 * window, 1e-9);
    EXPECT_NEAR(e.y, 0.5 * e.x, 1e-12);
    // 25 tan(15 deg) off the axis: theta = 15 deg, falloff 20 / 15 - 1 = 1/3, distance 25 / cos(15 deg).
    const double t = 15.0 * std::numbers::pi / 180.0, d = 25.0 / std::cos(t);
    const glm::dvec3 off = below + glm::dvec3(25.0 * std::tan(t), 0.0, 0.0);
    const double qo = d / 5000.0, wo = (1.0 - qo * qo * qo * qo) * (1.0 - qo * qo * qo * qo);
    EXPECT_NEAR(spotIrradiance(s, off).x, 2.0e4 / (d * d) * wo / 3.0, 1e-8); // 1e7 m from the origin
    // Outside the cone, beyond the range, behind the lamp: nothing. At the lamp itself: finite.
    EXPECT_EQ(spotIrradiance(s, below + glm::dvec3(25.0 * std::tan(0.4), 0.0, 0.0)).x, 0.0);
    s.range = 20.0;
    EXPECT_EQ(spotIrradiance(s, below).x, 0.0);
    s.range = 5000.0;
    EXPECT_EQ(spotIrradiance(s, s.position + glm::dvec3(0.0, 0.0, 10.0)).x, 0.0);
    const glm::dvec3 at = spotIrradiance(s, s.position);
    EXPECT_TRUE(std::isfinite(at.x));
    EXPECT_NEAR(at.x, 2.0e4 / (SPOT_MIN_DISTANCE * SPOT_MIN_DISTANCE), 1e-6);
}

TEST(SpotLight, BadSpotsAreNamedByField) {
    auto message = [](const SpotLight& s) {
        try {
            validateSpotLight(s, 3);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(message(SpotLight{}), "accepted");
    SpotLight s;
    s.position.y = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(message(s), "spots[3].position must be finite");
    s = {};
    s.direction = glm::dvec3(0.0);
    EXPECT_EQ(message(s), "spots[3].direction must be finite and non-zero");
    s = {};
    s.frustumDeg = 0.0;
    EXPECT_EQ(message(s), "spots[3].frustumDeg must be in (0, 90], got 0.000000");
    s.frustumDeg = 120.0;
    EXPECT_EQ(message(s), "spots[3].frustumDeg must be in (0, 90], got 120.000000");
    s = {};
    s.color.g = -1.0f;
    EXPECT_EQ(message(s), "spots[3].color must be finite and >= 0");
    s = {};
    s.intensity = std::numeric_limits<float>::infinity();
    EXPECT_EQ(message(s), "spots[3].intensity must be finite and >= 0");
    s = {};
    s.range = 0.0;
    EXPECT_EQ(message(s), "spots[3].range must be finite and > 0");
    // Finite colour and intensity whose float product would overflow in the shader (then NaN at 0 x inf).
    s = {};
    s.color = glm::vec3(1e30f, 0.0f, 0.0f);
    s.intensity = 1e30f;
    EXPECT_EQ(message(s).rfind("spots[3].color x intensity must be <= 1e12, got ", 0), 0u) << message(s);
    s.color = glm::vec3(0.5f, 1e9f, 1.0f);
    s.intensity = 1e3f; // 1e12 on the brightest channel: the bound itself
    EXPECT_EQ(message(s), "accepted");
    s.intensity = 2e3f;
    EXPECT_EQ(message(s), "spots[3].color x intensity must be <= 1e12, got 2000000000000.000000");
}

namespace {

/// Whether p lies in the spot's cone and range (the definition spotConeInterval narrows a ray to).
bool inSpotCone(const SpotLight& s, const glm::dvec3& p) {
    const glm::dvec3 w = p - s.position;
    const double d = glm::length(w);
    return d < s.range &&
           glm::dot(w, glm::normalize(s.direction)) >= d * std::cos(s.frustumDeg * std::numbers::pi / 180.0);
}

} // namespace

// The ray's part in a cone against a fine march along it, for rays of every kind: from outside across the
// cone, from inside, from the apex, along the axis, along the cone's surface, against a 90-degree cone (a
// half-space), missing it, and 1e7 m from the origin.
TEST(SpotLight, ConeIntervalMatchesAMarch) {
    struct Case {
        const char* name;
        glm::dvec3 lamp, axis;
        double frustumDeg;
        glm::dvec3 origin, dir;
        double tMax;
    };
    const double c20 = std::cos(20.0 * std::numbers::pi / 180.0),
                 s20 = std::sin(20.0 * std::numbers::pi / 180.0);
    const Case cases[] = {
        {"across", {0, 0, 20}, {0, 0, -1}, 20.0, {-100, 0, 10}, {1, 0, 0}, 400.0},
        {"from inside",
         {0, 0, 20},
         {0, 0, -1},
         20.0,
         {0, 0, 5},
         glm::normalize(glm::dvec3(1, 0.3, 0.2)),
         400.0},
        {"from the apex",
         {0, 0, 20},
         {0, 0, -1},
         20.0,
         {0, 0, 20},
         glm::normalize(glm::dvec3(0.1, 0, -1)),
         400.0},
        {"along the axis", {0, 0, 20}, {0, 0, -1}, 20.0, {0, 0, 100}, {0, 0, -1}, 400.0},
        {"along the surface", {0, 0, 20}, {0, 0, -1}, 20.0, {0, 0, 20}, {s20, 0, -c20}, 400.0},
        {"half-space",
         {0, 0, 20},
         {1, 0, 0},
         90.0,
         {-50, 3, 0},
         glm::normalize(glm::dvec3(1, 0.2, 0.1)),
         400.0},
        {"missing", {0, 0, 20}, {0, 0, -1}, 20.0, {-100, 0, 30}, {1, 0, 0}, 400.0},
        {"behind the lamp", {0, 0, 20}, {0, 0, -1}, 20.0, {0, 0, 40}, {0, 0, 1}, 400.0},
        {"far from the origin",
         {1e7, -1e7, 20},
         glm::normalize(glm::dvec3(1, 0, 0.2)),
         10.0,
         {1e7 - 300, -1e7 + 40, 5},
         glm::normalize(glm::dvec3(1, -0.1, 0.05)),
         3000.0},
    };
    for (const Case& k : cases) {
        SCOPED_TRACE(k.name);
        SpotLight s;
        s.position = k.lamp;
        s.direction = k.axis;
        s.frustumDeg = k.frustumDeg;
        s.range = 1000.0;
        double t0 = 0.0, t1 = k.tMax;
        const bool hit = spotConeInterval(s, k.origin, k.dir, t0, t1);
        const int steps = 200000;
        const double dt = k.tMax / steps;
        double first = -1.0, last = -1.0;
        for (int i = 0; i <= steps; ++i) {
            const double t = i * dt;
            if (inSpotCone(s, k.origin + t * k.dir)) {
                if (first < 0.0)
                    first = t;
                last = t;
            }
        }
        if (first < 0.0 || last - first < 4.0 * dt) { // none (or a graze thinner than the march resolves)
            EXPECT_TRUE(!hit || t1 - t0 < 4.0 * dt) << t0 << ".." << t1;
            continue;
        }
        ASSERT_TRUE(hit);
        EXPECT_NEAR(t0, first, 2.0 * dt + 1e-6 * k.tMax);
        EXPECT_NEAR(t1, last, 2.0 * dt + 1e-6 * k.tMax);
    }
}

// The beams' quadrature (spotInScatter) against the trapezoid rule over 2e5 even steps in t, for a beam seen
// from the side, a ray up its axis from inside the fog, and a ray passing 1 m from the lamp: the error of
// each sample count (LightingDesc::spotScatterSamples), and the hard cases finite.
TEST(SpotLight, InScatterQuadratureConvergesToTheIntegral) {
    LightingDesc fog;
    fog.fogDensity = 2e-3f;
    fog.fogHeightFalloff = 600.0f;
    SpotLight s;
    s.position = {0.0, 0.0, 20.0};
    s.direction = glm::normalize(glm::dvec3(0.0, 1.0, 0.3));
    s.frustumDeg = 8.0;
    s.range = 3000.0;
    auto reference = [&](const glm::dvec3& eye, const glm::dvec3& dir, double tMax) {
        const int steps = 200000;
        double sum = 0.0;
        const double dt = tMax / steps;
        const glm::dvec3 axis = glm::normalize(s.direction);
        const double g = SPOT_FOG_PHASE_G;
        for (int i = 0; i <= steps; ++i) {
            const double t = i * dt;
            const glm::dvec3 x = eye + t * dir;
            const glm::dvec3 toX = x - s.position;
            const double d = glm::length(toX);
            if (!inSpotCone(s, x))
                continue;
            const glm::dvec3 l = toX / d;
            const double theta = std::acos(std::clamp(glm::dot(axis, l), -1.0, 1.0));
            const double hg = 1.0 + g * g - 2.0 * g * glm::dot(l, -dir);
            const double phase = (1.0 - g * g) / (4.0 * std::numbers::pi * hg * std::sqrt(hg));
            const double q = d / s.range, window = (1.0 - q * q * q * q) * (1.0 - q * q * q * q);
            const double tau =
                fogOpticalDepth(eye.z, x.z, t, fog) + fogOpticalDepth(s.position.z, x.z, d, fog);
            const double r = std::max(d, SPOT_MIN_DISTANCE);
            sum += (i == 0 || i == steps ? 0.5 : 1.0) * fog.fogDensity * std::exp(-x.z / 600.0) * phase *
                   spotFalloff(theta, 8.0 * std::numbers::pi / 180.0) * window * std::exp(-tau) / (r * r);
        }
        return SUN_DIFFUSE_SCALE * s.intensity * sum * dt;
    };
    struct Ray {
        const char* name;
        glm::dvec3 eye, dir;
        double tMax;
        double bound8; // relative error allowed with 8 samples (measured 0.75 %, 0.28 %, 1.1 %)
    };
    const Ray rays[] = {
        {"from the side", {-300.0, 150.0, 40.0}, glm::normalize(glm::dvec3(1.0, 0.05, 0.02)), 800.0, 0.02},
        {"up the axis", s.position + 30.0 * glm::normalize(s.direction), glm::normalize(s.direction), 2900.0,
         0.02},
        {"across it 1 m from the lamp",
         s.position + glm::normalize(s.direction) - glm::dvec3(200.0, 0.0, 0.0),
         {1.0, 0.0, 0.0},
         600.0,
         0.05},
    };
    for (const Ray& ray : rays) {
        SCOPED_TRACE(ray.name);
        const double exact = reference(ray.eye, ray.dir, ray.tMax);
        ASSERT_GT(exact, 0.0);
        std::printf("[beam] %s: exact %.4g;", ray.name, exact);
        double err8 = 0.0;
        for (int n : {2, 4, 8, 16, 32}) {
            const double v = spotInScatter(s, fog, ray.eye, ray.dir, ray.tMax, n).x;
            const double err = std::abs(v / exact - 1.0);
            std::printf(" %d: %.2g%%", n, 100.0 * err);
            if (n == 8)
                err8 = err;
            if (n == 32) {
                EXPECT_LT(err, 0.01);
            }
        }
        std::printf("\n");
        EXPECT_LT(err8, ray.bound8);
    }
    // Outside the cone nothing; none without fog or with no samples; more of the beam, more light.
    EXPECT_EQ(spotInScatter(s, fog, {-300.0, -100.0, 40.0}, {1.0, 0.0, 0.0}, 800.0, 8).x, 0.0);
    LightingDesc clear = fog;
    clear.fogDensity = 0.0f;
    EXPECT_EQ(spotInScatter(s, clear, rays[0].eye, rays[0].dir, 800.0, 8).x, 0.0);
    EXPECT_EQ(spotInScatter(s, fog, rays[0].eye, rays[0].dir, 800.0, 0).x, 0.0);
    double previous = 0.0;
    for (double tMax : {100.0, 300.0, 1000.0, 2900.0}) {
        const double v = spotInScatter(s, fog, rays[1].eye, rays[1].dir, tMax, 32).x;
        EXPECT_GT(v, previous) << tMax;
        previous = v;
    }
    // The eye at the lamp, looking along its axis and across it; a spot pointing straight down: finite.
    for (const glm::dvec3& dir :
         {glm::normalize(s.direction), glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 0.0, -1.0)}) {
        const glm::dvec3 v = spotInScatter(s, fog, s.position, dir, 500.0, 8);
        EXPECT_TRUE(std::isfinite(v.x) && v.x >= 0.0);
    }
    SpotLight down = s;
    down.direction = {0.0, 0.0, -1.0};
    const glm::dvec3 v = spotInScatter(down, fog, {0.0, 0.0, 30.0}, {0.0, 0.0, -1.0}, 30.0, 8);
    EXPECT_TRUE(std::isfinite(v.x) && v.x > 0.0);
}

// Krisciunas & Schaefer's moonlight: 0.313 lx full (m = -12.73, I = 10^(-0.4 x 3.84) = 0.0291 fc), dimming
// with the phase angle by their magnitude law, new Moon nearly dark; a moonlit LightingDesc is the Sun's
// light in the Moon's direction scaled by their ratio, the gradient sky alike, the physical sky through the
// Sun's.
TEST(Moonlight, FollowsKrisciunasAndSchaefer) {
    EXPECT_NEAR(moonIlluminanceLux(0.0), 0.3134, 5e-4);
    EXPECT_NEAR(moonIlluminanceLux(90.0),
                moonIlluminanceLux(0.0) * std::pow(10.0, -0.4 * (0.026 * 90.0 + 4e-9 * std::pow(90.0, 4.0))),
                1e-9);
    double previous = 1.0;
    for (double a = 0.0; a <= 180.0; a += 15.0) {
        const double lux = moonIlluminanceLux(a);
        EXPECT_LT(lux, previous) << a;
        previous = lux;
    }
    EXPECT_LT(moonIlluminanceLux(180.0), 1e-3 * moonIlluminanceLux(0.0));
    EXPECT_THROW(moonIlluminanceLux(-1.0), std::invalid_argument);
    EXPECT_THROW(moonIlluminanceLux(std::nan("")), std::invalid_argument);

    LightingDesc day;
    const LightingDesc night = moonlit(day, {0.0, 2.0, 1.0}, 0.0);
    EXPECT_NEAR(night.sunIntensity / day.sunIntensity, moonIlluminanceLux(0.0) / SUN_ILLUMINANCE_LUX, 1e-9);
    EXPECT_NEAR(glm::length(night.sunDirection - glm::normalize(glm::dvec3(0.0, 2.0, 1.0))), 0.0, 1e-12);
    EXPECT_EQ(night.skyIntensity, day.skyIntensity) << "the physical sky follows sunIntensity already";
    day.sky = LightingDesc::Sky::Gradient;
    EXPECT_NEAR(moonlit(day, {0.0, 2.0, 1.0}, 0.0).skyIntensity, 0.3134 / SUN_ILLUMINANCE_LUX, 1e-8);
    EXPECT_THROW(moonlit(day, glm::dvec3(0.0), 0.0), std::invalid_argument);
    EXPECT_NO_THROW(validateLighting(night));
}

// A moonlit night dims a fixed fog colour and an environment map by the same ratio as the light (the map
// copied: the daylight one is left as it was).
TEST(Moonlight, DimsTheFogColourAndTheEnvironmentToo) {
    LightingDesc day;
    day.fogColor = glm::vec3(0.5f, 0.6f, 0.7f);
    auto map = std::make_shared<EnvironmentMap>();
    map->intensity = 2.0f;
    day.environment = map;
    const double ratio = moonIlluminanceLux(30.0) / SUN_ILLUMINANCE_LUX;
    const LightingDesc night = moonlit(day, {1.0, 0.0, 1.0}, 30.0);
    EXPECT_NEAR(night.fogColor->g / 0.6, ratio, 1e-9);
    EXPECT_NEAR(night.environment->intensity / 2.0, ratio, 1e-9);
    EXPECT_EQ(map->intensity, 2.0f);
    EXPECT_NE(night.environment.get(), map.get());
    // Pre-exposure scales them back up.
    const LightingDesc exposedNight = exposed(night, 10.0);
    EXPECT_NEAR(exposedNight.fogColor->g / night.fogColor->g, 1024.0, 1e-3);
    EXPECT_NEAR(exposedNight.environment->intensity / night.environment->intensity, 1024.0, 1e-3);
    EXPECT_THROW(exposed(night, 41.0), std::invalid_argument);
}
