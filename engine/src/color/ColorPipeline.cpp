// ColorPipeline implementation: the embedded ACES config built in code, config loading with the
// CLI > $OCIO > embedded precedence, display/view selection with error messages that list the valid names,
// and extraction of the selected processor for the CPU (reference) and the GPU (GLSL 4.0 text, LUTs and
// dynamic uniforms). This is the only file of the engine that includes OpenColorIO; every OCIO::Exception
// is caught here and rethrown as ColorError (STYLE.md, "Errors").
#include "engine/color/ColorPipeline.h"

#include "engine/Log.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace OCIO = OCIO_NAMESPACE;

namespace pacifica::color {
namespace {

constexpr const char* EMBEDDED_SOURCE = "embedded default";
constexpr const char* GPU_FUNCTION_NAME = "pacificaOCIODisplay";
constexpr const char* GPU_RESOURCE_PREFIX = "pacifica_ocio";

// Names shared with the ACES studio config (studio-config-v1.0.0_aces-v1.3_ocio-v2.1.ocio) except the
// display, which we name "sRGB" (the studio config's is "sRGB - Display").
constexpr const char* CS_ACES2065_1 = "ACES2065-1";
constexpr const char* CS_LINEAR_REC709 = "Linear Rec.709 (sRGB)";
constexpr const char* CS_XYZ_D65 = "CIE-XYZ-D65";
constexpr const char* CS_SRGB_DISPLAY = "sRGB - Display";
constexpr const char* DISPLAY_SRGB = "sRGB";
constexpr const char* VIEW_ACES_SDR = "ACES 1.0 - SDR Video";
constexpr const char* VIEW_UNTONEMAPPED = "Un-tone-mapped";

// ACES2065-1 (AP0, D60) -> linear Rec.709 (D65, Bradford), copied from the studio config's
// "Linear Rec.709 (sRGB)" colour space (CLFtransformID urn:aswf:ocio:transformId:1.0:OCIO:Utility:
// AP0_to_Linear_Rec709:1.0). Row-major 4x4 as OCIO's MatrixTransform expects.
constexpr double AP0_TO_LINEAR_REC709[16] = {2.52168618674388,
                                             -1.13413098823972,
                                             -0.387555198504164,
                                             0, //
                                             -0.276479914229922,
                                             1.37271908766826,
                                             -0.096239173438334,
                                             0, //
                                             -0.0153780649660342,
                                             -0.152975335867399,
                                             1.16835340083343,
                                             0, //
                                             0,
                                             0,
                                             0,
                                             1};

std::string quotedList(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) {
        if (!out.empty())
            out += ", ";
        out += '\'' + n + '\'';
    }
    return out.empty() ? "(none)" : out;
}

OCIO::BuiltinTransformRcPtr builtin(const char* style) {
    OCIO::BuiltinTransformRcPtr t = OCIO::BuiltinTransform::Create();
    t->setStyle(style);
    return t;
}

// The embedded config. It mirrors the studio config's structure (OCIO v2 scene and display reference
// spaces, view transforms, a display colour space per display) so that the ACES SDR view produces the
// same numbers as the studio config's "ACES 1.0 - SDR Video" view on "sRGB - Display":
//   scene_linear (Linear Rec.709) -> ACES2065-1 (inverse of the matrix above)
//     -> view transform: BuiltinTransform "ACES-OUTPUT - ACES2065-1_to_CIE-XYZ-D65 - SDR-VIDEO_1.0"
//     -> display colour space: BuiltinTransform "DISPLAY - CIE-XYZ-D65_to_sRGB" (piecewise sRGB encoding).
// "Un-tone-mapped" uses the studio config's view transform, "UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD"; composed
// with the Rec.709 -> AP0 matrix it is the plain Rec.709 -> CIE XYZ (D65) matrix (Bradford there and back),
// so the view is linear Rec.709 encoded with the sRGB curve and nothing else.
OCIO::ConstConfigRcPtr buildEmbeddedConfig() {
    OCIO::ConfigRcPtr config = OCIO::Config::Create();
    config->setMajorVersion(2);
    config->setMinorVersion(1);
    config->setName("pacifica-embedded_aces-v1.3_ocio-v2.1");
    config->setDescription(
        "Pacifica's embedded config: scene-linear Rec.709 to sRGB through the ACES 1.0 SDR "
        "video output transform, or un-tone-mapped. Mirrors the structure of the ACES studio "
        "config v1.0.0 (ACES v1.3, OCIO v2.1).");

    OCIO::ColorSpaceRcPtr aces = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_SCENE);
    aces->setName(CS_ACES2065_1);
    aces->setFamily("ACES");
    aces->setEncoding("scene-linear");
    aces->setDescription("The \"Academy Color Encoding System\" reference colorspace.");
    config->addColorSpace(aces);

