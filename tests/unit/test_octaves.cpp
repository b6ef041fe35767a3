// Unit tests of the height-map octave surface (GPU Gems 2 §18.2.1): tiling in space and time, unit-RMS
// maps, analytic slopes, camera-relative parameters far from the origin and at huge times; every vertex
// filter at texel centres and between them, the Trilinear snap band, the combined path's interpolation bound.
#include "ocean/HeightOctaves.h"
#include "ocean/OceanConstants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace pacifica::ocean;

namespace {

HeightOctavesDesc smallDesc() {
    HeightOctavesDesc d;
    d.mapSize = 64;
    d.frames = 16;
    d.wavesPerOctave = 24;
    return d;
}

const HeightOctaves& surface() {
    static const HeightOctaves s(smallDesc());
    return s;
}

} // namespace

TEST(HeightOctaves, MapsHaveUnitRmsAndAreFinite) {
    for (const OctaveMap& m : surface().maps()) {
        double sum = 0.0;
        const size_t n = static_cast<size_t>(m.size) * m.size;
        for (size_t i = 0; i < n; ++i) {
            ASSERT_TRUE(std::isfinite(m.texels[i * 4]));
            sum += double(m.texels[i * 4]) * m.texels[i * 4];
        }
        // Normalised analytically (orthogonal lattice cosines); half rounding changes it by < 1e-3.
        EXPECT_NEAR(std::sqrt(sum / n), 1.0, 2e-3);
    }
}

TEST(HeightOctaves, TilesInSpaceAndLoopsInTime) {
    const HeightOctaves& s = surface();
    const auto& o = s.desc().octaves;
    const glm::dvec2 p(12.3, -45.6);
    const double t = 3.21;
    const double h = s.heightAt(p, t);
    // Octave tiles are deliberately incommensurate, so the sum has no short period: test each map — a shift
    // by whole tiles in u, v and by a whole loop in frames must give the identical sample.
    for (int i = 0; i < static_cast<int>(o.size()); ++i) {
        const glm::dvec3 a = s.sampleMap(i, {0.37, 0.81}, 5.25);
        const glm::dvec3 b = s.sampleMap(i, {0.37 + 7.0, 0.81 - 3.0}, 5.25 + s.desc().frames);
        EXPECT_NEAR(a.x, b.x, 1e-9);
        EXPECT_NEAR(a.y, b.y, 1e-9);
    }
    // Time: a whole loop period of octave i leaves octave i unchanged.
    EXPECT_TRUE(std::isfinite(h));
    const double period0 = o[0].loopPeriod;
    const glm::dvec3 g0 = s.heightAndGradient(p, t, 1);
    const glm::dvec3 g1 = s.heightAndGradient(p, t + 1000.0 * period0, 1);
    EXPECT_NEAR(g0.x, g1.x, 1e-6);
}

TEST(HeightOctaves, StoredSlopesMatchFiniteDifferencesOfHeight) {
    // dh/du is analytic per texel; a central difference of the bilinear height across one texel at a
    // texel centre approximates it to O(du^2) — bound 5% of the slope scale (2 pi * max cycles).
    const HeightOctaves& s = surface();
    const int size = s.desc().mapSize;
    const double du = 1.0 / size;
    double worst = 0.0, scale = 0.0;
    for (int k = 0; k < 50; ++k) {
        const double u = (k * 7 % size + 0.5) / size, v = (k * 13 % size + 0.5) / size;
        const double analytic = s.sampleMap(0, {u, v}, 0.0).y;
        const double numeric =
            (s.sampleMap(0, {u + du, v}, 0.0).x - s.sampleMap(0, {u - du, v}, 0.0).x) / (2 * du);
        worst = std::max(worst, std::abs(analytic - numeric));
        scale = std::max(scale, std::abs(analytic));
    }
    EXPECT_LT(worst, 0.05 * 2.0 * 3.14159 * (size / 16));
    EXPECT_GT(scale, 1.0); // slopes are not all zero: the test can fail
}

