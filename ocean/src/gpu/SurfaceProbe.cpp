// SurfaceProbe: transform-feedback evaluation of a model's GLSL at given points (see the header).
#include "gpu/SurfaceProbe.h"

#include "engine/gl/Shader.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanShaders.h"

#include <epoxy/gl.h>

namespace pacifica::ocean {

ProbeResult probeSurface(SurfaceGpu& gpu, const std::vector<glm::vec2>& rel, const glm::dvec3& cameraWorld,
                         double time) {
    std::vector<gl::ShaderSource> sources;
    sources.push_back({"<ocean constants>", shaderConstantDefines()});
    for (const std::string& f : gpu.glslFiles())
        sources.push_back({f, std::string(shaderText(f))});
    sources.push_back({"<probe.vert>", "layout(location = 0) in vec2 aRel;\n"
                                       "out vec3 vDisplacement;\nout vec3 vLighting;\nout vec2 vFoam;\n"
                                       "void main() {\n"
                                       "    vDisplacement = modelDisplacement(aRel);\n"
                                       "    vLighting = modelLighting(aRel);\n"
                                       "#ifdef MODEL_HAS_FOAM_INPUTS\n"
                                       "    vFoam = modelFoamInputs(aRel);\n"
                                       "#else\n"
                                       "    vFoam = vec2(vDisplacement.z, 1.0);\n"
                                       "#endif\n"
                                       "    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n}\n"});
    gl::Program program = gl::buildProgram({{gl::ShaderStage::Vertex, sources}}, "surface probe",
                                           {"vDisplacement", "vLighting", "vFoam"});
    gl::StateGuard guard;
    gpu.update(time, cameraWorld);
    // Drawing needs a complete framebuffer even with rasterizer discard (headless contexts have none).
    gl::Texture color = gl::Texture::create2D(GL_RGBA8, 1, 1);
    gl::Framebuffer fbo = gl::Framebuffer::create();
    fbo.attachColor(0, color);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo.id());
    glUseProgram(program.id());
    gpu.bind(program.id(), 0, time, cameraWorld);

    const size_t n = rel.size();
    gl::Buffer input = gl::Buffer::create(n * sizeof(glm::vec2), rel.data());
    constexpr size_t STRIDE = 8; // floats per point: displacement, lighting, foam
    gl::Buffer output = gl::Buffer::create(n * STRIDE * sizeof(float), nullptr);
    gl::VertexArray vao = gl::VertexArray::create();
    glVertexArrayVertexBuffer(vao.id(), 0, input.id(), 0, sizeof(glm::vec2));
    glEnableVertexArrayAttrib(vao.id(), 0);
    glVertexArrayAttribFormat(vao.id(), 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao.id(), 0, 0);
    glBindVertexArray(vao.id());
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, output.id());
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    std::vector<float> interleaved(n * STRIDE);
    glGetNamedBufferSubData(output.id(), 0, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                            interleaved.data());
    ProbeResult r;
    r.displacement.resize(n);
    r.lighting.resize(n);
    r.foam.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const float* p = &interleaved[i * STRIDE];
        r.displacement[i] = glm::vec3(p[0], p[1], p[2]);
        r.lighting[i] = glm::vec3(p[3], p[4], p[5]);
        r.foam[i] = glm::vec2(p[6], p[7]);
    }
    return r;
}

} // namespace pacifica::ocean