    OCIO::ColorSpaceRcPtr lin709 = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_SCENE);
    lin709->setName(CS_LINEAR_REC709);
    lin709->setFamily("Utility");
    lin709->setEncoding("scene-linear");
    lin709->setDescription("Linear Rec.709 primaries, D65 white point: the renderer's scene-linear space.");
    OCIO::MatrixTransformRcPtr toRec709 = OCIO::MatrixTransform::Create();
    toRec709->setMatrix(AP0_TO_LINEAR_REC709);
    lin709->setTransform(toRec709, OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    config->addColorSpace(lin709);

    OCIO::ColorSpaceRcPtr xyz = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_DISPLAY);
    xyz->setName(CS_XYZ_D65);
    xyz->setDescription("The \"CIE XYZ (D65)\" display connection colorspace.");
    config->addColorSpace(xyz);

    OCIO::ColorSpaceRcPtr srgb = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_DISPLAY);
    srgb->setName(CS_SRGB_DISPLAY);
    srgb->setFamily("Display");
    srgb->setEncoding("sdr-video");
    srgb->setDescription("Convert CIE XYZ (D65 white) to sRGB (piecewise EOTF)");
    srgb->setTransform(builtin("DISPLAY - CIE-XYZ-D65_to_sRGB"), OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    config->addColorSpace(srgb);

    OCIO::ViewTransformRcPtr sdr = OCIO::ViewTransform::Create(OCIO::REFERENCE_SPACE_SCENE);
    sdr->setName(VIEW_ACES_SDR);
    sdr->setDescription("Component of ACES Output Transforms for SDR D65 video "
                        "(urn:ampas:aces:transformId:v1.5:ODT.Academy.RGBmonitor_100nits_dim.a1.0.3)");
    sdr->setTransform(builtin("ACES-OUTPUT - ACES2065-1_to_CIE-XYZ-D65 - SDR-VIDEO_1.0"),
                      OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE);
    config->addViewTransform(sdr);

    OCIO::ViewTransformRcPtr untonemapped = OCIO::ViewTransform::Create(OCIO::REFERENCE_SPACE_SCENE);
    untonemapped->setName(VIEW_UNTONEMAPPED);
    untonemapped->setDescription("No tone mapping: scene-linear values encoded for the display as they are.");
    untonemapped->setTransform(builtin("UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD"),
                               OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE);
    config->addViewTransform(untonemapped);
    config->setDefaultViewTransformName(VIEW_UNTONEMAPPED);

    // The first view of a display is its default view.
    config->addDisplayView(DISPLAY_SRGB, VIEW_ACES_SDR, VIEW_ACES_SDR, CS_SRGB_DISPLAY, "", "", "");
    config->addDisplayView(DISPLAY_SRGB, VIEW_UNTONEMAPPED, VIEW_UNTONEMAPPED, CS_SRGB_DISPLAY, "", "", "");

    config->setRole(OCIO::ROLE_SCENE_LINEAR, CS_LINEAR_REC709);
    config->setRole(OCIO::ROLE_DEFAULT, CS_LINEAR_REC709);
    config->setRole(OCIO::ROLE_INTERCHANGE_SCENE, CS_ACES2065_1);
    config->setRole(OCIO::ROLE_INTERCHANGE_DISPLAY, CS_XYZ_D65);
    // Like the studio config: the connection and display colour spaces are reached through views only.
    config->setInactiveColorSpaces((std::string(CS_XYZ_D65) + ", " + CS_SRGB_DISPLAY).c_str());

    config->validate(); // throws OCIO::Exception: a bug here, reported by createDefault() as ColorError
    return config;
}

} // namespace