TEST(HeightOctaves, FrameParamsFarFromOriginAndAtHugeTimesStayWrapped) {
    const HeightOctaves& s = surface();
    for (const glm::dvec2 cam : {glm::dvec2(0.0, 0.0), glm::dvec2(1e7, -1e7), glm::dvec2(-3.3e7, 2.2e7)}) {
        for (double t : {0.0, 1e6, 1e9}) {
            for (const OctaveFrameParams& p : s.frameParams(cam, t)) {
                EXPECT_GE(p.uvOffset.x, 0.0f);
                EXPECT_LT(p.uvOffset.x, 1.0f);
                EXPECT_GE(p.uvOffset.y, 0.0f);
                EXPECT_LT(p.uvOffset.y, 1.0f);
                EXPECT_GE(p.framePosition, 0.0f);
                EXPECT_LT(p.framePosition, float(s.desc().frames));
            }
        }
    }
    // The camera-relative evaluation the GPU does (float offset + float relative position) agrees with the
    // CPU's double world evaluation at 10^7 m: offset error <= 6e-8 tile, i.e. < 1e-4 m of height change.
    const glm::dvec2 cam(1e7 + 0.3, -1e7 + 0.7);
    const double t = 1e6 + 0.125;
    const auto params = s.frameParams(cam, t);
    const glm::dvec2 rel(123.0, -45.0);
    double gpuLike = 0.0;
    for (int i = 0; i < s.desc().displacedOctaves; ++i) {
        const auto& p = params[static_cast<size_t>(i)];
        const glm::dvec2 u = glm::dvec2(glm::vec2(rel) * p.invTileSize + p.uvOffset);
        gpuLike += p.amplitude * s.sampleMap(i, u, p.framePosition).x;
    }
    EXPECT_NEAR(gpuLike, s.heightAt(cam + rel, t), 1e-3);
}

TEST(HeightOctaves, InvalidDescriptionsNameTheField) {
    HeightOctavesDesc d = smallDesc();
    d.mapSize = 100;
    EXPECT_THROW(HeightOctaves{d}, std::invalid_argument);
    d = smallDesc();
    d.octaves[1].tileSize = -1.0;
    try {
        HeightOctaves bad(d);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("octaves[1].tileSize"), std::string::npos) << e.what();
    }
    d = smallDesc();
    d.displacedOctaves = 9;
    EXPECT_THROW(HeightOctaves{d}, std::invalid_argument);
}

// --- Vertex filters (GPU Gems 2 §18.2.4, listings 18-2 and 18-3) and the combined path (§18.2.5) ---

namespace {

constexpr VertexFilter ALL_FILTERS[] = {VertexFilter::Nearest, VertexFilter::Bilinear,
                                        VertexFilter::HardwareBilinear, VertexFilter::Packed4Tap,
                                        VertexFilter::Trilinear};

/// Largest |second difference| of octave i's level-0 heights along u or v, over all frames.
double maxSecondDifference(const HeightOctaves& s, int octave) {
    const int n = s.desc().mapSize;
    double worst = 0.0;
    for (int f = 0; f < s.desc().frames; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const double h = s.heightMip(octave, 0, f, x + 1, y);
                const double hv = s.heightMip(octave, 0, f, x, y + 1);
                worst = std::max(worst, std::abs(s.heightMip(octave, 0, f, x + 2, y) - 2.0 * h +
                                                 s.heightMip(octave, 0, f, x, y)));
                worst = std::max(worst, std::abs(s.heightMip(octave, 0, f, x, y + 2) - 2.0 * hv +
                                                 s.heightMip(octave, 0, f, x, y)));
            }
    return worst;
}

} // namespace

TEST(HeightOctavesFilters, TexelCentresGiveTheTexelValueExactly) {
    const HeightOctaves& s = surface();
    const int n = s.desc().mapSize;
    for (VertexFilter filter : {VertexFilter::Nearest, VertexFilter::Bilinear, VertexFilter::HardwareBilinear,
                                VertexFilter::Packed4Tap, VertexFilter::Trilinear}) {
        for (int k = 0; k < 40; ++k) {
            const int o = k % s.desc().displacedOctaves, f = (k * 5) % s.desc().frames;
            const int x = (k * 37) % n, y = (k * 11 + 3) % n;
            // Texel centre (x + 0.5) / n, whole tiles away, on a slice (integer frame position); LOD 0.
            const glm::dvec2 u((x + 0.5) / n - 3.0, (y + 0.5) / n + 5.0);
            EXPECT_EQ(s.sampleHeight(o, filter, u, f, 0.0), double(s.heightMip(o, 0, f, x, y)))
                << toString(filter) << " octave " << o << " texel " << x << "," << y;
        }
    }
    // Nearest: anywhere inside the texel's square, the texel itself.
    EXPECT_EQ(s.sampleHeight(0, VertexFilter::Nearest, {(7 + 0.01) / n, (9 + 0.99) / n}, 2.0),
              double(s.heightMip(0, 0, 2, 7, 9)));
}

