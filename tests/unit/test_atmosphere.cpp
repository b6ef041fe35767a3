// The physical clear sky (ocean/Atmosphere.h) on the CPU: the transmittance table against its integral and
// the closed form, the reddened sunlight, a blue zenith and a brighter horizon band at sun 30 degrees, the
// sky's symmetry about the sun, convergence of the view integral (the quality knob's error), the lat-long
// map's orientation and its agreement with the direct integral, and hard cases (sea level, 100 km, the sun
// at the zenith, the nadir and on the horizon) that must stay finite.
#include "ocean/Atmosphere.h"
#include "ocean/OceanConstants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

using namespace pacifica;
using ocean::AtmosphereDesc;
using ocean::ClearSky;
using ocean::ClearSkyQuality;

namespace {

constexpr double PI = std::numbers::pi;

double luminance(const glm::dvec3& c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

/// Unit vector at `elevationDeg` above the horizontal and `headingDeg` clockwise from north (ENU).
glm::dvec3 dirAt(double elevationDeg, double headingDeg) {
    const double e = elevationDeg * PI / 180.0, h = headingDeg * PI / 180.0;
    return {std::cos(e) * std::sin(h), std::cos(e) * std::cos(h), std::sin(e)};
}

/// One sky shared by the tests (its tables take ~0.1 s).
const ClearSky& earth() {
    static const ClearSky sky;
    return sky;
}

double maxRelativeError(const glm::dvec3& a, const glm::dvec3& ref) {
    double e = 0.0;
    for (int c = 0; c < 3; ++c)
        e = std::max(e, std::abs(a[c] - ref[c]) / std::max(std::abs(ref[c]), 1e-12));
    return e;
}

} // namespace

// The table (256 x 64, Bruneton 2017's horizon-aware coordinates, bilinear) against a 4000-step integral,
// from the sea to 40 km and from the zenith to the horizon: within 1 % down to mu = 0.03 (1.7 degrees),
// 4 % below (1.5 % at mu = 0.01 and 3 % on the horizon, from 2 m).
TEST(Atmosphere, TransmittanceTableMatchesItsIntegral) {
    const ClearSky& sky = earth();
    double worst = 0.0;
    for (double h : {0.0, 2.0, 500.0, 3000.0, 15000.0, 40000.0})
        for (double mu : {1.0, 0.7, 0.3, 0.1, 0.03, 0.01, 0.0}) {
            const glm::dvec3 table = sky.transmittanceToSpace(h, mu);
            const glm::dvec3 ref = sky.transmittanceToSpaceIntegrated(h, mu, 4000);
            ASSERT_GT(ref.b, 0.0) << "h " << h << " mu " << mu;
            worst = std::max(worst, maxRelativeError(table, ref));
            // The tangent ray from near the sea crosses the most air over the least table resolution.
            EXPECT_LT(maxRelativeError(table, ref), mu >= 0.03 ? 0.01 : 0.04) << "h " << h << " mu " << mu;
        }
    std::printf("transmittance table vs integral: worst relative error %.2e\n", worst);
}

// Straight up through a single exponential layer the optical depth is beta H (1 - e^(-(top - bottom) / H)),
// exactly (the vertical ray is radial).
TEST(Atmosphere, ZenithTransmittanceFollowsTheClosedForm) {
    AtmosphereDesc d;
    d.mieScattering = 0.0;
    d.mieExtinction = 0.0;
    d.ozoneAbsorption = glm::dvec3(0.0);
    const ClearSky sky(d);
    const double thickness = d.topRadius - d.bottomRadius;
    for (int c = 0; c < 3; ++c) {
        const double tau = d.rayleighScattering[c] * d.rayleighScaleHeight *
                           (1.0 - std::exp(-thickness / d.rayleighScaleHeight));
        EXPECT_NEAR(sky.transmittanceToSpace(0.0, 1.0)[c], std::exp(-tau), 1e-4 * std::exp(-tau)) << c;
    }
}

// Sunlight through the air is reddened, more so low in the sky; at 2 degrees below the horizon it is gone,
// and with the sun's centre on the horizon about half its disc is seen.
TEST(Atmosphere, SunlightIsReddenedByTheAir) {
    const ClearSky& sky = earth();
    const glm::dvec3 high = sky.sunlight(0.0, dirAt(30.0, 90.0));
    const glm::dvec3 low = sky.sunlight(0.0, dirAt(5.0, 90.0));
    std::printf("sunlight at the sea, sun 30 deg: %.3f %.3f %.3f; 5 deg: %.3f %.3f %.3f\n", high.r, high.g,
                high.b, low.r, low.g, low.b);
    EXPECT_GT(high.r, high.g);
    EXPECT_GT(high.g, high.b);
    EXPECT_GT(high.b, 0.4);
    EXPECT_LT(high.r, 1.0);
    EXPECT_GT(low.r / low.b, 1.5 * (high.r / high.b));
    EXPECT_EQ(sky.sunlight(0.0, dirAt(-2.0, 90.0)), glm::dvec3(0.0));
    const double half = sky.sunlight(0.0, dirAt(0.0, 90.0)).r / sky.transmittanceToSpace(0.0, 0.0).r;
    EXPECT_NEAR(half, 0.5, 1e-6);
    EXPECT_EQ(sky.sunlight(0.0, dirAt(0.3, 90.0)).r,
              sky.transmittanceToSpace(0.0, std::sin(0.3 * PI / 180.0)).r);
    // More air overhead, less light: from 10 km the sun is brighter and whiter.
    const glm::dvec3 aloft = sky.sunlight(10000.0, dirAt(30.0, 90.0));
    EXPECT_GT(aloft.b, high.b * 1.2);
}

// The clear-sky test at sun 30 degrees, from the sea: the zenith's hue is blue (b > g > r) and the
// band a few degrees above the horizon, away from the sun, is brighter than the zenith.
TEST(Atmosphere, ClearSkyHasABlueZenithAndABrighterHorizonBand) {
    const ClearSky& sky = earth();
    const glm::dvec3 sun = dirAt(30.0, 90.0);
    const glm::dvec3 zenith = sky.radiance(0.0, {0.0, 0.0, 1.0}, sun);
    EXPECT_GT(zenith.b, 1.5 * zenith.g);
    EXPECT_GT(zenith.g, 1.5 * zenith.r);
    for (double heading : {0.0, 180.0, 270.0}) {
        const glm::dvec3 band = sky.radiance(0.0, dirAt(3.0, heading), sun);
        EXPECT_GT(luminance(band), 2.0 * luminance(zenith)) << "heading " << heading;
    }
    // The aureole (the aerosols' forward Mie lobe): 4 degrees from the sun is brighter than the sky opposite
    // it at the same elevation.
    EXPECT_GT(luminance(sky.radiance(0.0, dirAt(30.0, 95.0), sun)),
              2.5 * luminance(sky.radiance(0.0, dirAt(30.0, 270.0), sun)));
    // From 15 km, above most of the air, the zenith is darker and a deeper blue.
    const glm::dvec3 high = sky.radiance(15000.0, {0.0, 0.0, 1.0}, sun);
    EXPECT_LT(luminance(high), 0.5 * luminance(zenith));
    EXPECT_GT(high.b / high.r, zenith.b / zenith.r);
}

// The sky is symmetric about the sun's vertical plane.
TEST(Atmosphere, SkyIsSymmetricAboutTheSun) {
    const ClearSky& sky = earth();
    const glm::dvec3 sun = dirAt(20.0, 130.0);
    for (double off : {10.0, 45.0, 120.0})
        for (double e : {2.0, 30.0}) {
            const glm::dvec3 a = sky.radiance(1000.0, dirAt(e, 130.0 + off), sun);
            const glm::dvec3 b = sky.radiance(1000.0, dirAt(e, 130.0 - off), sun);
            EXPECT_LT(maxRelativeError(a, b), 1e-9) << off << " " << e;
        }
}

// The quality knob ClearSkyQuality::viewSteps: 32 steps (the default) lie within 1 % of 1024 in every
// direction tried, from the sea and from 10 km; 8 steps are measurably worse.
TEST(Atmosphere, ViewIntegralConvergesWithSteps) {
    const ClearSky& sky = earth();
    const glm::dvec3 sun = dirAt(30.0, 90.0);
    double worst32 = 0.0, worst8 = 0.0;
    for (double h : {0.0, 10000.0})
        for (double e : {90.0, 20.0, 3.0, 0.5, -1.0, -10.0})
            for (double heading : {90.0, 120.0, 270.0}) {
                const glm::dvec3 ref = sky.radiance(h, dirAt(e, heading), sun, 1024);
                worst32 =
                    std::max(worst32, maxRelativeError(sky.radiance(h, dirAt(e, heading), sun, 32), ref));
                worst8 = std::max(worst8, maxRelativeError(sky.radiance(h, dirAt(e, heading), sun, 8), ref));
            }
    std::printf("view integral vs 1024 steps: worst relative error 32 steps %.4f, 8 steps %.4f\n", worst32,
                worst8);
    EXPECT_LT(worst32, 0.01);
    EXPECT_GT(worst8, worst32);
}

// The lat-long map: the EnvironmentMap layout (the aureole lies where the sun is), and each pixel
// within 3 % of the direct integral in the pixel's direction (the sky-view table's resampling error) away
// from the sun's 10 degrees and the last degree above the sea's horizon, where the table is coarsest.
TEST(Atmosphere, SkyMapMatchesTheDirectIntegralAndIsOriented) {
    const ClearSky& sky = earth();
    const glm::dvec3 sun = dirAt(25.0, 200.0);
    const double altitude = 300.0;
    const ocean::EnvironmentMap map = sky.skyMap(altitude, sun);
    ASSERT_EQ(map.width, 512);
    ASSERT_EQ(map.height, 256);
    auto pixel = [&](const glm::dvec3& dir) { // nearest pixel, by the layout's own inverse
        const glm::dvec2 uv = ocean::environmentUv(dir);
        const int col = std::min(static_cast<int>(uv.x * map.width), map.width - 1);
        const int row = std::min(static_cast<int>(uv.y * map.height), map.height - 1);
        const float* p = &map.rgb[(static_cast<size_t>(row) * map.width + col) * 3];
        return glm::dvec3(p[0], p[1], p[2]);
    };
    // The aureole is where the sun is: toward it, brighter than opposite it at the same elevation.
    EXPECT_GT(luminance(pixel(sun)), 2.5 * luminance(pixel(dirAt(25.0, 20.0))));
    EXPECT_GT(luminance(pixel(sun)), 2.5 * luminance(pixel(dirAt(25.0, 110.0))));
    double worst = 0.0;
    int compared = 0;
    for (int row = 2; row < map.height / 2; row += 9)
        for (int col = 3; col < map.width; col += 37) {
            const glm::dvec3 dir =
                ocean::environmentDirection((col + 0.5) / map.width, (row + 0.5) / map.height);
            if (glm::dot(dir, sun) > std::cos(10.0 * PI / 180.0) || dir.z < std::sin(1.0 * PI / 180.0))
                continue;
            const float* p = &map.rgb[(static_cast<size_t>(row) * map.width + col) * 3];
            const glm::dvec3 got(p[0], p[1], p[2]);
            worst = std::max(worst, maxRelativeError(got, sky.radiance(altitude, dir, sun)));
            ++compared;
        }
    std::printf("sky map vs direct integral: %d pixels, worst relative error %.4f\n", compared, worst);
    EXPECT_GT(compared, 100);
    EXPECT_LT(worst, 0.03);
}

// Hard cases: the sea surface, 1 mm up, 15 km, 100 km (above the air: clamped to its top), the sun at the
// zenith, at the nadir, on the horizon, and straight down the view; every value finite and >= 0, nothing
// at all from a sun 20 degrees below the horizon seen from the sea but the twilight's faint multiple
// scattering.
TEST(Atmosphere, HardCasesStayFinite) {
    const ClearSky& sky = earth();
    ClearSkyQuality q;
    q.mapWidth = 64;
    q.tableAzimuths = 16;
    q.tableElevations = 16;
    for (double h : {0.0, 0.001, 15000.0, 100000.0})
        for (const glm::dvec3& sun :
             {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), dirAt(0.0, 45.0), dirAt(-20.0, 0.0)}) {
            const ocean::EnvironmentMap map = sky.skyMap(h, sun, q);
            for (float v : map.rgb)
                ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << "h " << h;
            for (const glm::dvec3& v :
                 {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), dirAt(0.0, 10.0), dirAt(-0.01, 10.0)}) {
                const glm::dvec3 l = sky.radiance(h, v, sun);
                for (int c = 0; c < 3; ++c)
                    ASSERT_TRUE(std::isfinite(l[c]) && l[c] >= 0.0) << "h " << h;
            }
        }
    const glm::dvec3 night = sky.radiance(0.0, {0.0, 0.0, 1.0}, dirAt(-20.0, 0.0));
    EXPECT_LT(luminance(night), 1e-3 * luminance(sky.radiance(0.0, {0.0, 0.0, 1.0}, dirAt(30.0, 0.0))));
}