struct ColorPipeline::Impl {
    OCIO::ConstConfigRcPtr config;
    std::string source;
    std::string display;
    std::string view;
    std::string input; // colour space the processors start from; empty = the scene_linear role
    OCIO::ConstProcessorRcPtr processor;
    OCIO::ConstCPUProcessorRcPtr cpu;

    // "config 'path'" or "embedded config", for messages.
    std::string where() const {
        return source == EMBEDDED_SOURCE ? std::string("embedded config") : "config '" + source + "'";
    }
    std::vector<std::string> displayList() const {
        std::vector<std::string> out;
        for (int i = 0; i < config->getNumDisplays(); ++i)
            out.emplace_back(config->getDisplay(i));
        return out;
    }
    void requireDisplay(const std::string& name) const {
        const std::vector<std::string> all = displayList();
        if (std::find(all.begin(), all.end(), name) == all.end())
            throw ColorError("ColorPipeline: unknown display '" + name + "' in " + where() +
                             "; valid displays: " + quotedList(all));
    }
    std::vector<std::string> viewList(const std::string& name) const {
        requireDisplay(name);
        std::vector<std::string> out;
        for (int i = 0; i < config->getNumViews(name.c_str()); ++i)
            out.emplace_back(config->getView(name.c_str(), i));
        return out;
    }
};

ColorPipeline::ColorPipeline(std::unique_ptr<Impl> impl) : mImpl(std::move(impl)) {}
ColorPipeline::ColorPipeline(const ColorPipeline& other) : mImpl(std::make_unique<Impl>(*other.mImpl)) {}
ColorPipeline& ColorPipeline::operator=(const ColorPipeline& other) {
    if (this != &other)
        mImpl = std::make_unique<Impl>(*other.mImpl);
    return *this;
}
ColorPipeline::ColorPipeline(ColorPipeline&&) noexcept = default;
ColorPipeline& ColorPipeline::operator=(ColorPipeline&&) noexcept = default;
ColorPipeline::~ColorPipeline() = default;

ColorPipeline ColorPipeline::createDefault() {
    auto impl = std::make_unique<Impl>();
    impl->source = EMBEDDED_SOURCE;
    try {
        impl->config = buildEmbeddedConfig();
    } catch (const OCIO::Exception& e) {
        throw ColorError(std::string("ColorPipeline::createDefault(): embedded config is invalid: ") +
                         e.what());
    }
    ColorPipeline pipeline(std::move(impl));
    pipeline.select("", "");
    return pipeline;
}

ColorPipeline ColorPipeline::fromFile(const std::filesystem::path& path) {
    auto impl = std::make_unique<Impl>();
    impl->source = path.string();
    // OCIO's own message for a missing file is only "Error could not read '...' OCIO profile."; say why.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw ColorError("ColorPipeline::fromFile(): OCIO config '" + path.string() +
                         "' does not exist or is not a regular file");
    try {
        impl->config = OCIO::Config::CreateFromFile(path.string().c_str());
    } catch (const OCIO::Exception& e) {
        throw ColorError("ColorPipeline::fromFile(): cannot load OCIO config '" + path.string() +
                         "': " + e.what());
    }
    ColorPipeline pipeline(std::move(impl));
    if (const std::string report = pipeline.validateReport(); !report.empty())
        logWarning("ColorPipeline: OCIO config '" + path.string() + "' does not validate: " + report);
    pipeline.select("", "");
    return pipeline;
}

ColorPipeline ColorPipeline::fromEnvironmentOr(const std::optional<std::filesystem::path>& cliOverride) {
    if (cliOverride)
        return fromFile(*cliOverride);
    if (const char* env = std::getenv("OCIO"); env && *env) {
        try {
            return fromFile(env);
        } catch (const ColorError& e) {
            throw ColorError(std::string("$OCIO: ") + e.what());
        }
    }
    return createDefault();
}

