// GL tests for pacifica::color::Tonemapper under headless EGL: the GPU pass must reproduce OCIO's CPU
// processor (ColorPipeline::applyCpu, the reference) on an HDR ramp that spans 1e-4 .. 1e4, negatives and
// mixed values, for both views of the embedded config, the ACES studio config, and a small config of our
// own that makes OCIO use every LUT texture kind (1D, 1D folded into 2D, 3D) and a dynamic uniform.
#include "SharedData.h"
#include <epoxy/gl.h>

#include "engine/color/ColorPipeline.h"
#include "engine/color/Tonemapper.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GlObjects.h"

#include "GlLayerTest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using pacifica::color::ColorPipeline;
using pacifica::color::Tonemapper;
namespace gl = pacifica::gl;

constexpr int WIDTH = 64;
constexpr int HEIGHT = 4;
constexpr int PIXELS = WIDTH * HEIGHT;

using pacifica::testdata::sharedDir;

// The HDR test ramp, packed RGBA: R log-spaced 1e-4 .. 1e4 (8 decades over 256 pixels), G negative
// log-spaced -1e-3 .. -10, B cycling through mid grey, R's value, a small negative and zero, A = 1.
std::vector<float> hdrRamp() {
    std::vector<float> rgba(static_cast<size_t>(PIXELS) * 4);
    for (int i = 0; i < PIXELS; ++i) {
        const double t = static_cast<double>(i) / (PIXELS - 1);
        const float r = static_cast<float>(std::pow(10.0, -4.0 + 8.0 * t));
        const float g = static_cast<float>(-std::pow(10.0, -3.0 + 4.0 * t));
        const float mix[4] = {0.18f, r, -0.01f * r, 0.f};
        float* px = &rgba[static_cast<size_t>(i) * 4];
        px[0] = r;
        px[1] = g;
        px[2] = mix[i % 4];
        px[3] = 1.f;
    }
    return rgba;
}

struct Comparison {
    float maxDiff = 0.f;    // max |gpu - cpu| over R, G, B of every pixel
    float maxRelDiff = 0.f; // max |gpu - cpu| / max(1, |cpu|): for views whose output reaches 1e5
    int worstPixel = -1;
    int nonFinite = 0;    // pixels where CPU or GPU produced NaN/Inf
    int alphaChanged = 0; // pixels whose alpha differs from the input's
};

class TonemapTest : public pacifica::gltest::GlTest {
protected:
    // Runs the pipeline's selection through the Tonemapper and through applyCpu on the same ramp.
    Comparison compareGpuWithCpu(const ColorPipeline& pipeline, int expectedLuts = 0) {
        const std::vector<float> input = hdrRamp();

        gl::Texture scene = gl::Texture::create2D(GL_RGBA32F, WIDTH, HEIGHT);
        glTextureSubImage2D(scene.id(), 0, 0, 0, WIDTH, HEIGHT, GL_RGBA, GL_FLOAT, input.data());
        gl::Texture display = gl::Texture::create2D(GL_RGBA32F, WIDTH, HEIGHT);
        gl::Framebuffer fbo = gl::Framebuffer::create();
        fbo.attachColor(0, display);
        fbo.checkComplete("tonemap target");

        Tonemapper tonemapper(pipeline);
        EXPECT_EQ(tonemapper.display(), pipeline.selectedDisplay());
        EXPECT_EQ(tonemapper.view(), pipeline.selectedView());
        EXPECT_EQ(tonemapper.lutCount(), expectedLuts);
        tonemapper.run(scene, fbo, WIDTH, HEIGHT);

        std::vector<float> gpu(input.size(), -12345.f);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo.id());
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, WIDTH, HEIGHT, GL_RGBA, GL_FLOAT, gpu.data());
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

        std::vector<float> cpu = input;
        pipeline.applyCpu(cpu.data(), PIXELS);

        Comparison c;
        for (int i = 0; i < PIXELS; ++i) {
            const size_t o = static_cast<size_t>(i) * 4;
            for (int ch = 0; ch < 3; ++ch) {
                const float g = gpu[o + static_cast<size_t>(ch)], r = cpu[o + static_cast<size_t>(ch)];
                if (!std::isfinite(g) || !std::isfinite(r)) {
                    ++c.nonFinite;
                    continue;
                }
                c.maxRelDiff = std::max(c.maxRelDiff, std::abs(g - r) / std::max(1.f, std::abs(r)));
                if (std::abs(g - r) > c.maxDiff) {
                    c.maxDiff = std::abs(g - r);
                    c.worstPixel = i;
                }
            }
            if (gpu[o + 3] != input[o + 3])
                ++c.alphaChanged;
        }
        const std::string name =
            pipeline.configDescription() + " " + pipeline.selectedDisplay() + "/" + pipeline.selectedView();
        std::printf("[ info ] %s: GPU vs CPU max abs diff %.3g (relative %.3g)", name.c_str(),
                    static_cast<double>(c.maxDiff), static_cast<double>(c.maxRelDiff));
        if (c.worstPixel >= 0) {
            const size_t o = static_cast<size_t>(c.worstPixel) * 4;
            std::printf(" at pixel %d: in (%g, %g, %g) cpu (%.7g, %.7g, %.7g) gpu (%.7g, %.7g, %.7g)",
                        c.worstPixel, static_cast<double>(input[o]), static_cast<double>(input[o + 1]),
                        static_cast<double>(input[o + 2]), static_cast<double>(cpu[o]),
                        static_cast<double>(cpu[o + 1]), static_cast<double>(cpu[o + 2]),
                        static_cast<double>(gpu[o]), static_cast<double>(gpu[o + 1]),
                        static_cast<double>(gpu[o + 2]));
        }
        std::printf("\n");
        ::testing::Test::RecordProperty("maxDiff " + name, std::to_string(c.maxDiff));
        return c;
    }
};

