// OctavesGpu: uploads the octave maps and the vertex filter's texture, runs the combine pass and binds the
// octave uniforms (GPU Gems 2 §18.2.1, §18.2.4, §18.2.5; see the header).
#include "gpu/OctavesGpu.h"

#include "gpu/GpuInterface.h"

#include <epoxy/gl.h>

#include "engine/Time.h"
#include "engine/gl/Shader.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanShaders.h"

#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace pacifica::ocean {
namespace {

/// Local size of octaves_combine.comp in x and y.
constexpr int COMBINE_GROUP = 8;

/// Location of `base[i]` (snprintf: GCC 12 warns falsely about string concatenation here).
GLint arrayLocation(GLuint prog, const char* base, int i) {
    char name[64];
    std::snprintf(name, sizeof name, "%s[%d]", base, i);
    return glGetUniformLocation(prog, name);
}

GLint location(GLuint prog, const char* name) {
    return glGetUniformLocation(prog, name);
}

/// The vertex filter's texture: one 2D array for all displaced octaves, layer = octave * frames + frame.
gl::Texture createFilterMaps(const HeightOctaves& s) {
    const HeightOctavesDesc& d = s.desc();
    const int layers = d.displacedOctaves * d.frames;
    if (layers == 0)
        return {};
    if (d.vertexFilter == VertexFilter::Nearest || d.vertexFilter == VertexFilter::Bilinear ||
        d.vertexFilter == VertexFilter::HardwareBilinear) {
        // Non-mipmapped R16F copy of the heights: texelFetch (Nearest, Bilinear) or texture() with GL_LINEAR
        // (HardwareBilinear). One sampler for all octaves: see octaves.glsl uFilterMaps.
        gl::Texture t = gl::Texture::createArray2D(GL_R16F, d.mapSize, d.mapSize, layers, 1);
        std::vector<uint16_t> half(static_cast<size_t>(layers) * d.mapSize * d.mapSize);
        size_t k = 0;
        for (int o = 0; o < d.displacedOctaves; ++o)
            for (int f = 0; f < d.frames; ++f)
                for (int y = 0; y < d.mapSize; ++y)
                    for (int x = 0; x < d.mapSize; ++x)
                        half[k++] = glm::packHalf1x16(s.heightMip(o, 0, f, x, y));
        glTextureSubImage3D(t.id(), 0, 0, 0, 0, d.mapSize, d.mapSize, layers, GL_RED, GL_HALF_FLOAT,
                            half.data());
        t.setSampling(GL_LINEAR, GL_LINEAR, GL_REPEAT);
        return t;
    }
    // Listing 18-2's packed maps (HeightOctaves::packedTexel, exact in half: the values are half already);
    // Trilinear needs the whole chain (glGenerateMipmap would average the packed neighbours wrongly).
    const int levels = d.vertexFilter == VertexFilter::Trilinear ? s.mipLevels() : 1;
    gl::Texture t = gl::Texture::createArray2D(GL_RGBA16F, d.mapSize, d.mapSize, layers, levels);
    for (int level = 0; level < levels; ++level) {
        const int size = d.mapSize >> level;
        std::vector<uint16_t> half(static_cast<size_t>(layers) * size * size * 4);
        size_t k = 0;
        for (int o = 0; o < d.displacedOctaves; ++o)
            for (int f = 0; f < d.frames; ++f)
                for (int y = 0; y < size; ++y)
                    for (int x = 0; x < size; ++x) {
                        const glm::vec4 p = s.packedTexel(o, level, f, x, y);
                        for (int c = 0; c < 4; ++c)
                            half[k++] = glm::packHalf1x16(p[c]);
                    }
        glTextureSubImage3D(t.id(), level, 0, 0, 0, size, size, layers, GL_RGBA, GL_HALF_FLOAT, half.data());
    }
    t.setSampling(levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST, GL_NEAREST, GL_REPEAT);
    return t;
}

} // namespace

