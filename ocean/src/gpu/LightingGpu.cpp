// LightingGpu: lighting uniforms for the sky and sea programs, and the lighting textures (environment map,
// foam pattern, fog noise), each uploaded once and counted for the renderer's stats.
#include "gpu/LightingGpu.h"

#include "engine/Time.h"
#include "ocean/OceanConstants.h"
#include "ocean/SurfaceModel.h"

#include <epoxy/gl.h>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <future>
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

namespace {
int skyAltitudeLevel(double altitude) {
    const double h = std::isfinite(altitude) ? std::max(altitude, 0.0) : 0.0;
    return static_cast<int>(std::lround(std::log1p(h / SKY_ALTITUDE_H0) / std::log1p(SKY_ALTITUDE_STEP)));
}

double skyLevelAltitude(int level) {
    return SKY_ALTITUDE_H0 * std::expm1(level * std::log1p(SKY_ALTITUDE_STEP));
}

} // namespace

LightingGpu::GeneratedSky LightingGpu::computeSky(const ClearSky& air, int level, const glm::dvec3& sun) {
    GeneratedSky g;
    g.level = level;
    g.sun = sun;
    g.map = std::make_shared<const EnvironmentMap>(air.skyMap(skyLevelAltitude(level), sun));
    g.sunColor = glm::vec3(air.sunlight(0.0, sun));
    g.horizonBand = air.horizonBand(skyLevelAltitude(level), sun, ENVIRONMENT_HORIZON_BINS);
    return g;
}

const LightingGpu::GeneratedSky& LightingGpu::generatedSky(const LightingDesc& l, double cameraAltitude) {
    constexpr size_t KEPT = 4; // a few cameras at different altitudes, or a climb, without recomputing
    const glm::dvec3 sun = glm::normalize(l.sunDirection);
    const AtmosphereDesc air = atmosphereFor(l);
    if (mClearSky && (mClearSky->desc().hazeExtinction != air.hazeExtinction ||
                      mClearSky->desc().hazeScaleHeight != air.hazeScaleHeight)) {
        mPendingSkies.clear(); // another haze: new tables and skies (waits for the workers)
        mGeneratedSkies.clear();
        mClearSky.reset();
    }
    if (!mClearSky)
        mClearSky = std::make_shared<const ClearSky>(air);
    const int level = skyAltitudeLevel(cameraAltitude);
    auto kept = [&](int lv) {
        return std::find_if(mGeneratedSkies.begin(), mGeneratedSkies.end(),
                            [&](const GeneratedSky& g) { return g.level == lv && g.sun == sun; });
    };
    auto pending = [&](int lv) {
        return std::find_if(mPendingSkies.begin(), mPendingSkies.end(),
                            [&](const PendingSky& p) { return p.level == lv && p.sun == sun; });
    };
    if (kept(level) == mGeneratedSkies.end()) {
        GeneratedSky g;
        if (auto p = pending(level); p != mPendingSkies.end()) {
            g = p->result.get();
            mPendingSkies.erase(p);
        } else {
            g = computeSky(*mClearSky, level, sun);
        }
        if (mGeneratedSkies.size() >= KEPT)
            mGeneratedSkies.erase(mGeneratedSkies.begin()); // the oldest; its texture goes with its map
        mGeneratedSkies.push_back(std::move(g));
    }
    // Prefetch the levels above and below; drop work for another sun (its futures wait for the workers).
    std::erase_if(mPendingSkies, [&](const PendingSky& p) { return p.sun != sun; });
    for (int next : {level + 1, level - 1})
        if (next >= 0 && kept(next) == mGeneratedSkies.end() && pending(next) == mPendingSkies.end())
            mPendingSkies.push_back({next, sun, std::async(std::launch::async, [air = mClearSky, next, sun] {
                                         return computeSky(*air, next, sun);
                                     })});
    return *kept(level);
}

namespace {

/// The foam patterns and their squares (fine layer RG, coarse BA): the mipmaps average them, so a filtered
/// read gives the mean and the variance of each field over a footprint (ocean.frag foamCover). Built once
/// per process (~120 ms of CPU; every renderer used to build its own) and never changed.
const std::vector<float>& foamMoments() {
    static const std::vector<float> moments = [] {
        const std::vector<float> fine = makeFoamPattern(FOAM_PATTERN_SIZE),
                                 coarse = makeFoamStreaks(FOAM_PATTERN_SIZE);
        std::vector<float> m(fine.size() * 4);
        for (size_t i = 0; i < fine.size(); ++i) {
            m[4 * i] = fine[i];
            m[4 * i + 1] = fine[i] * fine[i];
            m[4 * i + 2] = coarse[i];
            m[4 * i + 3] = coarse[i] * coarse[i];
        }
        return m;
    }();
    return moments;
}

/// The fog noise as half floats, built once per process like the foam.
const std::vector<uint16_t>& fogNoiseHalf() {
    static const std::vector<uint16_t> half = toHalfClamped(makeFogNoise(FOG_NOISE_SIZE));
    return half;
}

} // namespace

