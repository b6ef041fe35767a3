// Quality presets: each level is a valid ocean, and quality rises monotonically in the knobs the accuracy
// sweep found to matter (grid density, lighting octaves, culling).
#include "ocean/Presets.h"

#include <gtest/gtest.h>

using namespace pacifica::ocean;

TEST(Presets, LevelsAreValidAndOrdered) {
    const Quality levels[] = {Quality::Low, Quality::Medium, Quality::High, Quality::Reference};
    int previousVertices = 0;
    size_t previousOctaves = 0;
    for (Quality q : levels) {
        const OceanDesc d = oceanPreset(q);
        EXPECT_NO_THROW(RadialGrid{d.grid}) << toString(q);
        const int vertices = d.grid.rings * d.grid.segments;
        EXPECT_GT(vertices, previousVertices) << toString(q);
        EXPECT_GE(d.octaves.octaves.size(), previousOctaves) << toString(q);
        EXPECT_LE(d.octaves.displacedOctaves, static_cast<int>(d.octaves.octaves.size())) << toString(q);
        previousVertices = vertices;
        previousOctaves = d.octaves.octaves.size();
    }
    EXPECT_EQ(oceanPreset(Quality::Low).grid.rings, 64);
    EXPECT_EQ(oceanPreset(Quality::High).grid.rings, OceanDesc{}.grid.rings); // high is the default
    EXPECT_FALSE(oceanPreset(Quality::Reference).cullVertices);
    // The same bilinear heights from one fetch (listing 18-2) in the presets; the reference keeps the seed's.
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High})
        EXPECT_EQ(oceanPreset(q).octaves.vertexFilter, VertexFilter::Packed4Tap) << toString(q);
    EXPECT_EQ(oceanPreset(Quality::Reference).octaves.vertexFilter, VertexFilter::Bilinear);
}

TEST(Presets, NamesRoundTripAndUnknownNamesListTheValidOnes) {
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High, Quality::Reference})
        EXPECT_EQ(parseQuality(toString(q)), q);
    try {
        parseQuality("ultra");
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("low, medium, high, reference"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("'ultra'"), std::string::npos);
    }
}
