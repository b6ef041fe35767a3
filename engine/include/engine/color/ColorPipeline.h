// ColorPipeline: the engine's HDR colour management, a thin layer over OpenColorIO 2.1 that turns the
// renderer's scene-linear frame into display code values for one (display, view) pair. It loads a config
// (the CLI's --ocio path, else $OCIO, else an embedded ACES 1.3 config built in code, since OCIO 2.1 has
// no ocio:// built-in configs), lists its displays and views, resolves the processor from the config's
// scene_linear role to the selected display and view, and exposes it twice: a CPU path (applyCpu, the
// reference the tests compare against) and the GLSL text, LUTs and uniforms the GL Tonemapper builds its
// pass from. No OpenColorIO type appears in this header (pimpl), so including it stays cheap; every
// OCIO::Exception is caught inside the module and rethrown as ColorError.
//
// STEP BY STEP
//   1. auto pipeline = pacifica::color::ColorPipeline::fromEnvironmentOr(cli.ocioPath);  // optional path
//   2. pipeline.select(cli.display, cli.view);   // "" = the config's defaults; unknown names throw
//   ColorError
//   3. pacifica::color::Tonemapper tonemap(pipeline);   // GL context current; rebuild after select()
//   4. per frame: tonemap.run(sceneLinearTexture, displayFramebuffer, width, height);
//   5. metadata: pipeline.source(), pipeline.configDescription(), selectedDisplay(), selectedView()
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pacifica::color {

/// A colour configuration or selection could not be loaded or resolved. The message names the config
/// file (or "embedded default") and the field at fault; for unknown names it lists the valid ones.
class ColorError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class ColorPipeline {
public:
    /// The OCIO GPU shader of the selected processor, ready for a GLSL 4.x fragment shader.
    /// The text holds no `#version` line; its samplers have no binding (set the units with glUniform1i).
    struct GpuShader {
        /// One LUT texture the shader samples. dims 1: GL_TEXTURE_1D (width x 1); dims 2: GL_TEXTURE_2D
        /// (OCIO folds long 1D LUTs into rows of at most 4096 texels); dims 3: GL_TEXTURE_3D RGB with
        /// width = height = depth = edge length. values: width*height*depth*channels floats, row-major,
        /// red fastest, exactly as OCIO lays them out.
        struct Lut {
            std::string samplerName;
            int dims = 1; ///< 1, 2 or 3
            int width = 1, height = 1, depth = 1;
            int channels = 3;   ///< 1 (red only) or 3 (RGB)
            bool linear = true; ///< GL_LINEAR filtering, else GL_NEAREST
            std::vector<float> values;
        };
        /// A uniform OCIO reads at draw time (dynamic properties, e.g. ExposureContrastTransform parameters;
        /// none for ACES output transforms). The getter of its kind returns the current value; the getters
        /// keep the OCIO objects they read alive, so upload every frame.
        struct Uniform {
            enum class Kind { Double, Bool, Float3, VectorFloat, VectorInt };
            std::string name;
            Kind kind = Kind::Double;
            std::function<double()> getDouble;                  ///< Kind::Double (upload as float)
            std::function<bool()> getBool;                      ///< Kind::Bool
            std::function<std::array<float, 3>()> getFloat3;    ///< Kind::Float3
            std::function<std::vector<float>()> getVectorFloat; ///< Kind::VectorFloat (float array)
            std::function<std::vector<int>()> getVectorInt;     ///< Kind::VectorInt (int array)
        };

        std::string functionName; ///< "pacificaOCIODisplay": vec4 pacificaOCIODisplay(vec4 inPixel)
        std::string glslText;     ///< declarations, helpers and the function; GPU_LANGUAGE_GLSL_4_0
        std::vector<Lut> luts;
        std::vector<Uniform> uniforms;
    };

    /// The embedded config, built in code and mirroring the structure of the ACES studio config
    /// (studio-config-v1.0.0_aces-v1.3_ocio-v2.1): scene reference ACES2065-1, scene_linear role
    /// "Linear Rec.709 (sRGB)", display reference CIE-XYZ-D65, display "sRGB" with the views
    /// "ACES 1.0 - SDR Video" (default) and "Un-tone-mapped". The default display and view are selected.
    static ColorPipeline createDefault();
    /// Loads an .ocio file and selects its default display and view. Throws ColorError naming the file and
    /// carrying OCIO's message when it cannot be read or parsed, or when the default selection fails.
    static ColorPipeline fromFile(const std::filesystem::path& path);
    /// Precedence: cliOverride if given, else $OCIO if set and non-empty, else createDefault().
    /// source() says which was used. Throws ColorError when the chosen file fails to load (no fallback:
    /// a config that was asked for and is broken is an error, not a reason to silently look different).
    static ColorPipeline fromEnvironmentOr(const std::optional<std::filesystem::path>& cliOverride);

    /// Copies are independent (select() on one leaves the other); they share OCIO's immutable config.
    /// A moved-from pipeline may only be assigned to or destroyed.
    ColorPipeline(const ColorPipeline& other);
    ColorPipeline& operator=(const ColorPipeline& other);
    ColorPipeline(ColorPipeline&& other) noexcept;
    ColorPipeline& operator=(ColorPipeline&& other) noexcept;
    ~ColorPipeline();

    /// "embedded default", or the path of the loaded config file.
    const std::string& source() const;
    /// A short name for metadata: the config's name, else the file's stem.
    std::string configDescription() const;
    /// Empty when the config passes OCIO's Config::validate(), else OCIO's message.
    std::string validateReport() const;

    /// The config's active displays, in config order.
    std::vector<std::string> displays() const;
    /// The active views of a display, in config order. Throws ColorError for an unknown display.
    std::vector<std::string> views(const std::string& display) const;
    std::string defaultDisplay() const;
    /// Throws ColorError for an unknown display.
    std::string defaultView(const std::string& display) const;

    /// Selects the output: the processor from the scene_linear role to (display, view). Empty strings
    /// mean the config's default display / that display's default view. Throws ColorError, listing the
    /// valid names, for an unknown display or view, or naming the role when scene_linear is missing; the
    /// previous selection stays in place then. GL passes built from the old selection must be recreated.
    void select(const std::string& display, const std::string& view);
    /// The colour space processors start from: empty (default) = the config's scene_linear role. Tools
    /// comparing configs whose scene_linear is not the renderer's Linear Rec.709 (the ACES configs use
    /// ACEScg) set linearRec709ColorSpace() here. Re-selects the current output; throws ColorError naming an
    /// unknown colour space.
    void setInput(const std::string& colorSpace);
    const std::string& input() const;
    /// The config's colour space for linear Rec.709 primaries, found by the names and aliases common
    /// configs use ("Linear Rec.709 (sRGB)", "lin_rec709", "Utility - Linear - sRGB", ...); "" if none.
    std::string linearRec709ColorSpace() const;

    const std::string& selectedDisplay() const;
    const std::string& selectedView() const;

    /// Applies the selected processor on the CPU, in place, to packed RGBA float pixels (alpha passes
    /// through). Output is not clamped. Thread-safe.
    void applyCpu(float* rgba, std::size_t pixelCount) const;

    /// Decodes code values of the selected (display, view) back to the config's display reference (CIE XYZ
    /// D65 in the ACES configs; for the PQ and HLG displays of those configs 1.0 = 100 cd/m^2), in place,
    /// with the display colour space's own transform. Returns false, touching nothing, when the view's colour
    /// space is not a display colour space (a v1-style view) -- the caller must know its encoding then.
    bool decodeDisplayCpu(float* rgba, std::size_t pixelCount) const;

    /// The selected processor as GLSL 4.0 (OCIO's default GPU processor, function "pacificaOCIODisplay",
    /// resource prefix "pacifica_ocio"), with the LUT data and dynamic uniforms it needs.
    GpuShader gpuShader() const;

private:
    struct Impl;
    explicit ColorPipeline(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> mImpl;
};

} // namespace pacifica::color