TEST(HeightOctavesFilters, PackedTexelsHoldTheTwoByTwoFootprintWrapped) {
    const HeightOctaves& s = surface();
    const int n = s.desc().mapSize;
    const glm::vec4 t = s.packedTexel(1, 0, 3, n - 1, n - 1);
    EXPECT_EQ(t.x, s.heightMip(1, 0, 3, n - 1, n - 1));
    EXPECT_EQ(t.y, s.heightMip(1, 0, 3, 0, n - 1));
    EXPECT_EQ(t.z, s.heightMip(1, 0, 3, n - 1, 0));
    EXPECT_EQ(t.w, s.heightMip(1, 0, 3, 0, 0));
    // Mip level 1 is the 2x2 box average of level 0, rounded to half (relative 2^-11).
    const double avg = 0.25 * (s.heightMip(1, 0, 3, 4, 6) + s.heightMip(1, 0, 3, 5, 6) +
                               s.heightMip(1, 0, 3, 4, 7) + s.heightMip(1, 0, 3, 5, 7));
    EXPECT_NEAR(s.heightMip(1, 1, 3, 2, 3), avg, std::abs(avg) * std::ldexp(1.0, -11) + 1e-7);
    EXPECT_EQ(s.mipLevels(), 7); // 64 -> 1
}

TEST(HeightOctavesFilters, BilinearModesAgreeWithinTheWeightQuantisation) {
    const HeightOctaves& s = surface();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uni(-2.0, 2.0), fr(0.0, 16.0);
    const double quantum = std::ldexp(1.0, -HeightOctaves::HARDWARE_WEIGHT_BITS);
    for (int o = 0; o < s.desc().displacedOctaves; ++o) {
        // Per unit-RMS map: 2 axes x 2^-8 texel of weight error x the largest texel step.
        const double bound = 2.0 * quantum * s.maxTexelStep(o);
        double worstHw = 0.0;
        for (int k = 0; k < 2000; ++k) {
            const glm::dvec2 u(uni(rng), uni(rng));
            const double f = fr(rng);
            const double bil = s.sampleHeight(o, VertexFilter::Bilinear, u, f);
            // Listing 18-2 packs losslessly: the identical value.
            EXPECT_EQ(s.sampleHeight(o, VertexFilter::Packed4Tap, u, f), bil);
            EXPECT_EQ(s.sampleHeight(o, VertexFilter::Trilinear, u, f, 0.0), bil);
            worstHw =
                std::max(worstHw, std::abs(s.sampleHeight(o, VertexFilter::HardwareBilinear, u, f) - bil));
        }
        EXPECT_LE(worstHw, bound) << "octave " << o;
        EXPECT_GT(worstHw, 0.05 * bound) << "octave " << o << ": quantisation not applied?";
    }
    // A specific value: sub-texel fraction 0.3 + 2^-10 rounds to 77/256 along x (y at a texel centre).
    const int n = s.desc().mapSize;
    const double ax = 0.3 + std::ldexp(1.0, -10);
    const glm::dvec2 u((10 + 0.5 + ax) / n, (20 + 0.5) / n);
    const double h0 = s.heightMip(0, 0, 0, 10, 20), h1 = s.heightMip(0, 0, 0, 11, 20);
    EXPECT_NEAR(s.sampleHeight(0, VertexFilter::HardwareBilinear, u, 0.0), h0 + (h1 - h0) * (77.0 / 256.0),
                1e-12);
    EXPECT_NEAR(s.sampleHeight(0, VertexFilter::Bilinear, u, 0.0), h0 + (h1 - h0) * ax, 1e-12);
    EXPECT_NEAR(s.hardwareBilinearBound(),
                2.0 * quantum *
                    (0.55 * s.maxTexelStep(0) + 0.40 * s.maxTexelStep(1) + 0.13 * s.maxTexelStep(2)),
                1e-12);
}