// docs/PLATFORM.md measured 3.4e-6 (analytic transforms) between OCIO's GPU and CPU processors on
// llvmpipe; 1e-4 leaves room for other drivers' pow/exp2 while still catching a wrong transform, a wrong
// texel, or a lost channel (display values here are 0 .. ~50 for un-tone-mapped, 0 .. ~1.04 for ACES).
constexpr float ANALYTIC_TOLERANCE = 1e-4f;

TEST_F(TonemapTest, EmbeddedAcesSdrViewMatchesCpu) {
    ColorPipeline p = ColorPipeline::createDefault();
    p.select("sRGB", "ACES 1.0 - SDR Video");
    const Comparison c = compareGpuWithCpu(p);
    EXPECT_EQ(c.nonFinite, 0);
    EXPECT_EQ(c.alphaChanged, 0);
    EXPECT_LE(c.maxDiff, ANALYTIC_TOLERANCE);
}

TEST_F(TonemapTest, EmbeddedUntonemappedViewMatchesCpu) {
    ColorPipeline p = ColorPipeline::createDefault();
    p.select("sRGB", "Un-tone-mapped");
    const Comparison c = compareGpuWithCpu(p);
    EXPECT_EQ(c.nonFinite, 0);
    EXPECT_EQ(c.alphaChanged, 0);
    EXPECT_LE(c.maxDiff, ANALYTIC_TOLERANCE);
}

TEST_F(TonemapTest, StudioConfigAcesSdrViewMatchesCpu) {
    // The studio config's scene_linear is ACEScg, not Rec.709: the ramp means something else there, but GPU
    // and CPU run the same processor, which is what is compared.
    ColorPipeline p = ColorPipeline::fromFile(sharedDir() / "data" / "ocio" /
                                              "studio-config-v1.0.0_aces-v1.3_ocio-v2.1.ocio");
    p.select("sRGB - Display", "ACES 1.0 - SDR Video");
    const Comparison c = compareGpuWithCpu(p);
    EXPECT_EQ(c.nonFinite, 0);
    EXPECT_EQ(c.alphaChanged, 0);
    EXPECT_LE(c.maxDiff, ANALYTIC_TOLERANCE);
}

// A config that makes OCIO emit every GPU resource kind: a 1024-entry 1D LUT (GL_TEXTURE_1D, red only), an
// 8192-entry 1D LUT (folded into a 4096 x 3 GL_TEXTURE_2D), a 17^3 3D LUT (RGB32F GL_TEXTURE_3D,
// tetrahedral) and an ExposureContrastTransform (its gamma becomes a dynamic float uniform).
class LutConfig {
public:
    LutConfig() {
        mDir =
            std::filesystem::temp_directory_path() / ("pacifica-test-tonemap-" + std::to_string(::getpid()));
        std::filesystem::create_directories(mDir);
        writeSpi1d("curve.spi1d", 1024);
        writeSpi1d("long.spi1d", 8192);
        {
            constexpr int N = 17;
            std::ofstream out(mDir / "cube.cube");
            out << "LUT_3D_SIZE " << N << "\n";
            for (int b = 0; b < N; ++b)
                for (int g = 0; g < N; ++g)
                    for (int r = 0; r < N; ++r) {
                        const double R = r / (N - 1.0), G = g / (N - 1.0), B = b / (N - 1.0);
                        out << 0.8 * R + 0.2 * G * G << ' ' << G * (0.5 + 0.5 * B) << ' '
                            << 0.9 * std::sqrt(B) + 0.1 * R << "\n";
                    }
        }
        std::ofstream(mDir / "config.ocio") << R"(ocio_profile_version: 2.1
search_path: "."
name: pacifica-test-luts
roles:
  scene_linear: linear
  default: linear
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  Test:
    - !<View> {name: Lut1D, colorspace: lut1d}
    - !<View> {name: LongLut1D, colorspace: longlut1d}
    - !<View> {name: Lut3D, colorspace: lut3d}
    - !<View> {name: Exposure, colorspace: exposure}
colorspaces:
  - !<ColorSpace>
    name: linear
  - !<ColorSpace>
    name: lut1d
    from_scene_reference: !<FileTransform> {src: curve.spi1d, interpolation: linear}
  - !<ColorSpace>
    name: longlut1d
    from_scene_reference: !<FileTransform> {src: long.spi1d, interpolation: linear}
  - !<ColorSpace>
    name: lut3d
    from_scene_reference: !<FileTransform> {src: cube.cube, interpolation: tetrahedral}
  - !<ColorSpace>
    name: exposure
    from_scene_reference: !<ExposureContrastTransform> {style: linear, exposure: 1, contrast: 1.2, pivot: 0.18}
)";
    }
    ~LutConfig() {
        std::error_code ec;
        std::filesystem::remove_all(mDir, ec);
    }
    LutConfig(const LutConfig&) = delete;
    LutConfig& operator=(const LutConfig&) = delete;
    std::filesystem::path path() const { return mDir / "config.ocio"; }