const std::string& ColorPipeline::source() const {
    return mImpl->source;
}

std::string ColorPipeline::configDescription() const {
    if (const char* name = mImpl->config->getName(); name && *name)
        return name;
    if (mImpl->source == EMBEDDED_SOURCE)
        return mImpl->source;
    return std::filesystem::path(mImpl->source).stem().string();
}

std::string ColorPipeline::validateReport() const {
    try {
        mImpl->config->validate();
    } catch (const OCIO::Exception& e) {
        return e.what();
    }
    return {};
}

std::vector<std::string> ColorPipeline::displays() const {
    return mImpl->displayList();
}

std::vector<std::string> ColorPipeline::views(const std::string& display) const {
    return mImpl->viewList(display);
}

std::string ColorPipeline::defaultDisplay() const {
    const char* d = mImpl->config->getDefaultDisplay();
    return d ? d : "";
}

std::string ColorPipeline::defaultView(const std::string& display) const {
    mImpl->requireDisplay(display);
    const char* v = mImpl->config->getDefaultView(display.c_str());
    return v ? v : "";
}

void ColorPipeline::select(const std::string& display, const std::string& view) {
    Impl& impl = *mImpl;
    const std::string d = display.empty() ? defaultDisplay() : display;
    if (d.empty())
        throw ColorError("ColorPipeline::select(): " + impl.where() +
                         " defines no display ('displays' is empty)");
    const std::vector<std::string> valid = impl.viewList(d); // throws for an unknown display
    const std::string v = view.empty() ? defaultView(d) : view;
    if (std::find(valid.begin(), valid.end(), v) == valid.end())
        throw ColorError("ColorPipeline::select(): unknown view '" + v + "' for display '" + d + "' in " +
                         impl.where() + "; valid views: " + quotedList(valid));
    if (impl.input.empty() && !impl.config->getColorSpace(OCIO::ROLE_SCENE_LINEAR))
        throw ColorError("ColorPipeline::select(): " + impl.where() +
                         " has no 'scene_linear' role (roles: the renderer's input space)");
    const char* from = impl.input.empty() ? OCIO::ROLE_SCENE_LINEAR : impl.input.c_str();
    try {
        OCIO::ConstProcessorRcPtr processor =
            impl.config->getProcessor(from, d.c_str(), v.c_str(), OCIO::TRANSFORM_DIR_FORWARD);
        OCIO::ConstCPUProcessorRcPtr cpu = processor->getDefaultCPUProcessor();
        impl.processor = std::move(processor);
        impl.cpu = std::move(cpu);
    } catch (const OCIO::Exception& e) {
        throw ColorError("ColorPipeline::select(): " + impl.where() + ": cannot build the processor from '" +
                         from + "' to display '" + d + "', view '" + v + "': " + e.what());
    }
    impl.display = d;
    impl.view = v;
}

std::string ColorPipeline::linearRec709ColorSpace() const {
    // Names and aliases used for linear Rec.709 / sRGB primaries by the ACES studio and CG configs, Blender
    // and common hand-written configs (getColorSpace() resolves aliases).
    for (const char* name : {"Linear Rec.709 (sRGB)", "lin_rec709_srgb", "lin_rec709",
                             "Utility - Linear - sRGB", "Linear sRGB", "lin_srgb", "Linear"})
        if (const OCIO::ConstColorSpaceRcPtr cs = mImpl->config->getColorSpace(name))
            return cs->getName();
    return "";
}

void ColorPipeline::setInput(const std::string& colorSpace) {
    if (!colorSpace.empty() && !mImpl->config->getColorSpace(colorSpace.c_str()))
        throw ColorError("ColorPipeline::setInput(): " + mImpl->where() + " has no colour space '" +
                         colorSpace + "'");
    mImpl->input = colorSpace;
    if (!mImpl->display.empty())
        select(mImpl->display, mImpl->view);
}

