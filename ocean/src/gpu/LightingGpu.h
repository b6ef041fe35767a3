// LightingGpu (internal): sets the lighting uniforms (sun, sky, fog, normal tilt) of the sky and sea
// programs and binds the lighting textures from a given unit on.
#pragma once

#include "ocean/Lighting.h"

namespace pacifica::ocean {

class LightingGpu {
public:
    LightingGpu();
    ~LightingGpu();
    LightingGpu(const LightingGpu&) = delete;
    LightingGpu& operator=(const LightingGpu&) = delete;
    /// Uniforms for `program`; textures (if any) on units [firstUnit, ...).
    void bind(unsigned program, int firstUnit, const LightingDesc& lighting);
};

} // namespace pacifica::ocean
