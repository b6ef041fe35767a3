// OctavesGpu (internal): the GPU side of HeightOctaves — the octave maps as one RGBA16F 2D array texture
// (layer = octave * frames + time slice, mipmapped); the vertex filter's texture, one 2D array for all
// displaced octaves (an R16F copy of the heights for Nearest, Bilinear and HardwareBilinear, the packed maps
// of listing 18-2 for Packed4Tap and their mip chain for Trilinear), all uploaded once; and, with
// combinedDisplacement, the combine compute pass of GPU Gems 2 §18.2.5 run by update() every frame into an
// R32F array (one layer per combined level).
//
// Every frame update() mixes the lighting maps' two time slices of every octave into one mipmapped layer
// per octave (octaves_light_mix.comp, 1 compute pass), so the lighting samples once per octave.
//
// Texture units from bind()'s firstUnit: 0 the lighting maps at this frame's time; 1 the filter texture
// (per-vertex paths) or the combined texture (combined path). update() uses units 0 and 1 and image unit 0
// and leaves them bound (texture bindings are not part of the saved state); it restores the program.
// bind() must follow update() with the same camera and time: the combined texture is centred on the
// camera and the lighting maps hold update()'s time.
#pragma once

#include "gpu/SurfaceGpu.h"
#include "ocean/HeightOctaves.h"

#include <memory>

namespace pacifica::ocean {

class OctavesGpu final : public SurfaceGpu {
public:
    explicit OctavesGpu(std::shared_ptr<const HeightOctaves> surface);
    /// {"octaves.glsl"} for the default Bilinear path; otherwise the variant file that selects the filter
    /// (or the combined path) first: an absent feature costs no shader work, and each variant has its own
    /// program.
    std::vector<std::string> glslFiles() const override;
    /// Counts the uploads once (first call); mixes the lighting maps to `time` (1 compute pass); runs the
    /// combine pass when enabled (1 more).
    SurfaceGpuStats update(double time, const glm::dvec3& cameraWorld) override;
    void bind(unsigned program, int firstUnit, double time, const glm::dvec3& cameraWorld) override;
    int unitsUsed() const override;

    /// The octaves_variant_*.glsl file selecting `filter`, or nullptr for Bilinear (octaves.glsl's default).
    static const char* variantFile(VertexFilter filter);

private:
    /// Per-octave uniforms, the lighting maps at firstUnit, the filter texture (if asked and present) at
    /// firstUnit + 1, and the filter's and the combined levels' uniforms.
    void bindOctaves(unsigned program, int firstUnit, double time, const glm::dvec3& cameraWorld,
                     bool filterTexture);

    std::shared_ptr<const HeightOctaves> mSurface;
    gl::Texture mLightMaps; // every octave's (h, dh/du, dh/dv, |grad h|^2), layer = octave * frames + frame
    int mLightLevels = 0, mLightSize = 0;
    gl::Texture mLightNow; ///< the same at update()'s time: one layer per octave, mipmapped
    gl::Program mLightMixProgram;
    gl::Texture mFilterMaps; ///< R16F heights or packed RGBA16F (Packed4Tap, Trilinear); none without
                             ///< displaced octaves
    gl::Texture mCombined;   ///< R32F, combinedSize^2 x combinedLevels (combined path only)
    gl::Program mCombineProgram;
    bool mUploadReported = false;
};

} // namespace pacifica::ocean
