// OctavesGpu (internal): the GPU side of HeightOctaves — the octave maps as RGBA16F 2D array textures
// (one layer per time slice, mipmapped for lighting), uploaded once, and the per-frame uniforms
// (octave offsets and frame positions wrapped in double). No per-frame GPU work.
#pragma once

#include "gpu/SurfaceGpu.h"
#include "ocean/HeightOctaves.h"

#include <memory>

namespace pacifica::ocean {

class OctavesGpu final : public SurfaceGpu {
public:
    explicit OctavesGpu(std::shared_ptr<const HeightOctaves> surface);
    std::vector<std::string> glslFiles() const override { return {"octaves.glsl"}; }
    SurfaceGpuStats update(double, const glm::dvec3&) override;
    void bind(unsigned program, int firstUnit, double time, const glm::dvec3& cameraWorld) override;
    int unitsUsed() const override { return static_cast<int>(mMaps.size()); }

private:
    std::shared_ptr<const HeightOctaves> mSurface;
    std::vector<gl::Texture> mMaps;
    bool mUploadReported = false;
};

} // namespace pacifica::ocean