const std::string& ColorPipeline::input() const {
    return mImpl->input;
}

const std::string& ColorPipeline::selectedDisplay() const {
    return mImpl->display;
}
const std::string& ColorPipeline::selectedView() const {
    return mImpl->view;
}

void ColorPipeline::applyCpu(float* rgba, std::size_t pixelCount) const {
    if (pixelCount == 0)
        return;
    try {
        OCIO::PackedImageDesc image(rgba, static_cast<long>(pixelCount), 1, 4);
        mImpl->cpu->apply(image);
    } catch (const OCIO::Exception& e) {
        throw ColorError("ColorPipeline::applyCpu(): " + mImpl->where() + ": " + e.what());
    }
}

bool ColorPipeline::decodeDisplayCpu(float* rgba, std::size_t pixelCount) const {
    const Impl& impl = *mImpl;
    try {
        std::string name = impl.config->getDisplayViewColorSpaceName(impl.display.c_str(), impl.view.c_str());
        if (name ==
            OCIO::OCIO_VIEW_USE_DISPLAY_NAME) // v2 views: the display colour space is named as the display
            name = impl.display;
        const OCIO::ConstColorSpaceRcPtr cs = impl.config->getColorSpace(name.c_str());
        if (!cs || cs->getReferenceSpaceType() != OCIO::REFERENCE_SPACE_DISPLAY)
            return false;
        OCIO::ConstProcessorRcPtr processor;
        if (const OCIO::ConstTransformRcPtr to = cs->getTransform(OCIO::COLORSPACE_DIR_TO_REFERENCE))
            processor = impl.config->getProcessor(to, OCIO::TRANSFORM_DIR_FORWARD);
        else if (const OCIO::ConstTransformRcPtr from = cs->getTransform(OCIO::COLORSPACE_DIR_FROM_REFERENCE))
            processor = impl.config->getProcessor(from, OCIO::TRANSFORM_DIR_INVERSE);
        else
            return false;
        if (pixelCount > 0) {
            OCIO::PackedImageDesc image(rgba, static_cast<long>(pixelCount), 1, 4);
            processor->getDefaultCPUProcessor()->apply(image);
        }
        return true;
    } catch (const OCIO::Exception& e) {
        throw ColorError("ColorPipeline::decodeDisplayCpu(): " + impl.where() + ": " + e.what());
    }
}

