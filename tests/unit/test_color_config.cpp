// Unit tests for pacifica::color::ColorPipeline on the CPU (no GL): the embedded ACES config (validates,
// its display and views, reference values of both views), error messages for unknown names and bad files,
// the shipped ACES studio config, and the CLI > $OCIO > embedded precedence of fromEnvironmentOr().
#include "SharedData.h"
#include "engine/color/ColorPipeline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using pacifica::color::ColorError;
using pacifica::color::ColorPipeline;

constexpr const char* STUDIO_CONFIG = "studio-config-v1.0.0_aces-v1.3_ocio-v2.1.ocio";

using pacifica::testdata::sharedDir;

std::filesystem::path studioConfig() {
    return sharedDir() / "data" / "ocio" / STUDIO_CONFIG;
}

bool contains(const std::vector<std::string>& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
}

// Runs one grey pixel (v, v, v, 1) through the selected processor and returns its red channel.
float applyGrey(const ColorPipeline& p, float v) {
    std::array<float, 4> px{v, v, v, 1.f};
    p.applyCpu(px.data(), 1);
    EXPECT_FLOAT_EQ(px[3], 1.f) << "alpha must pass through";
    EXPECT_NEAR(px[0], px[1], 1e-5f) << "grey must stay grey";
    EXPECT_NEAR(px[0], px[2], 1e-5f) << "grey must stay grey";
    return px[0];
}

// The message of the ColorError fn throws ("" if it did not throw: the EXPECTs on it then fail readably).
template <typename Fn>
std::string colorError(Fn&& fn) {
    try {
        fn();
    } catch (const ColorError& e) {
        return e.what();
    }
    return "";
}

// Sets or unsets $OCIO for one scope and restores the previous value.
class ScopedOcioEnv {
public:
    explicit ScopedOcioEnv(const char* value) {
        if (const char* old = std::getenv("OCIO"))
            mOld = old;
        if (value)
            setenv("OCIO", value, 1);
        else
            unsetenv("OCIO");
    }
    ~ScopedOcioEnv() {
        if (mOld)
            setenv("OCIO", mOld->c_str(), 1);
        else
            unsetenv("OCIO");
    }
    ScopedOcioEnv(const ScopedOcioEnv&) = delete;
    ScopedOcioEnv& operator=(const ScopedOcioEnv&) = delete;

private:
    std::optional<std::string> mOld;
};

TEST(ColorConfig, EmbeddedConfigValidatesAndSelectsTheAcesSdrView) {
    const ColorPipeline p = ColorPipeline::createDefault();
    EXPECT_EQ(p.validateReport(), "");
    EXPECT_EQ(p.source(), "embedded default");
    EXPECT_EQ(p.configDescription(), "pacifica-embedded_aces-v1.3_ocio-v2.1");
    EXPECT_EQ(p.displays(), std::vector<std::string>{"sRGB"});
    EXPECT_EQ(p.defaultDisplay(), "sRGB");
    const std::vector<std::string> views = p.views("sRGB");
    EXPECT_TRUE(contains(views, "ACES 1.0 - SDR Video"));
    EXPECT_TRUE(contains(views, "Un-tone-mapped"));
    EXPECT_EQ(p.defaultView("sRGB"), "ACES 1.0 - SDR Video");
    EXPECT_EQ(p.selectedDisplay(), "sRGB");
    EXPECT_EQ(p.selectedView(), "ACES 1.0 - SDR Video");
}

TEST(ColorConfig, AcesSdrViewReferenceValues) {
    ColorPipeline p = ColorPipeline::createDefault();
    p.select("sRGB", "ACES 1.0 - SDR Video");
    // 0.3559543: measured with OCIO 2.1.2's CPU processor (Debian 12); the ACES studio config's
    // "sRGB - Display" / "ACES 1.0 - SDR Video" gives the same 0.3559543 for ACEScg 0.18 (grey is grey in
    // every linear space with a D65-adapted white). Hand check against the ACES 1.0.3 CTL: the RRT and the
    // ODT's segmented spline C9 put mid grey at ~4.8 of 48 cd/m^2, so Y = (4.8 - 0.02) / (48 - 0.02) = 0.0996
    // (ODT.Academy.RGBmonitor_100nits_dim, Y_2_linCV); the dim-surround gamma 0.9811 lifts it to 0.10406;
    // and the sRGB encoding of that is 1.055 * 0.10406^(1/2.4) - 0.055 = 0.35595.
    EXPECT_NEAR(applyGrey(p, 0.18f), 0.356f, 0.01f);
    EXPECT_NEAR(applyGrey(p, 0.f), 0.f, 1e-4f);
    // The SDR output transform saturates: 1e6 lands at ~1.0404 (measured; 64 -> 1.0168, docs/PLATFORM.md).
    const float huge = applyGrey(p, 1e6f);
    EXPECT_TRUE(std::isfinite(huge));
    EXPECT_LE(huge, 1.1f);
    EXPECT_GE(huge, 0.99f);
}