void LightingGpu::ensureNoiseTextures() {
    if (!mFoam) {
        const int n = FOAM_PATTERN_SIZE;
        // 32-bit: the variance of a magnified texel is a small difference of large squares.
        mFoam = gl::Texture::create2D(GL_RGBA32F, n, n, mipLevels(n, n));
        {
            const UnpackAlignment tight;
            glTextureSubImage2D(mFoam.id(), 0, 0, 0, n, n, GL_RGBA, GL_FLOAT, foamMoments().data());
        }
        glGenerateTextureMipmap(mFoam.id());
        mFoam.setSampling(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
        ++mUploads;
    }
    if (!mFogNoise) {
        const int n = FOG_NOISE_SIZE;
        mFogNoise = gl::Texture::create3D(GL_R16F, n, n, n, mipLevels(n, n));
        {
            const UnpackAlignment tight;
            glTextureSubImage3D(mFogNoise.id(), 0, 0, 0, 0, n, n, n, GL_RED, GL_HALF_FLOAT,
                                fogNoiseHalf().data());
        }
        glGenerateTextureMipmap(mFogNoise.id());
        mFogNoise.setSampling(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, GL_REPEAT);
        ++mUploads;
    }
}

void LightingGpu::setFoamUniforms(unsigned prog, const LightingDesc& l, double time, const glm::dvec3& cam) {
    auto loc = [prog](const char* name) { return glGetUniformLocation(prog, name); };
    // The pattern's x axis lies along the wind: the camera in the wind's frame (along, across), the two
    // layers drifting apart along it; offsets wrapped in double (camera + drift).
    const double wind = l.windDirectionDeg * std::numbers::pi / 180.0;
    const glm::dvec2 along(std::sin(wind), std::cos(wind)); // compass angle to (east, north)
    glProgramUniform2f(prog, loc("uFoamWind"), static_cast<float>(along.x), static_cast<float>(along.y));
    const glm::dvec2 camWind(glm::dot(glm::dvec2(cam), along),
                             glm::dot(glm::dvec2(cam), glm::dvec2(-along.y, along.x)));
    const glm::dvec2 drift(FOAM_DRIFT_SPEED * time, 0.0);
    const glm::dvec2 nearOff = (camWind + drift) / FOAM_TILE_NEAR;
    const glm::dvec2 farOff = (camWind - drift) / FOAM_TILE_FAR;
    glProgramUniform2f(prog, loc("uFoamOffsetNear"), static_cast<float>(wrap01(nearOff.x)),
                       static_cast<float>(wrap01(nearOff.y)));
    glProgramUniform2f(prog, loc("uFoamOffsetFar"), static_cast<float>(wrap01(farOff.x)),
                       static_cast<float>(wrap01(farOff.y)));
    // Each layer is a mix cos theta A + sin theta B of the pattern and a shifted copy, theta quasi-periodic
    // (aperiodicMixWeights, SurfaceModel.h, phase set FOAM_MIX_SET + layer), so no tile repeats over a
    // wide foam (a wake, a slick): psi = wrap(k.camera + phase, 2 pi) in double, the float sees k.rel.
    const double tiles[2] = {FOAM_TILE_NEAR, FOAM_TILE_FAR};
    for (int layer = 0; layer < 2; ++layer)
        for (int j = 0; j < FFT_MIX_TERMS; ++j) {
            const glm::dvec3 m = aperiodicMixTerm(tiles[layer], FOAM_MIX_SET + layer, j);
            const double psi = wrapPhase(m.x * cam.x + m.y * cam.y + m.z, 2.0 * std::numbers::pi);
            const std::string name = "uFoamMix[" + std::to_string(layer * FFT_MIX_TERMS + j) + "]";
            glProgramUniform3f(prog, loc(name.c_str()), static_cast<float>(m.x), static_cast<float>(m.y),
                               static_cast<float>(psi));
        }
    glProgramUniform1f(prog, loc("uFoamHeightStart"), l.foamHeightStart);
    glProgramUniform1f(prog, loc("uFoamHeightFull"), l.foamHeightFull);
    glProgramUniform1f(prog, loc("uFoamJacobianThreshold"), l.foamJacobianThreshold);
    glProgramUniform1f(prog, loc("uFoamIntensity"), l.foamIntensity);
}

void LightingGpu::setUniforms(unsigned prog, int firstUnit, const LightingDesc& l, double time,
                              const glm::dvec3& cam, double cameraAltitude) {
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

    // Environment map on firstUnit (the sampler always names its unit: see LightingGpu.h): the host's, or
    // the physical sky's (per unit solar irradiance: scaled by the sun and sky intensities).
    const bool physical = !l.environment && l.sky == LightingDesc::Sky::Physical;
    const GeneratedSky* generated = physical ? &generatedSky(l, cameraAltitude) : nullptr;
    const Environment* env = environmentFor(generated ? generated->map : l.environment);
    const glm::vec3 sunColor =
        generated ? generated->sunColor : glm::vec3(SUN_COLOR[0], SUN_COLOR[1], SUN_COLOR[2]);
    glProgramUniform3f(prog, loc("uSunColor"), sunColor.r, sunColor.g, sunColor.b);
    glProgramUniform1i(prog, loc("uPhysicalSky"), generated ? 1 : 0);
    glProgramUniform1i(prog, loc("uSkyHoldsFog"), generated && skyHoldsFog(l) ? 1 : 0);
    const LightingDesc defaults;
    glProgramUniform1f(prog, loc("uWaterLightReference"),
                       PHYSICAL_SKY_WATER_REFERENCE * defaults.sunIntensity * defaults.skyIntensity);
    glBindTextureUnit(static_cast<GLuint>(firstUnit), env ? env->texture.id() : 0);
    glProgramUniform1i(prog, loc("uEnvironment"), firstUnit);
    glProgramUniform1i(prog, loc("uHasEnvironment"), env ? 1 : 0);
    glProgramUniform1i(prog, loc("uEnvironmentBackground"), generated || l.environmentBackground ? 1 : 0);
    glProgramUniform1f(prog, loc("uEnvironmentIntensity"),
                       generated ? l.sunIntensity * l.skyIntensity
                       : env     ? l.environment->intensity
                                 : 0.0f);
    glProgramUniform1f(prog, loc("uEnvironmentMaxLod"), env ? static_cast<float>(env->levels - 1) : 0.0f);
    const glm::vec3 irr = env ? env->irradiance : glm::vec3(0.0f);
    glProgramUniform3f(prog, loc("uEnvironmentIrradiance"), irr.x, irr.y, irr.z);
    if (env) {
        const std::vector<glm::vec3>& band = generated ? generated->horizonBand : env->horizonBand;
        glProgramUniform3fv(prog, loc("uEnvironmentHorizon"), ENVIRONMENT_HORIZON_BINS, &band[0].x);
        glm::vec3 mean(0.0f);
        for (const glm::vec3& c : band)
            mean += c / static_cast<float>(band.size());
        glProgramUniform3f(prog, loc("uEnvironmentHorizonMean"), mean.r, mean.g, mean.b);
    }

    // Foam on firstUnit + 1, fog noise on firstUnit + 2.
    ensureNoiseTextures();
    glBindTextureUnit(static_cast<GLuint>(firstUnit + 1), mFoam.id());
    glBindTextureUnit(static_cast<GLuint>(firstUnit + 2), mFogNoise.id());
    glProgramUniform1i(prog, loc("uFoamMap"), firstUnit + 1);
    glProgramUniform1i(prog, loc("uFogNoiseMap"), firstUnit + 2);
    setFoamUniforms(prog, l, time, cam);

    glProgramUniform1f(prog, loc("uFogDensity"), l.fogDensity);
    glProgramUniform3f(prog, loc("uWaterColor"), l.waterColor.r, l.waterColor.g, l.waterColor.b);
    glProgramUniform1f(prog, loc("uFogHeightFalloff"), l.fogHeightFalloff);
    glProgramUniform1f(prog, loc("uFogNoise"), l.fogNoise);
    const glm::dvec2 fogXY = (glm::dvec2(cam) - l.fogWind * time) / FOG_NOISE_TILE;
    glProgramUniform3f(prog, loc("uFogNoiseOffset"), static_cast<float>(wrap01(fogXY.x)),
                       static_cast<float>(wrap01(fogXY.y)),
                       static_cast<float>(wrap01(cam.z / FOG_NOISE_TILE_VERTICAL)));
    const glm::dvec2 fogXY2 = (glm::dvec2(cam) - l.fogWind * time) / FOG_NOISE_TILE_2;
    glProgramUniform3f(prog, loc("uFogNoiseOffset2"), static_cast<float>(wrap01(fogXY2.x)),
                       static_cast<float>(wrap01(fogXY2.y)),
                       static_cast<float>(wrap01(cam.z / FOG_NOISE_TILE_VERTICAL_2)));
    glProgramUniform1i(prog, loc("uHasFogColor"), l.fogColor ? 1 : 0);
    const glm::vec3 fog = l.fogColor.value_or(glm::vec3(0.0f));
    glProgramUniform3f(prog, loc("uFogColor"), fog.r, fog.g, fog.b);
}

void LightingGpu::bind(unsigned prog, int firstUnit, const OceanDesc& desc, const OceanFrame& frame) {
    setUniforms(prog, firstUnit, desc.lighting, frame.time, frame.camera.origin, frame.camera.origin.z);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uCameraHeight"),
                       static_cast<float>(frame.camera.origin.z));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uCurvature"),
                       desc.earthCurvature ? static_cast<float>(1.0 / (2.0 * EARTH_RADIUS)) : 0.0f);
}

void LightingGpu::bind(unsigned prog, int firstUnit, const LightingDesc& lighting) {
    setUniforms(prog, firstUnit, lighting, 0.0, glm::dvec3(0.0), 0.0);
}

} // namespace pacifica::ocean