namespace {

/// The 1D LUTs: OCIO declares a sampler1D when height == 1 and a sampler2D when it had to fold a long LUT
/// into rows (GpuShaderCreator::addTexture: "Add a 2D texture (1D texture if height equals 1)").
void addLuts1D(const OCIO::GpuShaderDescRcPtr& desc, std::vector<ColorPipeline::GpuShader::Lut>& luts) {
    for (unsigned i = 0; i < desc->getNumTextures(); ++i) {
        const char* textureName = nullptr;
        const char* samplerName = nullptr;
        unsigned width = 0, height = 0;
        OCIO::GpuShaderDesc::TextureType channel = OCIO::GpuShaderDesc::TEXTURE_RGB_CHANNEL;
        OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
        desc->getTexture(i, textureName, samplerName, width, height, channel, interpolation);
        const float* values = nullptr;
        desc->getTextureValues(i, values);
        ColorPipeline::GpuShader::Lut lut;
        lut.samplerName = samplerName;
        lut.dims = height > 1 ? 2 : 1;
        lut.width = static_cast<int>(width);
        lut.height = static_cast<int>(height);
        lut.depth = 1;
        lut.channels = channel == OCIO::GpuShaderDesc::TEXTURE_RED_CHANNEL ? 1 : 3;
        lut.linear = interpolation != OCIO::INTERP_NEAREST;
        lut.values.assign(values, values + static_cast<size_t>(width) * height * lut.channels);
        luts.push_back(std::move(lut));
    }
}

void addLuts3D(const OCIO::GpuShaderDescRcPtr& desc, std::vector<ColorPipeline::GpuShader::Lut>& luts) {
    for (unsigned i = 0; i < desc->getNum3DTextures(); ++i) {
        const char* textureName = nullptr;
        const char* samplerName = nullptr;
        unsigned edge = 0;
        OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
        desc->get3DTexture(i, textureName, samplerName, edge, interpolation);
        const float* values = nullptr;
        desc->get3DTextureValues(i, values);
        ColorPipeline::GpuShader::Lut lut;
        lut.samplerName = samplerName;
        lut.dims = 3;
        lut.width = lut.height = lut.depth = static_cast<int>(edge);
        lut.channels = 3;
        lut.linear = interpolation != OCIO::INTERP_NEAREST;
        lut.values.assign(values, values + static_cast<size_t>(edge) * edge * edge * 3);
        luts.push_back(std::move(lut));
    }
}

/// Dynamic uniforms: OCIO's getters read dynamic properties owned by the shader description, so every
/// wrapper holds `desc` to keep them alive as long as the GpuShader is. `where` names the pipeline in the
/// error for a uniform of an unknown type.
void addUniforms(const OCIO::GpuShaderDescRcPtr& desc,
                 std::vector<ColorPipeline::GpuShader::Uniform>& uniforms, const std::string& where) {
    using Uniform = ColorPipeline::GpuShader::Uniform;
    for (unsigned i = 0; i < desc->getNumUniforms(); ++i) {
        OCIO::GpuShaderDesc::UniformData data;
        const char* name = desc->getUniform(i, data);
        Uniform u;
        u.name = name;
        switch (data.m_type) {
        case OCIO::UNIFORM_DOUBLE:
            u.kind = Uniform::Kind::Double;
            u.getDouble = [desc, get = data.m_getDouble] { return get(); };
            break;
        case OCIO::UNIFORM_BOOL:
            u.kind = Uniform::Kind::Bool;
            u.getBool = [desc, get = data.m_getBool] { return get(); };
            break;
        case OCIO::UNIFORM_FLOAT3:
            u.kind = Uniform::Kind::Float3;
            u.getFloat3 = [desc, get = data.m_getFloat3] { return std::array<float, 3>(get()); };
            break;
        case OCIO::UNIFORM_VECTOR_FLOAT:
            u.kind = Uniform::Kind::VectorFloat;
            u.getVectorFloat = [desc, v = data.m_vectorFloat] {
                const float* p = v.m_getVector();
                return std::vector<float>(p, p + v.m_getSize());
            };
            break;
        case OCIO::UNIFORM_VECTOR_INT:
            u.kind = Uniform::Kind::VectorInt;
            u.getVectorInt = [desc, v = data.m_vectorInt] {
                const int* p = v.m_getVector();
                return std::vector<int>(p, p + v.m_getSize());
            };
            break;
        case OCIO::UNIFORM_UNKNOWN:
            throw ColorError("ColorPipeline::gpuShader(): " + where + ": uniform '" + u.name +
                             "' has an unknown type");
        }
        uniforms.push_back(std::move(u));
    }
}

} // namespace

ColorPipeline::GpuShader ColorPipeline::gpuShader() const {
    const Impl& impl = *mImpl;
    GpuShader out;
    try {
        OCIO::GpuShaderDescRcPtr desc = OCIO::GpuShaderDesc::CreateShaderDesc();
        desc->setLanguage(OCIO::GPU_LANGUAGE_GLSL_4_0);
        desc->setFunctionName(GPU_FUNCTION_NAME);
        desc->setResourcePrefix(GPU_RESOURCE_PREFIX);
        impl.processor->getDefaultGPUProcessor()->extractGpuShaderInfo(desc);
        out.functionName = desc->getFunctionName();
        out.glslText = desc->getShaderText();
        addLuts1D(desc, out.luts);
        addLuts3D(desc, out.luts);
        addUniforms(desc, out.uniforms, impl.where());
    } catch (const OCIO::Exception& e) {
        throw ColorError("ColorPipeline::gpuShader(): " + impl.where() + ", display '" + impl.display +
                         "', view '" + impl.view + "': " + e.what());
    }
    return out;
}

} // namespace pacifica::color