TEST(ColorConfig, UntonemappedViewIsPlainSrgbEncoding) {
    ColorPipeline p = ColorPipeline::createDefault();
    p.select("sRGB", "Un-tone-mapped");
    EXPECT_EQ(p.selectedView(), "Un-tone-mapped");
    // IEC 61966-2-1 sRGB encoding: 1.055 * 0.18^(1/2.4) - 0.055 = 0.461356.
    EXPECT_NEAR(applyGrey(p, 0.18f), 0.4613f, 1e-3f);
    EXPECT_NEAR(applyGrey(p, 1.f), 1.f, 1e-3f);
    // Below the 0.0031308 break point the curve is linear with slope 12.92.
    EXPECT_NEAR(applyGrey(p, 0.001f), 0.01292f, 1e-4f);
}

TEST(ColorConfig, EmptyNamesSelectTheDefaults) {
    ColorPipeline p = ColorPipeline::createDefault();
    p.select("sRGB", "Un-tone-mapped");
    p.select("", "");
    EXPECT_EQ(p.selectedDisplay(), "sRGB");
    EXPECT_EQ(p.selectedView(), "ACES 1.0 - SDR Video");
}

TEST(ColorConfig, UnknownDisplayListsValidDisplays) {
    ColorPipeline p = ColorPipeline::createDefault();
    const std::string msg = colorError([&] { p.select("Foo", ""); });
    EXPECT_NE(msg.find("unknown display 'Foo'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("valid displays: 'sRGB'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("embedded config"), std::string::npos) << msg;
    EXPECT_NE(colorError([&] { (void)p.views("Foo"); }).find("valid displays: 'sRGB'"), std::string::npos);
    // A failed select() keeps the previous selection.
    EXPECT_EQ(p.selectedView(), "ACES 1.0 - SDR Video");
}

TEST(ColorConfig, UnknownViewListsValidViews) {
    ColorPipeline p = ColorPipeline::createDefault();
    p.select("sRGB", "Un-tone-mapped");
    const std::string msg = colorError([&] { p.select("sRGB", "Foo"); });
    EXPECT_NE(msg.find("unknown view 'Foo' for display 'sRGB'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("valid views: 'ACES 1.0 - SDR Video', 'Un-tone-mapped'"), std::string::npos) << msg;
    EXPECT_EQ(p.selectedView(), "Un-tone-mapped");
}

TEST(ColorConfig, MissingFileThrowsNamingThePath) {
    const std::filesystem::path missing =
        std::filesystem::temp_directory_path() / "pacifica-test-color-does-not-exist.ocio";
    const std::string msg = colorError([&] { (void)ColorPipeline::fromFile(missing); });
    EXPECT_NE(msg.find(missing.string()), std::string::npos) << msg;
}

TEST(ColorConfig, MalformedFileThrowsNamingThePath) {
    const std::filesystem::path bad =
        std::filesystem::temp_directory_path() /
        ("pacifica-test-color-malformed-" + std::to_string(::getpid()) + ".ocio");
    {
        std::ofstream out(bad);
        out << "ocio_profile_version: 2.1\nroles: [this is not: a map\ncolorspaces: {{{\n";
    }
    const std::string msg = colorError([&] { (void)ColorPipeline::fromFile(bad); });
    std::filesystem::remove(bad);
    EXPECT_NE(msg.find(bad.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot load OCIO config"), std::string::npos) << msg;
}

TEST(ColorConfig, StudioConfigLoadsAndListsSrgbDisplay) {
    const std::filesystem::path path = studioConfig();
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    ColorPipeline p = ColorPipeline::fromFile(path);
    EXPECT_EQ(p.source(), path.string());
    EXPECT_EQ(p.configDescription(), "studio-config-v1.0.0_aces-v1.3_ocio-v2.1");
    EXPECT_EQ(p.validateReport(), "");
    EXPECT_TRUE(contains(p.displays(), "sRGB - Display"));
    EXPECT_TRUE(contains(p.views("sRGB - Display"), "ACES 1.0 - SDR Video"));
    p.select("sRGB - Display", "ACES 1.0 - SDR Video");
    // Same output transform as the embedded config's default view: 0.3559543 measured (see above).
    EXPECT_NEAR(applyGrey(p, 0.18f), 0.356f, 0.01f);
}

TEST(ColorConfig, InputColourSpaceForConfigsWhoseSceneLinearIsNotRec709) {
    // The studio config's scene_linear is ACEScg: saturated Rec.709 red entered there is not red any more.
    ColorPipeline p = ColorPipeline::fromFile(studioConfig());
    EXPECT_EQ(p.linearRec709ColorSpace(), "Linear Rec.709 (sRGB)");
    EXPECT_EQ(ColorPipeline::createDefault().linearRec709ColorSpace(), "Linear Rec.709 (sRGB)");
    p.select("sRGB - Display", "Un-tone-mapped");
    std::array<float, 4> red{0.5f, 0.0f, 0.0f, 1.0f};
    p.applyCpu(red.data(), 1);
    EXPECT_GT(std::fabs(red[1]), 0.01f); // through ACEScg it is not pure red any more (out of gamut here)
    EXPECT_EQ(p.input(), "");
    p.setInput(p.linearRec709ColorSpace()); // re-selects the same view
    EXPECT_EQ(p.selectedView(), "Un-tone-mapped");
    red = {0.5f, 0.0f, 0.0f, 1.0f};
    p.applyCpu(red.data(), 1);
    EXPECT_NEAR(red[0], 0.7353569f, 1e-4f); // the sRGB encoding of 0.5
    EXPECT_NEAR(red[1], 0.0f, 1e-5f);
    EXPECT_NEAR(red[2], 0.0f, 1e-5f);
    EXPECT_NE(colorError([&] { p.setInput("No Such Space"); }).find("has no colour space 'No Such Space'"),
              std::string::npos);
    EXPECT_EQ(p.input(), "Linear Rec.709 (sRGB)");
}

TEST(ColorConfig, DecodeDisplayBackToXyz) {
    // sRGB display: code 0.5 is display-linear 0.214 (IEC 61966-2-1), as CIE Y of a grey.
    ColorPipeline p = ColorPipeline::createDefault();
    p.select("sRGB", "Un-tone-mapped");
    std::array<float, 4> px{0.5f, 0.5f, 0.5f, 1.0f};
    ASSERT_TRUE(p.decodeDisplayCpu(px.data(), 1));
    EXPECT_NEAR(px[1], 0.2140411f, 1e-4f);
    // PQ display of the studio config, entered from linear Rec.709: white 1.0 un-tone-mapped is 100 cd/m^2,
    // and decodes back to Y = 1 (the display reference's 1.0 = 100 cd/m^2).
    ColorPipeline s = ColorPipeline::fromFile(studioConfig());
    s.setInput(s.linearRec709ColorSpace());
    s.select("Rec.2100-PQ - Display", "Un-tone-mapped");
    px = {1.0f, 1.0f, 1.0f, 1.0f};
    s.applyCpu(px.data(), 1);
    EXPECT_NEAR(px[1], 0.508f, 0.001f); // ST 2084 code of 100 cd/m^2
    ASSERT_TRUE(s.decodeDisplayCpu(px.data(), 1));
    EXPECT_NEAR(px[1], 1.0f, 2e-3f);
}

TEST(ColorConfig, EnvironmentPrecedence) {
    const std::string studio = studioConfig().string();
    {
        ScopedOcioEnv env(nullptr);
        EXPECT_EQ(ColorPipeline::fromEnvironmentOr(std::nullopt).source(), "embedded default");
    }
    {
        ScopedOcioEnv env("");
        EXPECT_EQ(ColorPipeline::fromEnvironmentOr(std::nullopt).source(), "embedded default");
    }
    {
        ScopedOcioEnv env(studio.c_str());
        const ColorPipeline p = ColorPipeline::fromEnvironmentOr(std::nullopt);
        EXPECT_EQ(p.source(), studio);
        EXPECT_EQ(p.selectedDisplay(), "sRGB - Display");
    }
    {
        // The CLI path wins over $OCIO, and a broken one is an error, not a silent fallback.
        ScopedOcioEnv env(studio.c_str());
        const std::filesystem::path missing = "/nonexistent/pacifica-cli.ocio";
        const std::string msg = colorError([&] { (void)ColorPipeline::fromEnvironmentOr(missing); });
        EXPECT_NE(msg.find(missing.string()), std::string::npos) << msg;
    }
    {
        // A broken $OCIO is reported as coming from $OCIO.
        ScopedOcioEnv env("/nonexistent/pacifica-env.ocio");
        const std::string msg = colorError([&] { (void)ColorPipeline::fromEnvironmentOr(std::nullopt); });
        EXPECT_EQ(msg.rfind("$OCIO: ", 0), 0u) << msg;
        EXPECT_NE(msg.find("/nonexistent/pacifica-env.ocio"), std::string::npos) << msg;
        // ... and a CLI path overrides it.
        EXPECT_EQ(ColorPipeline::fromEnvironmentOr(studioConfig()).source(), studio);
    }
}

TEST(ColorConfig, CopiesAreIndependent) {
    ColorPipeline a = ColorPipeline::createDefault();
    ColorPipeline b = a;
    b.select("sRGB", "Un-tone-mapped");
    EXPECT_EQ(a.selectedView(), "ACES 1.0 - SDR Video");
    EXPECT_NEAR(applyGrey(a, 0.18f), 0.356f, 0.01f);
    EXPECT_NEAR(applyGrey(b, 0.18f), 0.4613f, 1e-3f);
}

TEST(ColorConfig, EmbeddedViewsNeedNoLutTexturesOnTheGpu) {
    ColorPipeline p = ColorPipeline::createDefault();
    for (const char* view : {"ACES 1.0 - SDR Video", "Un-tone-mapped"}) {
        p.select("sRGB", view);
        const ColorPipeline::GpuShader shader = p.gpuShader();
        EXPECT_EQ(shader.functionName, "pacificaOCIODisplay");
        EXPECT_NE(shader.glslText.find("vec4 pacificaOCIODisplay("), std::string::npos) << view;
        EXPECT_EQ(shader.glslText.find("#version"), std::string::npos) << view;
        EXPECT_EQ(shader.luts.size(), 0u) << view;
    }
}

} // namespace