// Bad input: a named error, never a NaN sky.
TEST(Atmosphere, BadInputIsRejectedByName) {
    AtmosphereDesc d;
    d.topRadius = d.bottomRadius;
    EXPECT_THROW(ClearSky{d}, std::invalid_argument);
    d = {};
    d.mieG = 1.0;
    try {
        ClearSky{d};
        FAIL() << "mieG = 1 accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("mieG"), std::string::npos) << e.what();
    }
    d = {};
    d.hazeExtinction = std::nan("");
    EXPECT_THROW(ClearSky{d}, std::invalid_argument);
    EXPECT_THROW(earth().skyMap(std::nan(""), dirAt(30.0, 0.0)), std::invalid_argument);
    EXPECT_THROW(earth().skyMap(0.0, glm::dvec3(0.0)), std::invalid_argument);
    ClearSkyQuality q;
    q.mapWidth = 7;
    EXPECT_THROW(earth().skyMap(0.0, dirAt(30.0, 0.0), q), std::invalid_argument);
}

// The haze layer (LightingDesc::fogDensity through the renderer) dims and whitens: less sunlight reaches
// the sea, and the horizon band's blue-to-red ratio falls.
TEST(Atmosphere, HazeDimsTheSunAndWhitensTheHorizon) {
    AtmosphereDesc hazy;
    hazy.hazeExtinction = 1e-4;
    const ClearSky haze(hazy);
    const glm::dvec3 sun = dirAt(30.0, 90.0);
    EXPECT_LT(haze.sunlight(0.0, sun).g, 0.95 * earth().sunlight(0.0, sun).g);
    const glm::dvec3 clear = earth().radiance(0.0, dirAt(3.0, 270.0), sun);
    const glm::dvec3 white = haze.radiance(0.0, dirAt(3.0, 270.0), sun);
    EXPECT_LT(white.b / white.r, clear.b / clear.r);
}

// OceanConstants.h's PHYSICAL_SKY_WATER_REFERENCE (the default physical sky's irradiance luminance per unit
// solar irradiance, under which LightingDesc::waterColor is defined) is what ClearSky computes for the
// default LightingDesc: its sun and its fog as the haze.
TEST(Atmosphere, WaterReferenceIsTheDefaultSkysIrradiance) {
    const ocean::LightingDesc l;
    const glm::vec3 e = ocean::environmentIrradiance(
        ClearSky(ocean::atmosphereFor(l)).skyMap(0.0, glm::normalize(l.sunDirection)));
    EXPECT_NEAR(0.2126 * e.r + 0.7152 * e.g + 0.0722 * e.b, ocean::PHYSICAL_SKY_WATER_REFERENCE, 2e-4);
}