TEST(HeightOctavesFilters, TrilinearSnapsOutsideTheBandAndBlendsInside) {
    const HeightOctaves& s = surface();
    const int n = s.desc().mapSize;
    const int o = 1, f = 4, x = 20, y = 42; // x, y even: level-1 position p1 = x / 2 - 0.25 (fraction 0.75)
    const glm::dvec2 u((x + 0.5) / n, (y + 0.5) / n);
    const double level0 = s.heightMip(o, 0, f, x, y);
    auto h1 = [&](int i, int j) { return double(s.heightMip(o, 1, f, i, j)); };
    const int i1 = x / 2 - 1, j1 = y / 2 - 1;
    const double bottom = h1(i1, j1) + (h1(i1 + 1, j1) - h1(i1, j1)) * 0.75;
    const double top = h1(i1, j1 + 1) + (h1(i1 + 1, j1 + 1) - h1(i1, j1 + 1)) * 0.75;
    const double level1 = bottom + (top - bottom) * 0.75;
    ASSERT_GT(std::abs(level1 - level0), 1e-3); // the two levels differ here: the blend is visible
    auto tri = [&](double lod) { return s.sampleHeight(o, VertexFilter::Trilinear, u, f, lod); };
    EXPECT_EQ(tri(0.0), level0);
    EXPECT_EQ(tri(0.29), level0);         // below the band: level 0 alone (one fetch)
    EXPECT_NEAR(tri(0.3), level0, 1e-12); // band edge: weight 0
    EXPECT_NEAR(tri(0.4), level0 + (level1 - level0) * 0.25, 1e-12);
    EXPECT_NEAR(tri(0.5), 0.5 * (level0 + level1), 1e-12);
    EXPECT_NEAR(tri(0.7), level1, 1e-12);                 // band edge: weight 1
    EXPECT_EQ(tri(0.71), level1);                         // above the band: level 1 alone
    EXPECT_EQ(tri(1.2), level1);                          // level 1 below its own band
    EXPECT_EQ(tri(99.0), tri(double(s.mipLevels() - 1))); // clamped to the 1x1 level
    // LOD from distance: lambda = log2(d * B * size / trilinearLodTexels) = log2(d / tileSize) here
    // (size 64 = trilinearLodTexels 64).
    const double tile = s.desc().octaves[o].tileSize;
    EXPECT_EQ(s.trilinearLod(o, 0.5 * tile), 0.0);
    EXPECT_NEAR(s.trilinearLod(o, 4.0 * tile), 2.0, 1e-12);
    EXPECT_NEAR(s.trilinearLod(o, 1.5 * tile), std::log2(1.5), 1e-12);
    EXPECT_EQ(s.trilinearLod(o, 1e9), double(s.mipLevels() - 1));
}

TEST(HeightOctavesFilters, PerVertexPathAndCpuQueriesUseTheSelectedFilter) {
    for (VertexFilter filter : ALL_FILTERS) {
        HeightOctavesDesc d = smallDesc();
        d.vertexFilter = filter;
        const HeightOctaves s(d);
        const glm::dvec2 cam(1e7 + 0.3, -1e7 + 0.7), p = cam + glm::dvec2(800.0, -1300.0);
        const double t = 1e6 + 0.125;
        EXPECT_EQ(s.heightSeenFrom(p, t, cam), s.filteredHeight(p, t, cam, filter)) << toString(filter);
        // heightAt: seen from right above the point (Trilinear: LOD 0, i.e. Bilinear).
        const VertexFilter nearFilter = filter == VertexFilter::Trilinear ? VertexFilter::Bilinear : filter;
        EXPECT_EQ(s.heightAt(p, t), s.filteredHeight(p, t, p, nearFilter)) << toString(filter);
        EXPECT_EQ(s.displacementSeenFrom(p, t, cam).z, s.heightSeenFrom(p, t, cam));
        // Any filter stays within the max displacement (convex combinations of texels).
        EXPECT_LE(std::abs(s.heightSeenFrom(p, t, cam)), s.maxDisplacement());
    }
}

