// The CPU/GPU interface (ocean/src/gpu/GpuInterface.h) against the driver: the real effects.glsl and the
// FFT passes compiled with the ocean's generated #defines; every member of ExplosionGpu, WakeGpu and
// EffectTileGpu (the effects field pass, effects_field.comp) sits at
// the offset the C++ struct gives it, the arrays' strides equal sizeof, and each storage block is bound at
// its slot of the StorageBinding enum. A member added, removed or reordered on one side fails here.
#include "engine/gl/GlContext.h"
#include "engine/gl/Shader.h"
#include "gpu/GpuInterface.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanShaders.h"

#include "GlLayerTest.h"
#include <epoxy/gl.h>

#include <gtest/gtest.h>

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace pacifica;
using namespace pacifica::ocean;

namespace {

/// A compute program of the ocean's generated #defines (both effect kinds on), then `file` (an embedded
/// shader), then `main` (test code, or nothing when the file has its own).
gl::Program effectsCompute(const char* file, const std::string& main, const std::string& name) {
    std::vector<gl::ShaderSource> sources{
        {"<ocean constants>", shaderConstantDefines()},
        {"<effect constants>",
         effectConstantDefines() + "#define EFFECTS_EXPLOSIONS\n#define EFFECTS_WAKES\n"},
        {file, std::string(shaderText(file))}};
    if (!main.empty())
        sources.push_back({"<test>", main});
    return gl::buildProgram({{gl::ShaderStage::Compute, sources}}, "GPU interface test: " + name);
}

/// A compute program over effects.glsl that reads every member of both structs (so none is optimised out).
gl::Program effectsProgram() {
    return effectsCompute("effects.glsl", R"(
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Sink { float sink[]; };
void main() {
    ExplosionGpu e = uExplosions[0];
    WakeGpu w = uWakes[0];
    sink[0] = e.centre.x + e.centre.y + e.gridRadius + e.amplitude + e.wavenumber + e.phase + e.coreRadius +
              e.front + e.frontWidth + e.crownFoam + e.crownRadius + e.peakAmplitude + e.slick + e.slickRadius;
    sink[1] = w.ship.x + w.ship.y + w.gridRadius + w.points + w.shipLength + w.beam + w.waveLife + w.foamLife +
              w.boxMin.x + w.boxMin.y + w.boxMax.x + w.boxMax.y;
    sink[2] = uWakePoints[0].x;
}
)",
                          "effects");
}

/// The real effects field pass: effects.glsl, then effects_field.comp (its own main).
gl::Program fieldProgram() {
    const std::string field(shaderText("effects_field.comp"));
    return effectsCompute("effects.glsl", field, "effects field");
}

/// effects_sample.glsl with a main that reads the field and the grid list.
gl::Program sampleProgram() {
    return effectsCompute("effects_sample.glsl", R"(
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Sink { float sink[]; };
void main() {
    sink[0] = effectFieldAt(vec2(1.0)).x + (insideEffectGrid(vec2(0.0)) ? 1.0 : 0.0);
}
)",
                          "effects sample");
}

GLint resource(GLuint program, GLenum interface, const std::string& name, GLenum property) {
    const GLuint index = glGetProgramResourceIndex(program, interface, name.c_str());
    EXPECT_NE(index, GL_INVALID_INDEX) << name << " is not in the program";
    if (index == GL_INVALID_INDEX)
        return -1;
    GLint value = -1;
    glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &value);
    return value;
}

void expectOffsets(GLuint program, const std::string& array, size_t size,
                   const std::vector<std::pair<const char*, size_t>>& members) {
    for (const auto& [member, offset] : members) {
        const std::string name = array + "[0]." + member;
        EXPECT_EQ(resource(program, GL_BUFFER_VARIABLE, name, GL_OFFSET), static_cast<GLint>(offset)) << name;
        EXPECT_EQ(resource(program, GL_BUFFER_VARIABLE, name, GL_TOP_LEVEL_ARRAY_STRIDE),
                  static_cast<GLint>(size))
            << name;
    }
}

class GpuInterface : public gltest::GlTest {};

TEST_F(GpuInterface, EffectStructsMatchTheDriversLayout) {
    const gl::Program program = effectsProgram();
    const GLuint p = program.id();
    expectOffsets(p, "uExplosions", sizeof(ExplosionGpu),
                  {{"centre", offsetof(ExplosionGpu, centre)},
                   {"gridRadius", offsetof(ExplosionGpu, gridRadius)},
                   {"amplitude", offsetof(ExplosionGpu, amplitude)},
                   {"wavenumber", offsetof(ExplosionGpu, wavenumber)},
                   {"phase", offsetof(ExplosionGpu, phase)},
                   {"coreRadius", offsetof(ExplosionGpu, coreRadius)},
                   {"front", offsetof(ExplosionGpu, front)},
                   {"frontWidth", offsetof(ExplosionGpu, frontWidth)},
                   {"crownFoam", offsetof(ExplosionGpu, crownFoam)},
                   {"crownRadius", offsetof(ExplosionGpu, crownRadius)},
                   {"peakAmplitude", offsetof(ExplosionGpu, peakAmplitude)},
                   {"slick", offsetof(ExplosionGpu, slick)},
                   {"slickRadius", offsetof(ExplosionGpu, slickRadius)}});
    expectOffsets(p, "uWakes", sizeof(WakeGpu),
                  {{"ship", offsetof(WakeGpu, ship)},
                   {"gridRadius", offsetof(WakeGpu, gridRadius)},
                   {"points", offsetof(WakeGpu, points)},
                   {"shipLength", offsetof(WakeGpu, shipLength)},
                   {"beam", offsetof(WakeGpu, beam)},
                   {"waveLife", offsetof(WakeGpu, waveLife)},
                   {"foamLife", offsetof(WakeGpu, foamLife)},
                   {"boxMin", offsetof(WakeGpu, boxMin)},
                   {"boxMax", offsetof(WakeGpu, boxMax)}});
    EXPECT_EQ(resource(p, GL_BUFFER_VARIABLE, "uWakePoints[0]", GL_ARRAY_STRIDE), 16); // two vec4 per point
    const gl::Program field = fieldProgram();
    expectOffsets(field.id(), "uTiles", sizeof(EffectTileGpu),
                  {{"level", offsetof(EffectTileGpu, level)},
                   {"tileX", offsetof(EffectTileGpu, tileX)},
                   {"tileY", offsetof(EffectTileGpu, tileY)},
                   {"first", offsetof(EffectTileGpu, first)},
                   {"explosions", offsetof(EffectTileGpu, explosions)},
                   {"wakes", offsetof(EffectTileGpu, wakes)}});
}

