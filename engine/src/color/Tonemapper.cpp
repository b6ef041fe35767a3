// Tonemapper implementation: builds the fullscreen-triangle program around OCIO's GLSL, uploads the LUT
// textures OCIO describes (1D as GL_TEXTURE_1D, folded 1D as GL_TEXTURE_2D, 3D as RGB32F GL_TEXTURE_3D;
// docs/PLATFORM.md "OpenColorIO 2.1.2"), binds their samplers to texture units 1..N with
// glProgramUniform1i (OCIO declares them without a binding), and refreshes OCIO's dynamic uniforms each run.
#include <epoxy/gl.h>

#include "engine/color/Tonemapper.h"

#include "engine/color/ColorPipeline.h"
#include "engine/gl/Shader.h"

#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pacifica::color {
namespace {

// An owned GL_TEXTURE_1D: gl::Texture only creates 2D and 3D textures, so reuse its handle and deleter.
class Texture1D : public gl::Handle<gl::TextureDeleter> {
public:
    Texture1D() = default;
    explicit Texture1D(GLuint id) : Handle(id, true) {}
};

constexpr const char* VERTEX_SHADER = R"GLSL(
// One triangle covering the viewport: (-1,-1), (3,-1), (-1,3). No vertex buffer; gl_VertexID only.
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
)GLSL";

// Unit 0 holds the scene-linear input; OCIO's LUT samplers take units 1..N.
constexpr GLuint INPUT_UNIT = 0;

std::string fragmentMain(const std::string& functionName) {
    return R"GLSL(
layout(binding = 0) uniform sampler2D pacificaSceneLinear;
layout(location = 0) out vec4 pacificaDisplayColor;

void main() {
    vec4 sceneLinear = texelFetch(pacificaSceneLinear, ivec2(gl_FragCoord.xy), 0);
    vec4 display = )GLSL" +
           functionName + R"GLSL((sceneLinear);
    pacificaDisplayColor = vec4(display.rgb, sceneLinear.a);
}
)GLSL";
}

// Sets the unpack state LUT uploads rely on (tightly packed client memory) and restores the host's.
class UnpackGuard {
public:
    UnpackGuard() {
        for (size_t i = 0; i < PARAMS.size(); ++i)
            glGetIntegerv(PARAMS[i], &mSaved[i]);
        glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &mBuffer);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        for (GLenum p : PARAMS)
            glPixelStorei(p, p == GL_UNPACK_ALIGNMENT ? 4 : 0);
    }
    ~UnpackGuard() {
        for (size_t i = 0; i < PARAMS.size(); ++i)
            glPixelStorei(PARAMS[i], mSaved[i]);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(mBuffer));
    }
    UnpackGuard(const UnpackGuard&) = delete;
    UnpackGuard& operator=(const UnpackGuard&) = delete;

private:
    static constexpr std::array<GLenum, 6> PARAMS = {GL_UNPACK_ALIGNMENT,    GL_UNPACK_ROW_LENGTH,
                                                     GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS,
                                                     GL_UNPACK_SKIP_ROWS,    GL_UNPACK_SKIP_IMAGES};
    std::array<GLint, 6> mSaved{};
    GLint mBuffer = 0;
};

struct BoundUniform {
    ColorPipeline::GpuShader::Uniform uniform;
    GLint location = -1;
};

} // namespace

struct Tonemapper::Impl {
    std::string display;
    std::string view;
    gl::Program program;
    gl::VertexArray vao;
    std::vector<gl::Texture> textures; // 2D and 3D LUTs
    std::vector<Texture1D> textures1D; // 1D LUTs
    std::vector<GLuint> lutIds;        // every LUT in GpuShader::luts order: texture unit = 1 + index
    std::vector<BoundUniform> uniforms;
};

