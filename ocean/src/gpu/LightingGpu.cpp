// LightingGpu: lighting uniforms for the sky and sea programs, and the lighting textures (environment map,
// foam pattern, fog noise), each uploaded once and counted for the renderer's stats.
#include "gpu/LightingGpu.h"

#include "ocean/OceanConstants.h"

#include <epoxy/gl.h>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace pacifica::ocean {

namespace {

int mipLevels(int w, int h) {
    return 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(std::max(w, h)))));
}

std::vector<uint16_t> toHalfClamped(const std::vector<float>& v) {
    std::vector<uint16_t> half(v.size());
    for (size_t i = 0; i < v.size(); ++i) // half's largest finite value: never let a bright sun become Inf
        half[i] = glm::packHalf1x16(std::min(v[i], 65504.0f));
    return half;
}

/// Tight rows for an upload, restoring the host's unpack alignment afterwards.
class UnpackAlignment {
public:
    UnpackAlignment() {
        glGetIntegerv(GL_UNPACK_ALIGNMENT, &mSaved);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    }
    ~UnpackAlignment() { glPixelStorei(GL_UNPACK_ALIGNMENT, mSaved); }
    UnpackAlignment(const UnpackAlignment&) = delete;
    UnpackAlignment& operator=(const UnpackAlignment&) = delete;

private:
    GLint mSaved = 4;
};

/// fract(x) in double, so offsets built from world positions of 10^7 m and times of 10^6 s stay exact.
double wrap01(double x) {
    return x - std::floor(x);
}

} // namespace

LightingGpu::LightingGpu() = default;
LightingGpu::~LightingGpu() = default;

int LightingGpu::uploadsSinceLastCall() {
    return std::exchange(mUploads, 0);
}