private:
    // y = sqrt(x) on [0, 1]: steep near 0, so interpolation errors show.
    void writeSpi1d(const char* name, int n) {
        std::ofstream out(mDir / name);
        out << "Version 1\nFrom 0.0 1.0\nLength " << n << "\nComponents 1\n{\n";
        for (int i = 0; i < n; ++i)
            out << "  " << std::sqrt(i / (n - 1.0)) << "\n";
        out << "}\n";
    }
    std::filesystem::path mDir;
};

TEST_F(TonemapTest, LutTexturesAndUniformsMatchCpu) {
    LutConfig config;
    ColorPipeline p = ColorPipeline::fromFile(config.path());
    struct Case {
        const char* view;
        int dims; // of the single LUT, 0 = none
        int uniforms;
        float tolerance;
        bool relative; // compare maxRelDiff instead of maxDiff
    };
    // 1D LUTs are sampled with the texture unit's linear filter. llvmpipe filters in float (measured 7e-9),
    // but GPUs use fixed-point weights (8 fractional bits is common): with neighbouring sqrt entries up to
    // 0.031 apart (1024-entry LUT near 0) a 1/256 weight step is 1.2e-4, so those views get 5e-4. The 3D LUT
    // is tetrahedral, fetched at texel centres (no filter weights): the analytic bound applies. The exposure
    // view (2^1 exposure, contrast 1.2 about 0.18) sends the ramp's 1e4 to ~1e5, where float carries only
    // ~0.01 absolute, so it is compared relative to max(1, |cpu|); 1e-5 is ~80 float ulps.
    const Case cases[] = {{"Lut1D", 1, 0, 5e-4f, false},
                          {"LongLut1D", 2, 0, 5e-4f, false},
                          {"Lut3D", 3, 0, ANALYTIC_TOLERANCE, false},
                          {"Exposure", 0, 1, 1e-5f, true}};
    for (const Case& k : cases) {
        SCOPED_TRACE(k.view);
        p.select("Test", k.view);
        const ColorPipeline::GpuShader shader = p.gpuShader();
        ASSERT_EQ(shader.luts.size(), k.dims ? 1u : 0u);
        if (k.dims) {
            EXPECT_EQ(shader.luts[0].dims, k.dims);
        }
        EXPECT_EQ(static_cast<int>(shader.uniforms.size()), k.uniforms);
        const Comparison c = compareGpuWithCpu(p, k.dims ? 1 : 0);
        EXPECT_EQ(c.nonFinite, 0);
        EXPECT_EQ(c.alphaChanged, 0);
        EXPECT_LE(k.relative ? c.maxRelDiff : c.maxDiff, k.tolerance);
    }
}

TEST_F(TonemapTest, RunRestoresHostState) {
    ColorPipeline p = ColorPipeline::createDefault();
    Tonemapper tonemapper(p);
    gl::Texture scene = gl::Texture::create2D(GL_RGBA16F, 8, 8);
    gl::Texture target = gl::Texture::create2D(GL_RGBA16F, 8, 8);
    gl::Framebuffer fbo = gl::Framebuffer::create();
    fbo.attachColor(0, target);
    gl::Framebuffer hostFbo = gl::Framebuffer::create();
    gl::Texture hostTarget = gl::Texture::create2D(GL_RGBA8, 4, 4);
    hostFbo.attachColor(0, hostTarget);

    glBindFramebuffer(GL_FRAMEBUFFER, hostFbo.id());
    glViewport(1, 2, 3, 4);
    glEnable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glColorMaski(0, GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    tonemapper.run(scene, fbo, 8, 8);

    GLint viewport[4] = {};
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(viewport[0], 1);
    EXPECT_EQ(viewport[3], 4);
    GLint draw = 0, program = -1;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    EXPECT_EQ(static_cast<GLuint>(draw), hostFbo.id());
    EXPECT_EQ(program, 0);
    EXPECT_TRUE(glIsEnabled(GL_BLEND));
    EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
    EXPECT_TRUE(glIsEnabled(GL_FRAMEBUFFER_SRGB));
    GLboolean mask[4] = {};
    glGetBooleani_v(GL_COLOR_WRITEMASK, 0, mask);
    EXPECT_EQ(mask[1], GL_FALSE);
    EXPECT_EQ(mask[2], GL_TRUE);

    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

} // namespace