const char* OctavesGpu::variantFile(VertexFilter filter) {
    switch (filter) {
    case VertexFilter::Nearest:
        return "octaves_variant_nearest.glsl";
    case VertexFilter::Bilinear:
        return nullptr;
    case VertexFilter::HardwareBilinear:
        return "octaves_variant_hwbilinear.glsl";
    case VertexFilter::Packed4Tap:
        return "octaves_variant_packed4tap.glsl";
    case VertexFilter::Trilinear:
        return "octaves_variant_trilinear.glsl";
    }
    return nullptr;
}

OctavesGpu::OctavesGpu(std::shared_ptr<const HeightOctaves> surface) : mSurface(std::move(surface)) {
    if (!mSurface)
        throw std::invalid_argument("OctavesGpu::OctavesGpu(): surface is null");
    // Every octave's map in one mipmapped array, layer = octave * frames + frame (all maps share mapSize and
    // frames): one sampler and one texture unit for the lighting loop, however many octaves (it was a
    // sampler array, one unit per octave). glGenerateTextureMipmap filters each layer on its own, as it did
    // per texture: the pixels are bit-identical.
    const std::vector<OctaveMap>& maps = mSurface->maps();
    if (!maps.empty()) {
        const int size = maps.front().size, frames = maps.front().frames;
        const int levels = 1 + static_cast<int>(std::log2(static_cast<double>(size)));
        const int layers = static_cast<int>(maps.size()) * frames;
        mLightMaps = gl::Texture::createArray2D(GL_RGBA16F, size, size, layers, levels);
        for (size_t o = 0; o < maps.size(); ++o) {
            const OctaveMap& map = maps[o];
            if (map.size != size || map.frames != frames)
                throw std::logic_error("OctavesGpu::OctavesGpu(): octave maps differ in size or frames");
            // The CPU copy already holds half-rounded values, so this conversion is exact. The lighting reads
            // only the gradient channels; a displaced octave's h channel carries its foam memory instead
            // (OctaveMap::foam: the living whitecaps, mixed to the frame's time and mipmapped with the rest).
            std::vector<uint16_t> half(map.texels.size());
            for (size_t i = 0; i < half.size(); ++i)
                half[i] =
                    glm::packHalf1x16(i % 4 == 0 && !map.foam.empty() ? map.foam[i / 4] : map.texels[i]);
            glTextureSubImage3D(mLightMaps.id(), 0, 0, 0, static_cast<int>(o) * frames, size, size, frames,
                                GL_RGBA, GL_HALF_FLOAT, half.data());
        }
        glGenerateTextureMipmap(mLightMaps.id());
        mLightMaps.setSampling(GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST, GL_REPEAT); // texelFetch only
        mLightLevels = levels;
        mLightSize = size;
        mLightNow = gl::Texture::createArray2D(GL_RGBA16F, size, size, static_cast<int>(maps.size()), levels);
        mLightNow.setSampling(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
        mLightMixProgram = gl::buildProgram(
            {{gl::ShaderStage::Compute,
              {{"<ocean constants>", shaderConstantDefines()},
               {"octaves_light_mix.comp", std::string(shaderText("octaves_light_mix.comp"))}}}},
            "octaves lighting time mix");
    }
    mFilterMaps = createFilterMaps(*mSurface);

    const HeightOctavesDesc& d = mSurface->desc();
    if (d.combinedDisplacement) {
        mCombined = gl::Texture::createArray2D(GL_R32F, d.combinedSize, d.combinedSize,
                                               mSurface->combinedLevels(), 1);
        mCombined.setSampling(GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
        std::vector<gl::ShaderSource> sources;
        sources.push_back({"<ocean constants>", shaderConstantDefines()});
        if (const char* variant = variantFile(d.vertexFilter))
            sources.push_back({variant, std::string(shaderText(variant))});
        sources.push_back({"octaves.glsl", std::string(shaderText("octaves.glsl"))});
        sources.push_back({"octaves_combine.comp", std::string(shaderText("octaves_combine.comp"))});
        mCombineProgram = gl::buildProgram({{gl::ShaderStage::Compute, sources}},
                                           "octaves combine (" + std::string(toString(d.vertexFilter)) + ")");
        if (arrayLocation(mCombineProgram.id(), "uCombinedOrigin", HeightOctaves::MAX_COMBINED_LEVELS - 1) <
            0)
            throw std::logic_error("OctavesGpu::OctavesGpu(): octaves.glsl's OCTAVES_MAX_COMBINED_LEVELS is "
                                   "smaller than HeightOctaves::MAX_COMBINED_LEVELS " +
                                   std::to_string(HeightOctaves::MAX_COMBINED_LEVELS));
    }
}

std::vector<std::string> OctavesGpu::glslFiles() const {
    const HeightOctavesDesc& d = mSurface->desc();
    std::vector<std::string> files;
    if (d.combinedDisplacement)
        files.emplace_back("octaves_variant_combined.glsl"); // the vertex shader only reads the result
    else if (const char* variant = variantFile(d.vertexFilter))
        files.emplace_back(variant);
    files.emplace_back("octaves.glsl");
    return files;
}

int OctavesGpu::unitsUsed() const {
    const bool extra = mSurface->desc().combinedDisplacement || mFilterMaps;
    return 1 + (extra ? 1 : 0);
}

SurfaceGpuStats OctavesGpu::update(double time, const glm::dvec3& cameraWorld) {
    SurfaceGpuStats s;
    if (!mUploadReported) { // the textures were uploaded at construction: count them once, on first use
        s.uploads = static_cast<int>(mSurface->maps().size()) + (mFilterMaps ? 1 : 0); // one per map
        mUploadReported = true;
    }
    if (mLightNow) {
        // The lighting maps at this time: every level of every octave, mix of its two time slices.
        gl::StateGuard guard; // restores the program
        const GLuint prog = mLightMixProgram.id();
        glUseProgram(prog);
        const std::vector<OctaveFrameParams> params = mSurface->frameParams(glm::dvec2(cameraWorld), time);
        const int n = static_cast<int>(params.size());
        for (int i = 0; i < n; ++i)
            glProgramUniform1f(prog, arrayLocation(prog, "uFramePos", i),
                               params[static_cast<size_t>(i)].framePosition);
        glProgramUniform1i(prog, location(prog, "uOctaveCount"), n);
        glProgramUniform1i(prog, location(prog, "uFrames"), mSurface->desc().frames);
        glBindTextureUnit(0, mLightMaps.id());
        glProgramUniform1i(prog, location(prog, "uLightMaps"), 0);
        for (int level = 0; level < mLightLevels; ++level) {
            const int size = std::max(1, mLightSize >> level);
            glProgramUniform1i(prog, location(prog, "uLevel"), level);
            glBindImageTexture(OCTAVE_LIGHT_IMAGE_UNIT, mLightNow.id(), level, GL_TRUE, 0, GL_WRITE_ONLY,
                               GL_RGBA16F);
            const GLuint groups = static_cast<GLuint>((size + 7) / 8);
            glDispatchCompute(groups, groups, static_cast<GLuint>(n));
        }
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        glBindImageTexture(OCTAVE_LIGHT_IMAGE_UNIT, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        s.computePasses += 1;
    }
    if (!mCombined)
        return s;
    // §18.2.5 pass 1: sum the displaced octaves into the combined levels around this camera.
    gl::StateGuard guard; // restores the program
    const GLuint prog = mCombineProgram.id();
    glUseProgram(prog);
    bindOctaves(prog, 0, time, cameraWorld, true);
    glBindImageTexture(OCTAVE_COMBINE_IMAGE_UNIT, mCombined.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    const GLuint groups =
        static_cast<GLuint>((mSurface->desc().combinedSize + COMBINE_GROUP - 1) / COMBINE_GROUP);
    glDispatchCompute(groups, groups, static_cast<GLuint>(mSurface->combinedLevels()));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindImageTexture(OCTAVE_COMBINE_IMAGE_UNIT, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    s.computePasses += 1;
    return s;
}

void OctavesGpu::bindOctaves(unsigned prog, int firstUnit, double time, const glm::dvec3& cameraWorld,
                             bool filterTexture) {
    const std::vector<OctaveFrameParams> params = mSurface->frameParams(glm::dvec2(cameraWorld), time);
    const int n = static_cast<int>(params.size());
    glBindTextureUnit(static_cast<GLuint>(firstUnit), mLightNow.id());
    glProgramUniform1i(prog, location(prog, "uLightNow"), firstUnit);
    for (int i = 0; i < n; ++i) {
        const OctaveFrameParams& p = params[static_cast<size_t>(i)];
        glProgramUniform2f(prog, arrayLocation(prog, "uUvOffset", i), p.uvOffset.x, p.uvOffset.y);
        glProgramUniform1f(prog, arrayLocation(prog, "uInvTile", i), p.invTileSize);
        glProgramUniform1f(prog, arrayLocation(prog, "uAmplitude", i), p.amplitude);
        glProgramUniform1f(prog, arrayLocation(prog, "uFramePos", i), p.framePosition);
    }
    const HeightOctavesDesc& d = mSurface->desc();
    glProgramUniform1i(prog, location(prog, "uOctaveCount"), n);
    glProgramUniform1i(prog, location(prog, "uDisplacedCount"), d.displacedOctaves);
    glProgramUniform1i(prog, location(prog, "uMapSize"), d.mapSize);
    glProgramUniform1i(prog, location(prog, "uFrames"), d.frames);
    // The lighting-only octaves' aperiodic mix: psi = wrap(k.camera + phase, 2 pi) in double, so the float
    // sees only k.rel.
    glProgramUniform1i(prog, location(prog, "uOctaveAperiodic"), d.aperiodic ? 1 : 0);
    for (int i = d.displacedOctaves; d.aperiodic && i < n; ++i) {
        const double tile = d.octaves[static_cast<size_t>(i)].tileSize;
        for (int j = 0; j < FFT_MIX_TERMS; ++j) {
            const glm::dvec3 m = aperiodicMixTerm(tile, OCTAVE_MIX_SET + i, j);
            const double psi =
                wrapPhase(m.x * cameraWorld.x + m.y * cameraWorld.y + m.z, 2.0 * std::numbers::pi);
            glProgramUniform3f(prog, arrayLocation(prog, "uOctaveMix", i * FFT_MIX_TERMS + j),
                               static_cast<float>(m.x), static_cast<float>(m.y), static_cast<float>(psi));
        }
    }

    // The filter's texture and uniforms (absent from programs whose variant does not declare them: -1).
    if (filterTexture && mFilterMaps)
        glBindTextureUnit(static_cast<GLuint>(firstUnit + 1), mFilterMaps.id());
    glProgramUniform1i(prog, location(prog, "uFilterMaps"),
                       filterTexture && mFilterMaps ? firstUnit + 1 : firstUnit);
    glProgramUniform1f(prog, location(prog, "uLodTexels"), static_cast<float>(d.trilinearLodTexels));
    glProgramUniform1i(prog, location(prog, "uMaxLevel"), mSurface->mipLevels() - 1);
    glProgramUniform2f(prog, location(prog, "uTrilinearBand"),
                       static_cast<float>(HeightOctaves::TRILINEAR_BAND_LOW),
                       static_cast<float>(HeightOctaves::TRILINEAR_BAND_HIGH));

    // The combined levels: origins relative to the camera, formed in double (|origin| < texel_k).
    glProgramUniform1i(prog, location(prog, "uCombinedSize"), d.combinedSize);
    glProgramUniform1i(prog, location(prog, "uCombinedLevels"), mSurface->combinedLevels());
    glProgramUniform1f(prog, location(prog, "uCombinedTexel0"), static_cast<float>(d.combinedTexel));
    const glm::dvec2 camera(cameraWorld);
    for (int k = 0; k < mSurface->combinedLevels(); ++k) {
        const glm::vec2 o(mSurface->combinedOrigin(k, camera) - camera);
        glProgramUniform2f(prog, arrayLocation(prog, "uCombinedOrigin", k), o.x, o.y);
    }
}

void OctavesGpu::bind(unsigned prog, int firstUnit, double time, const glm::dvec3& cameraWorld) {
    const bool combined = static_cast<bool>(mCombined);
    bindOctaves(prog, firstUnit, time, cameraWorld, !combined);
    const int unit = firstUnit + 1;
    if (combined)
        glBindTextureUnit(static_cast<GLuint>(unit), mCombined.id());
    glProgramUniform1i(prog, location(prog, "uCombined"), combined ? unit : firstUnit);
}

} // namespace pacifica::ocean