const LightingGpu::Environment*
LightingGpu::environmentFor(const std::shared_ptr<const EnvironmentMap>& map) {
    if (!map)
        return nullptr;
    // Forget maps nobody holds any more (their textures go with them).
    std::erase_if(mEnvironments, [](const Environment& e) { return e.source.expired(); });
    for (const Environment& e : mEnvironments)
        if (e.address == map.get() && e.source.lock() == map)
            return &e;
    Environment e;
    e.source = map;
    e.address = map.get();
    e.levels = mipLevels(map->width, map->height);
    e.texture = gl::Texture::create2D(GL_RGB16F, map->width, map->height, e.levels);
    const std::vector<uint16_t> half = toHalfClamped(map->rgb);
    {
        const UnpackAlignment tight;
        glTextureSubImage2D(e.texture.id(), 0, 0, 0, map->width, map->height, GL_RGB, GL_HALF_FLOAT,
                            half.data());
    }
    glGenerateTextureMipmap(e.texture.id());
    // Heading wraps around; elevation stops at the poles.
    glTextureParameteri(e.texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(e.texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(e.texture.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(e.texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    e.irradiance = environmentIrradiance(*map);
    e.horizonBand = environmentHorizonBand(*map);
    ++mUploads;
    mEnvironments.push_back(std::move(e));
    return &mEnvironments.back();
}

void LightingGpu::ensureNoiseTextures() {
    if (!mFoam) {
        const int n = FOAM_PATTERN_SIZE;
        mFoam = gl::Texture::create2D(GL_R16F, n, n, mipLevels(n, n));
        const std::vector<uint16_t> half = toHalfClamped(makeFoamPattern(n));
        {
            const UnpackAlignment tight;
            glTextureSubImage2D(mFoam.id(), 0, 0, 0, n, n, GL_RED, GL_HALF_FLOAT, half.data());
        }
        glGenerateTextureMipmap(mFoam.id());
        mFoam.setSampling(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
        ++mUploads;
    }
    if (!mFogNoise) {
        const int n = FOG_NOISE_SIZE;
        mFogNoise = gl::Texture::create3D(GL_R16F, n, n, n, mipLevels(n, n));
        const std::vector<uint16_t> half = toHalfClamped(makeFogNoise(n));
        {
            const UnpackAlignment tight;
            glTextureSubImage3D(mFogNoise.id(), 0, 0, 0, 0, n, n, n, GL_RED, GL_HALF_FLOAT, half.data());
        }
        glGenerateTextureMipmap(mFogNoise.id());
        mFogNoise.setSampling(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
        ++mUploads;
    }
}

void LightingGpu::setUniforms(unsigned prog, int firstUnit, const LightingDesc& l, double time,
                              const glm::dvec3& cam) {
    auto loc = [prog](const char* name) { return glGetUniformLocation(prog, name); };
    const glm::vec3 sun = glm::vec3(glm::normalize(l.sunDirection));
    glProgramUniform3f(prog, loc("uSunDir"), sun.x, sun.y, sun.z);
    glProgramUniform1f(prog, loc("uSkyIntensity"), l.skyIntensity);
    glProgramUniform1f(prog, loc("uSunIntensity"), l.sunIntensity);
    glProgramUniform1f(prog, loc("uNormalTilt"), l.normalTilt);
    glProgramUniform1f(prog, loc("uMicroSlopeVariance"), l.microSlopeVariance);
    glProgramUniform1f(prog, loc("uSubsurface"), l.subsurface);
    glProgramUniform1i(prog, loc("uGlitterBlinnPhong"),
                       l.glitter == LightingDesc::Glitter::BlinnPhong ? 1 : 0);

    // Environment map on firstUnit (the sampler always names its unit: see LightingGpu.h).
    const Environment* env = environmentFor(l.environment);
    glBindTextureUnit(static_cast<GLuint>(firstUnit), env ? env->texture.id() : 0);
    glProgramUniform1i(prog, loc("uEnvironment"), firstUnit);
    glProgramUniform1i(prog, loc("uHasEnvironment"), env ? 1 : 0);
    glProgramUniform1i(prog, loc("uEnvironmentBackground"), l.environmentBackground ? 1 : 0);
    glProgramUniform1f(prog, loc("uEnvironmentIntensity"), env ? l.environment->intensity : 0.0f);
    glProgramUniform1f(prog, loc("uEnvironmentMaxLod"), env ? static_cast<float>(env->levels - 1) : 0.0f);
    const glm::vec3 irr = env ? env->irradiance : glm::vec3(0.0f);
    glProgramUniform3f(prog, loc("uEnvironmentIrradiance"), irr.x, irr.y, irr.z);
    if (env) {
        glProgramUniform3fv(prog, loc("uEnvironmentHorizon"), ENVIRONMENT_HORIZON_BINS,
                            &env->horizonBand[0].x);
        glm::vec3 mean(0.0f);
        for (const glm::vec3& c : env->horizonBand)
            mean += c / static_cast<float>(env->horizonBand.size());
        glProgramUniform3f(prog, loc("uEnvironmentHorizonMean"), mean.r, mean.g, mean.b);
    }

    // Foam on firstUnit + 1, fog noise on firstUnit + 2; offsets wrapped in double (camera + drift).
    ensureNoiseTextures();
    glBindTextureUnit(static_cast<GLuint>(firstUnit + 1), mFoam.id());
    glBindTextureUnit(static_cast<GLuint>(firstUnit + 2), mFogNoise.id());
    glProgramUniform1i(prog, loc("uFoamMap"), firstUnit + 1);
    glProgramUniform1i(prog, loc("uFogNoiseMap"), firstUnit + 2);
    const glm::dvec2 drift = FOAM_DRIFT_SPEED * glm::dvec2(0.6, 0.8) * time;
    const glm::dvec2 nearOff = (glm::dvec2(cam) + drift) / FOAM_TILE_NEAR;
    const glm::dvec2 farOff = (glm::dvec2(cam) - drift) / FOAM_TILE_FAR;
    glProgramUniform2f(prog, loc("uFoamOffsetNear"), static_cast<float>(wrap01(nearOff.x)),
                       static_cast<float>(wrap01(nearOff.y)));
    glProgramUniform2f(prog, loc("uFoamOffsetFar"), static_cast<float>(wrap01(farOff.x)),
                       static_cast<float>(wrap01(farOff.y)));
    glProgramUniform1f(prog, loc("uFoamHeightStart"), l.foamHeightStart);
    glProgramUniform1f(prog, loc("uFoamHeightFull"), l.foamHeightFull);
    glProgramUniform1f(prog, loc("uFoamJacobianThreshold"), l.foamJacobianThreshold);
    glProgramUniform1f(prog, loc("uFoamIntensity"), l.foamIntensity);

    glProgramUniform1f(prog, loc("uFogDensity"), l.fogDensity);
    glProgramUniform3f(prog, loc("uWaterColor"), l.waterColor.r, l.waterColor.g, l.waterColor.b);
    glProgramUniform1f(prog, loc("uFogHeightFalloff"), l.fogHeightFalloff);
    glProgramUniform1f(prog, loc("uFogNoise"), l.fogNoise);
    const glm::dvec2 fogXY = (glm::dvec2(cam) - l.fogWind * time) / FOG_NOISE_TILE;
    glProgramUniform3f(prog, loc("uFogNoiseOffset"), static_cast<float>(wrap01(fogXY.x)),
                       static_cast<float>(wrap01(fogXY.y)),
                       static_cast<float>(wrap01(cam.z / FOG_NOISE_TILE_VERTICAL)));
    glProgramUniform1i(prog, loc("uHasFogColor"), l.fogColor ? 1 : 0);
    const glm::vec3 fog = l.fogColor.value_or(glm::vec3(0.0f));
    glProgramUniform3f(prog, loc("uFogColor"), fog.r, fog.g, fog.b);
}

void LightingGpu::bind(unsigned prog, int firstUnit, const OceanDesc& desc, const OceanFrame& frame) {
    setUniforms(prog, firstUnit, desc.lighting, frame.time, frame.camera.origin);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uCameraHeight"),
                       static_cast<float>(frame.camera.origin.z));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uCurvature"),
                       desc.earthCurvature ? static_cast<float>(1.0 / (2.0 * EARTH_RADIUS)) : 0.0f);
}

void LightingGpu::bind(unsigned prog, int firstUnit, const LightingDesc& lighting) {
    setUniforms(prog, firstUnit, lighting, 0.0, glm::dvec3(0.0));
}

} // namespace pacifica::ocean
