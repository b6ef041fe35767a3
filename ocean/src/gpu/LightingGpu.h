// LightingGpu (internal): the lighting of the sky and sea programs — sets the sun, sky, fog and foam
// uniforms (sky.glsl, ocean.frag) and owns the lighting textures, each uploaded once and bound from a given
// unit on:
//   firstUnit + 0: the environment map (LightingDesc::environment), RGB16F lat-long with a full mip chain,
//                  uploaded once per map (cached by identity while the map is alive); without one, the
//                  physical clear sky's map (ClearSky::skyMap) for the camera's altitude level and the sun,
//                  computed once per level and sun (the levels next to the camera's ahead of time, on
//                  a worker thread) and uploaded when first used (the last few kept)
//   firstUnit + 1: the foam patterns (makeFoamPattern, makeFoamStreaks) and their squares, RGBA32F,
//                  mipmapped, repeating
//   firstUnit + 2: the fog noise (makeFogNoise), R16F 3D, mipmapped, repeating
// Sampler uniforms are always pointed at these units, even when unused, because GL forbids samplers of
// different types on one unit (the surface model binds 2D arrays from unit 0).
#pragma once

#include "engine/gl/GlObjects.h"
#include "ocean/Atmosphere.h"
#include "ocean/Lighting.h"
#include "ocean/Ocean.h"

#include <glm/glm.hpp>

#include <future>
#include <memory>
#include <vector>

namespace pacifica::ocean {

class LightingGpu {
public:
    /// Texture units used from firstUnit on.
    static constexpr int UNITS_USED = 3;

    LightingGpu();
    ~LightingGpu();
    LightingGpu(const LightingGpu&) = delete;
    LightingGpu& operator=(const LightingGpu&) = delete;

    /// Uniforms for `program` and the lighting textures on units [firstUnit, firstUnit + UNITS_USED),
    /// for one frame: the camera's world position and the time place the foam and fog-noise textures in
    /// the world (offsets wrapped in double), and the camera height and Earth-curvature term reach the sky
    /// program (the sea's vertex stage declares the same uniforms, so they are shared there).
    void bind(unsigned program, int firstUnit, const OceanDesc& desc, const OceanFrame& frame);

    /// Transitional form for callers that do not pass the frame yet: as above with the camera at the world
    /// origin at t = 0 (foam and fog noise then move with the camera), and uCameraHeight/uCurvature left as
    /// the caller set them (the sky program then fogs as if the camera were at sea level).
    void bind(unsigned program, int firstUnit, const LightingDesc& lighting);

    /// Texture uploads since the previous call (environment maps, foam, fog noise: each once), for the
    /// renderer's OceanStats::uploads.
    int uploadsSinceLastCall();

private:
    struct Environment {
        std::weak_ptr<const EnvironmentMap> source;
        const EnvironmentMap* address = nullptr;
        gl::Texture texture;
        int levels = 0;
        glm::vec3 irradiance{0.0f};         ///< environmentIrradiance(), before intensity
        std::vector<glm::vec3> horizonBand; ///< environmentHorizonBand(): the fog colour per azimuth
    };
    /// A physical sky computed for one altitude level and sun direction (kept while it is recent).
    struct GeneratedSky {
        int level = 0;
        glm::dvec3 sun{0.0};
        std::shared_ptr<const EnvironmentMap> map;
        glm::vec3 sunColor{1.0f};           ///< ClearSky::sunlight at the sea
        std::vector<glm::vec3> horizonBand; ///< ClearSky::horizonBand: the fog colour per azimuth
    };
    const Environment* environmentFor(const std::shared_ptr<const EnvironmentMap>& map);
    const GeneratedSky& generatedSky(const LightingDesc& lighting, double cameraAltitude);
    /// The sky of one altitude level and sun (run on a worker thread too: ClearSky's queries are const).
    static GeneratedSky computeSky(const ClearSky& air, int level, const glm::dvec3& sun);
    void ensureNoiseTextures();
    void setUniforms(unsigned program, int firstUnit, const LightingDesc& lighting, double time,
                     const glm::dvec3& cameraWorld, double cameraAltitude);
    /// The foam's uniforms: its wind frame, the layers' offsets and mixes, the thresholds.
    void setFoamUniforms(unsigned program, const LightingDesc& lighting, double time,
                         const glm::dvec3& cameraWorld);

    std::vector<Environment> mEnvironments;
    /// A sky being computed on a worker thread: the levels next to the camera's, so that a climb or a descent
    /// finds its next sky ready instead of waiting ~20 ms for it (a frame's hitch). The content depends on
    /// the level and the sun only, so a frame's sky is the same whether it was prefetched or not.
    struct PendingSky {
        int level = 0;
        glm::dvec3 sun{0.0};
        std::future<GeneratedSky> result;
    };
    /// Its tables, built on the first physical sky and per haze; shared with the workers computing skies.
    std::shared_ptr<const ClearSky> mClearSky;
    std::vector<GeneratedSky> mGeneratedSkies;
    std::vector<PendingSky> mPendingSkies;
    gl::Texture mFoam, mFogNoise;
    int mUploads = 0;
};

} // namespace pacifica::ocean