Tonemapper::Tonemapper(const ColorPipeline& pipeline) : mImpl(std::make_unique<Impl>()) {
    Impl& impl = *mImpl;
    impl.display = pipeline.selectedDisplay();
    impl.view = pipeline.selectedView();
    ColorPipeline::GpuShader shader = pipeline.gpuShader();

    const std::string ocioName = "ocio:" + impl.display + "/" + impl.view;
    impl.program = gl::buildProgram(
        {{gl::ShaderStage::Vertex, {{"tonemap.vert", VERTEX_SHADER}}},
         {gl::ShaderStage::Fragment,
          {{ocioName, shader.glslText}, {"tonemap.frag", fragmentMain(shader.functionName)}}}},
        "Tonemapper(" + ocioName + ")");
    impl.vao = gl::VertexArray::create();

    UnpackGuard unpack;
    for (size_t i = 0; i < shader.luts.size(); ++i) {
        const ColorPipeline::GpuShader::Lut& lut = shader.luts[i];
        const GLenum internalFormat = lut.channels == 1 ? GL_R32F : GL_RGB32F;
        const GLenum format = lut.channels == 1 ? GL_RED : GL_RGB;
        const GLenum filter = lut.linear ? GL_LINEAR : GL_NEAREST;
        GLuint id = 0;
        if (lut.dims == 1) {
            glCreateTextures(GL_TEXTURE_1D, 1, &id);
            impl.textures1D.emplace_back(id);
            glTextureStorage1D(id, 1, internalFormat, lut.width);
            glTextureSubImage1D(id, 0, 0, lut.width, format, GL_FLOAT, lut.values.data());
            glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
            glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(filter));
            glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        } else if (lut.dims == 2) {
            gl::Texture t = gl::Texture::create2D(internalFormat, lut.width, lut.height);
            glTextureSubImage2D(t.id(), 0, 0, 0, lut.width, lut.height, format, GL_FLOAT, lut.values.data());
            t.setSampling(filter, filter, GL_CLAMP_TO_EDGE);
            id = t.id();
            impl.textures.push_back(std::move(t));
        } else {
            gl::Texture t = gl::Texture::create3D(internalFormat, lut.width, lut.height, lut.depth);
            glTextureSubImage3D(t.id(), 0, 0, 0, 0, lut.width, lut.height, lut.depth, format, GL_FLOAT,
                                lut.values.data());
            t.setSampling(filter, filter, GL_CLAMP_TO_EDGE);
            id = t.id();
            impl.textures.push_back(std::move(t));
        }
        impl.lutIds.push_back(id);
        const GLint location = impl.program.uniformLocation(lut.samplerName.c_str());
        if (location >= 0)
            glProgramUniform1i(impl.program.id(), location, static_cast<GLint>(INPUT_UNIT + 1 + i));
    }

    for (ColorPipeline::GpuShader::Uniform& u : shader.uniforms) {
        const GLint location = impl.program.uniformLocation(u.name.c_str());
        if (location >= 0) // optimised away: nothing to update
            impl.uniforms.push_back({std::move(u), location});
    }
}

Tonemapper::Tonemapper(Tonemapper&&) noexcept = default;
Tonemapper& Tonemapper::operator=(Tonemapper&&) noexcept = default;
Tonemapper::~Tonemapper() = default;

const std::string& Tonemapper::display() const {
    return mImpl->display;
}
const std::string& Tonemapper::view() const {
    return mImpl->view;
}
int Tonemapper::lutCount() const {
    return static_cast<int>(mImpl->lutIds.size());
}

void Tonemapper::run(const gl::Texture& sceneLinear, const gl::Framebuffer& displayTarget, int width,
                     int height) {
    if (!sceneLinear || width <= 0 || height <= 0)
        throw std::logic_error(
            "Tonemapper::run(): expected a scene-linear texture and a positive size, got texture " +
            std::to_string(sceneLinear.id()) + " and " + std::to_string(width) + "x" +
            std::to_string(height));
    Impl& impl = *mImpl;
    const GLuint program = impl.program.id();

    gl::StateGuard guard;
    const GLboolean srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    const GLboolean stencil = glIsEnabled(GL_STENCIL_TEST);
    GLboolean colorMask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    glGetBooleani_v(GL_COLOR_WRITEMASK, 0, colorMask);

    // Dynamic uniforms first: their values may have changed since the last frame.
    for (const BoundUniform& b : impl.uniforms) {
        using Kind = ColorPipeline::GpuShader::Uniform::Kind;
        switch (b.uniform.kind) {
        case Kind::Double:
            glProgramUniform1f(program, b.location, static_cast<float>(b.uniform.getDouble()));
            break;
        case Kind::Bool:
            glProgramUniform1i(program, b.location, b.uniform.getBool() ? 1 : 0);
            break;
        case Kind::Float3: {
            const std::array<float, 3> v = b.uniform.getFloat3();
            glProgramUniform3f(program, b.location, v[0], v[1], v[2]);
            break;
        }
        case Kind::VectorFloat: {
            const std::vector<float> v = b.uniform.getVectorFloat();
            glProgramUniform1fv(program, b.location, static_cast<GLsizei>(v.size()), v.data());
            break;
        }
        case Kind::VectorInt: {
            const std::vector<int> v = b.uniform.getVectorInt();
            glProgramUniform1iv(program, b.location, static_cast<GLsizei>(v.size()), v.data());
            break;
        }
        }
    }

    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, displayTarget.id());
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB); // OCIO's display colour space already encodes
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

    glUseProgram(program);
    glBindVertexArray(impl.vao.id());
    glBindTextureUnit(INPUT_UNIT, sceneLinear.id());
    for (size_t i = 0; i < impl.lutIds.size(); ++i)
        glBindTextureUnit(static_cast<GLuint>(INPUT_UNIT + 1 + i), impl.lutIds[i]);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glColorMaski(0, colorMask[0], colorMask[1], colorMask[2], colorMask[3]);
    if (srgb)
        glEnable(GL_FRAMEBUFFER_SRGB);
    if (stencil)
        glEnable(GL_STENCIL_TEST);
}

} // namespace pacifica::color