TEST_F(GpuInterface, StorageBlocksSitAtTheEnumsSlots) {
    const gl::Program program = effectsProgram();
    const std::vector<std::pair<const char*, int>> blocks = {
        {"EffectExplosions", EFFECT_EXPLOSIONS_BINDING},  {"EffectWakes", EFFECT_WAKES_BINDING},
        {"EffectWakePoints", EFFECT_WAKE_POINTS_BINDING}, {"EffectFieldTiles", EFFECT_FIELD_TILES_BINDING},
        {"EffectFieldLists", EFFECT_FIELD_LISTS_BINDING}, {"EffectGrids", EFFECT_GRIDS_BINDING}};
    const gl::Program field = fieldProgram();
    const gl::Program sample = sampleProgram();
    for (const auto& [block, slot] : blocks) {
        const std::string b = block;
        const GLuint p = b == "EffectGrids"               ? sample.id()
                         : b.rfind("EffectField", 0) == 0 ? field.id()
                                                          : program.id();
        EXPECT_EQ(resource(p, GL_SHADER_STORAGE_BLOCK, block, GL_BUFFER_BINDING), slot) << block;
    }
    // The field's image at its unit.
    const GLint image = glGetUniformLocation(field.id(), "uFieldImage");
    ASSERT_GE(image, 0);
    GLint unit = -1;
    glGetUniformiv(field.id(), image, &unit);
    EXPECT_EQ(unit, EFFECT_FIELD_IMAGE_UNIT);
    // The slots the effects use are theirs alone.
    for (int other : {FFT_PLANES_BINDING, FFT_H0_PAIRS_BINDING, FFT_OMEGA_MULTIPLES_BINDING,
                      FFT_TWIDDLES_BINDING, SHADE_TILE_BINDING})
        for (const auto& [block, slot] : blocks)
            EXPECT_NE(other, slot) << block;

    // The FFT spectrum pass: its three blocks at their slots.
    const std::string defines =
        "#define FFT_N 64u\n#define FFT_LOG2N 6u\n#define FFT_THREADS 32\n#define FFT_PLANES 8u\n"
        "#define TILE_GROUP 8\n#define JACOBIAN_FLOOR 0.1\n#define FFT_MAX_LAYERS 8\n";
    const gl::Program spectrum =
        gl::buildProgram({{gl::ShaderStage::Compute,
                           {{"<ocean constants>", shaderConstantDefines()},
                            {"<defines>", defines},
                            {"fft_spectrum.comp", std::string(shaderText("fft_spectrum.comp"))}}}},
                         "GPU interface test: FFT spectrum");
    EXPECT_EQ(resource(spectrum.id(), GL_SHADER_STORAGE_BLOCK, "Planes", GL_BUFFER_BINDING),
              FFT_PLANES_BINDING);
    EXPECT_EQ(resource(spectrum.id(), GL_SHADER_STORAGE_BLOCK, "H0Pairs", GL_BUFFER_BINDING),
              FFT_H0_PAIRS_BINDING);
    EXPECT_EQ(resource(spectrum.id(), GL_SHADER_STORAGE_BLOCK, "OmegaMultiples", GL_BUFFER_BINDING),
              FFT_OMEGA_MULTIPLES_BINDING);
}

TEST_F(GpuInterface, BindingDefinesAreGeneratedFromTheEnum) {
    const std::string d = shaderConstantDefines();
    for (const auto& [name, slot] :
         std::vector<std::pair<std::string, int>>{{"FFT_PLANES_BINDING", FFT_PLANES_BINDING},
                                                  {"FFT_TWIDDLES_BINDING", FFT_TWIDDLES_BINDING},
                                                  {"SHADE_TILE_BINDING", SHADE_TILE_BINDING},
                                                  {"EFFECT_EXPLOSIONS_BINDING", EFFECT_EXPLOSIONS_BINDING},
                                                  {"EFFECT_FIELD_TILES_BINDING", EFFECT_FIELD_TILES_BINDING},
                                                  {"EFFECT_GRIDS_BINDING", EFFECT_GRIDS_BINDING},
                                                  {"EFFECT_FIELD_IMAGE_UNIT", EFFECT_FIELD_IMAGE_UNIT}})
        EXPECT_NE(d.find("#define " + name + " " + std::to_string(slot) + "\n"), std::string::npos) << name;
}

} // namespace
