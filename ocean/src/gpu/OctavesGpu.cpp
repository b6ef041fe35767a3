// OctavesGpu: uploads the octave maps and binds the octave uniforms (GPU Gems 2 §18.2.1).
#include "gpu/OctavesGpu.h"

#include <epoxy/gl.h>

#include "ocean/OceanConstants.h"

#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstdio>

namespace pacifica::ocean {
namespace {

/// Location of `base[i]` (snprintf: GCC 12 warns falsely about string concatenation here).
GLint arrayLocation(GLuint prog, const char* base, int i) {
    char name[64];
    std::snprintf(name, sizeof name, "%s[%d]", base, i);
    return glGetUniformLocation(prog, name);
}

} // namespace

OctavesGpu::OctavesGpu(std::shared_ptr<const HeightOctaves> surface) : mSurface(std::move(surface)) {
    for (const OctaveMap& map : mSurface->maps()) {
        const int levels = 1 + static_cast<int>(std::log2(static_cast<double>(map.size)));
        gl::Texture t = gl::Texture::createArray2D(GL_RGBA16F, map.size, map.size, map.frames, levels);
        // The CPU copy already holds half-rounded values, so this conversion is exact.
        std::vector<uint16_t> half(map.texels.size());
        for (size_t i = 0; i < half.size(); ++i)
            half[i] = glm::packHalf1x16(map.texels[i]);
        glTextureSubImage3D(t.id(), 0, 0, 0, 0, map.size, map.size, map.frames, GL_RGBA, GL_HALF_FLOAT,
                            half.data());
        glGenerateTextureMipmap(t.id());
        t.setSampling(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
        mMaps.push_back(std::move(t));
    }
}

SurfaceGpuStats OctavesGpu::update(double, const glm::dvec3&) {
    SurfaceGpuStats s;
    if (!mUploadReported) { // the maps were uploaded at construction: count them once, on first use
        s.uploads = static_cast<int>(mMaps.size());
        mUploadReported = true;
    }
    return s;
}

void OctavesGpu::bind(unsigned prog, int firstUnit, double time, const glm::dvec3& cameraWorld) {
    const std::vector<OctaveFrameParams> params = mSurface->frameParams(glm::dvec2(cameraWorld), time);
    const int n = static_cast<int>(params.size());
    for (int i = 0; i < n; ++i) {
        const OctaveFrameParams& p = params[static_cast<size_t>(i)];
        glBindTextureUnit(static_cast<GLuint>(firstUnit + i), mMaps[static_cast<size_t>(i)].id());
        glProgramUniform1i(prog, arrayLocation(prog, "uMaps", i), firstUnit + i);
        glProgramUniform2f(prog, arrayLocation(prog, "uUvOffset", i), p.uvOffset.x, p.uvOffset.y);
        glProgramUniform1f(prog, arrayLocation(prog, "uInvTile", i), p.invTileSize);
        glProgramUniform1f(prog, arrayLocation(prog, "uAmplitude", i), p.amplitude);
        glProgramUniform1f(prog, arrayLocation(prog, "uFramePos", i), p.framePosition);
    }
    // Unused sampler slots must still name a unit holding a 2D array texture.
    for (int i = n; i < MAX_OCTAVES; ++i)
        glProgramUniform1i(prog, arrayLocation(prog, "uMaps", i), firstUnit);
    const HeightOctavesDesc& d = mSurface->desc();
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uOctaveCount"), n);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uDisplacedCount"), d.displacedOctaves);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uMapSize"), d.mapSize);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uFrames"), d.frames);
}

} // namespace pacifica::ocean