TEST(HeightOctavesFilters, CombinedLevelsReachTheGridAndSnapToTheirTexel) {
    const HeightOctaves& s = surface(); // combinedSize 256, combinedTexel 0.25 m, combinedRadius 40 km
    EXPECT_EQ(s.combinedLevels(), 12);  // reach 126 * 0.25 * 2^11 = 64.5 km >= 40 km > 32.3 km
    EXPECT_DOUBLE_EQ(s.combinedReach(0), 31.5);
    EXPECT_DOUBLE_EQ(s.combinedTexel(11), 512.0);
    EXPECT_EQ(s.combinedLevelFor({31.5, -31.5}), 0);
    EXPECT_EQ(s.combinedLevelFor({31.6, 0.0}), 1);
    EXPECT_EQ(s.combinedLevelFor({0.0, -40000.0}), 11);
    EXPECT_EQ(s.combinedLevelFor({1e6, 0.0}), 11); // beyond every reach: the last level
    const glm::dvec2 o = s.combinedOrigin(3, {1e7 + 0.3, -1e7 - 0.7});
    EXPECT_EQ(o, glm::dvec2(1e7, -1e7 - 2.0)); // floor(camera / 2 m) * 2 m
}

TEST(HeightOctavesFilters, CombinedPathMatchesThePerVertexPathWithinTheInterpolationBound) {
    // The combined texture interpolates g = filteredHeight bilinearly from nodes Delta apart. Bilinear =
    // I_x I_y, so I g - g = I_x (I_y g - g) + (I_x g - g) and |I g - g| <= E_x + E_y, each the error of 1D
    // linear interpolation along a line: over a segment of length Delta that is at most
    // Delta / 4 * (range of the slope on it). g = sum_i A_i G_i(B_i x) (convex in time) with G_i bilinear
    // in texels of w_i = tileSize_i / mapSize metres: along a line its slope changes only at the at most
    // ceil(Delta / w_i) texel edges crossed, each time by at most S_i / w_i (S_i = the largest second
    // difference of the map). So |combined - perVertex| <= sum_i Delta / 2 * A_i * ceil(Delta / w_i) * S_i /
    // w_i (and never more than 2 * maxDisplacement).
    const HeightOctaves& s = surface();
    std::vector<double> secondDiff;
    for (int i = 0; i < s.desc().displacedOctaves; ++i)
        secondDiff.push_back(maxSecondDifference(s, i));
    auto bound = [&](double delta) {
        double e = 0.0;
        for (int i = 0; i < s.desc().displacedOctaves; ++i) {
            const OctaveDesc& o = s.desc().octaves[static_cast<size_t>(i)];
            const double w = o.tileSize / s.desc().mapSize;
            e += delta / 2.0 * o.amplitude * std::ceil(delta / w) * secondDiff[static_cast<size_t>(i)] / w;
        }
        return std::min(e, 2.0 * s.maxDisplacement());
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> logR(std::log(0.1), std::log(40000.0)),
        angle(0.0, 6.283185307179586);
    for (const glm::dvec2 cam : {glm::dvec2(0.0, 0.0), glm::dvec2(1e7 + 0.3, -1e7 + 0.7)}) {
        for (double t : {0.0, 1e6 + 0.125}) {
            double worstRatio = 0.0, worstNear = 0.0;
            for (int k = 0; k < 3000; ++k) {
                const double r = std::exp(logR(rng)), a = angle(rng);
                const glm::dvec2 p = cam + r * glm::dvec2(std::cos(a), std::sin(a));
                const int level = s.combinedLevelFor(p - cam);
                const double err = std::abs(s.combinedHeight(p, t, cam, VertexFilter::Bilinear) -
                                            s.filteredHeight(p, t, cam, VertexFilter::Bilinear));
                const double b = bound(s.combinedTexel(level));
                ASSERT_LE(err, b + 1e-12) << "r " << r << " level " << level;
                worstRatio = std::max(worstRatio, err / b);
                if (level == 0)
                    worstNear = std::max(worstNear, err);
            }
            std::printf("combined vs per-vertex (bilinear): level-0 max error %.3g m (bound %.3g m), "
                        "max error / bound %.3f\n",
                        worstNear, bound(s.combinedTexel(0)), worstRatio);
            EXPECT_GT(worstNear, 0.0); // the combined path is a different approximation: it must show
        }
    }
    // At a node the combined value is the node's per-vertex value (weights 0).
    const glm::dvec2 cam(1e7 + 0.3, -1e7 + 0.7);
    const int level = 4;
    const double texel = s.combinedTexel(level);
    const glm::dvec2 node =
        s.combinedOrigin(level, cam) + (glm::dvec2(250.0, 10.0) + (0.5 - s.desc().combinedSize / 2)) * texel;
    ASSERT_EQ(s.combinedLevelFor(node - cam), level);
    EXPECT_NEAR(s.combinedHeight(node, 7.0, cam, VertexFilter::Trilinear),
                s.filteredHeight(node, 7.0, cam, VertexFilter::Trilinear), 1e-9);
    // CPU queries in combined mode: seen from right above the point.
    HeightOctavesDesc d = smallDesc();
    d.combinedDisplacement = true;
    const HeightOctaves combined(d);
    EXPECT_EQ(combined.heightAt(node, 7.0), combined.combinedHeight(node, 7.0, node, VertexFilter::Bilinear));
    EXPECT_EQ(combined.heightSeenFrom(node, 7.0, cam),
              combined.combinedHeight(node, 7.0, cam, VertexFilter::Bilinear));
}

TEST(HeightOctavesFilters, InvalidFilterFieldsNameTheField) {
    auto message = [](const HeightOctavesDesc& d) {
        try {
            HeightOctaves bad(d);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    HeightOctavesDesc d = smallDesc();
    d.trilinearLodTexels = 0.0;
    EXPECT_NE(message(d).find("trilinearLodTexels"), std::string::npos) << message(d);
    d = smallDesc();
    d.combinedSize = 100;
    EXPECT_NE(message(d).find("combinedSize"), std::string::npos) << message(d);
    d = smallDesc();
    d.combinedTexel = -1.0;
    EXPECT_NE(message(d).find("combinedTexel"), std::string::npos) << message(d);
    d = smallDesc();
    d.combinedRadius = 1e12; // would need more than 16 levels
    EXPECT_NE(message(d).find("combinedRadius"), std::string::npos) << message(d);
    d = smallDesc();
    d.vertexFilter = static_cast<VertexFilter>(17);
    EXPECT_NE(message(d).find("vertexFilter"), std::string::npos) << message(d);
    EXPECT_STREQ(toString(VertexFilter::Packed4Tap), "packed-4tap");
}

// Living whitecaps (foamMemory): a crest that stands for one slice leaves foam where it stood, which decays
// by e^(-dt / FOAM_DECAY_TIME) per slice and spreads with variance 2 D dt per slice (mass kept); a crest that
// keeps standing keeps its foam; troughs remember nothing of their own.
TEST(HeightOctavesFoam, CrestFoamStaysDecaysAndSpreads) {
    OctaveMap map;
    map.size = 32;
    map.frames = 64;
    map.texels.assign(static_cast<size_t>(map.frames) * 32 * 32 * 4, -1.0f);  // a trough everywhere...
    map.texels[(static_cast<size_t>(0) * 32 * 32 + 16 * 32 + 16) * 4] = 2.0f; // ...but one crest at slice 0
    const double texel = 0.5, dt = 0.25;
    const std::vector<float> m = foamMemory(map, texel, dt);
    ASSERT_EQ(m.size(), static_cast<size_t>(64) * 32 * 32);
    auto at = [&](int f, int x, int y) { return double(m[static_cast<size_t>(f) * 1024 + y * 32 + x]); };
    EXPECT_FLOAT_EQ(at(0, 16, 16), 2.0f); // it forms where the crest stands
    EXPECT_LT(at(0, 3, 3), 1e-4);         // no crest passed there (only the last loop's crest, spread thin)
    const double decay = std::exp(-dt / FOAM_DECAY_TIME),
                 var = 2.0 * FOAM_SPREAD_DIFFUSIVITY * dt / (texel * texel);
    for (int k : {4, 16}) {
        double mass = 0.0, second = 0.0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                mass += at(k, x, y);
                second += at(k, x, y) * ((x - 16) * (x - 16));
            }
        // The loop is periodic: the crest of the previous loop (64 slices earlier) adds its residue.
        const double now = std::pow(decay, k), before = std::pow(decay, k + 64);
        const double expectedMass = 2.0 * (now + before),
                     expectedVar = var * (now * k + before * (k + 64)) / (now + before);
        std::printf(
            "slice %d: centre %.4f, mass %.4f (expected %.4f), x variance %.3f (expected %.3f) texels^2\n", k,
            at(k, 16, 16), mass, expectedMass, second / mass, expectedVar);
        EXPECT_NEAR(mass, expectedMass, 2e-3 * k);                   // decays, half rounding per texel
        EXPECT_NEAR(second / mass, expectedVar, 0.03 * expectedVar); // spreads as a diffusion
        EXPECT_LT(at(k, 16, 16), at(k - 1, 16, 16));                 // fades where it formed
        EXPECT_GT(at(k, 18, 16), 0.0);                               // and reaches the neighbours
    }
    // A crest that stands all the time keeps its full foam.
    OctaveMap steady = map;
    for (int f = 0; f < steady.frames; ++f)
        steady.texels[(static_cast<size_t>(f) * 1024 + 16 * 32 + 16) * 4] = 2.0f;
    const std::vector<float> s = foamMemory(steady, texel, dt);
    for (int f = 0; f < steady.frames; ++f)
        EXPECT_FLOAT_EQ(s[static_cast<size_t>(f) * 1024 + 16 * 32 + 16], 2.0f);
    EXPECT_THROW(foamMemory(map, 0.0, dt), std::invalid_argument);
    EXPECT_THROW(foamMemory(map, texel, std::nan("")), std::invalid_argument);
}

// The octave surface's foam height input is at least the positive part of every displaced octave's height
// (a standing crest foams as before), and exceeds the current height where crests stood lately: sampled at
// 2000 points, it is >= H+ everywhere (within half rounding) and above it by > 1 cm at a share of them.
TEST(HeightOctavesFoam, FoamHeightRemembersCrests) {
    const HeightOctaves& s = surface();
    int above = 0;
    for (int n = 0; n < 2000; ++n) {
        const glm::dvec2 p(37.1 * n, 91.7 * std::fmod(n * 0.618, 7.0));
        const double t = 3.3 + 0.7 * n;
        double positive = 0.0;
        for (int i = 0; i < s.desc().displacedOctaves; ++i) {
            const OctaveDesc& o = s.desc().octaves[static_cast<size_t>(i)];
            const double fpos = std::fmod(t, o.loopPeriod) / o.loopPeriod * s.desc().frames;
            positive += o.amplitude *
                        std::max(0.0, s.sampleHeight(i, VertexFilter::Bilinear, p / o.tileSize, fpos, 0.0));
        }
        const double f = s.foamHeightAt(p, t);
        ASSERT_TRUE(std::isfinite(f));
        EXPECT_GE(f, s.heightAt(p, t) - 1e-3) << n;
        if (f > positive + 0.01)
            ++above;
    }
    std::printf("foam height above the octaves' positive heights by > 1 cm at %d of 2000 points\n", above);
    EXPECT_GT(above, 200);
}

// Without foam memory (the accuracy bench's knob) the foam height is the displaced octaves' height itself.
TEST(HeightOctavesFoam, WithoutMemoryTheFoamHeightIsTheHeight) {
    HeightOctavesDesc d = smallDesc();
    d.foamMemory = false;
    const HeightOctaves s(d);
    for (const OctaveMap& m : s.maps())
        EXPECT_TRUE(m.foam.empty());
    for (int n = 0; n < 200; ++n) {
        const glm::dvec2 p(13.7 * n - 900.0, 5.3 * n);
        const double t = 0.37 * n;
        EXPECT_NEAR(s.foamHeightAt(p, t), s.heightAt(p, t), 1e-9) << n;
    }
}
