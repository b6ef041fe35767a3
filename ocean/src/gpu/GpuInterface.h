// GpuInterface (internal): the CPU/GPU interface of the ocean's storage buffers, declared once. The C++
// structs below are what the CPU uploads; their std430 layout is fixed by the static_asserts; the GLSL
// declares the same members in the same order (effects.glsl) and test_gpu_interface_gl compiles the real
// shaders and checks the driver's offset of every member against offsetof() here. The binding slots are one
// enum, given to every ocean shader as #defines by shaderConstantDefines() (no slot is typed on both sides).
#pragma once

#include <glm/glm.hpp>

#include <cstddef>

namespace pacifica::ocean {

/// Shader-storage binding slots. The FFT's compute passes and the shading pass run apart from the
/// effects' draws, so their slots may coincide with each other but never with the effects'.
enum StorageBinding : int {
    FFT_PLANES_BINDING = 0,          ///< fft_*.comp: the complex planes [plane][y][x]
    FFT_H0_PAIRS_BINDING = 1,        ///< fft_spectrum.comp: (h0(k), conj(h0(-k)))
    FFT_OMEGA_MULTIPLES_BINDING = 2, ///< fft_spectrum.comp: w(k) / w0 (integers)
    FFT_TWIDDLES_BINDING = 3,        ///< fft_pass.comp: e^{2 pi i j / N}
    SHADE_TILE_BINDING = 3,          ///< ocean_shade*.comp: the tile lists (ComputeShading.h)
    EFFECT_EXPLOSIONS_BINDING = 4,   ///< effects.glsl: ExplosionGpu[]
    EFFECT_WAKES_BINDING = 5,        ///< effects.glsl: WakeGpu[]
    EFFECT_WAKE_POINTS_BINDING = 6,  ///< effects.glsl: vec4[2 * MAX_WAKE_POINTS] per wake
    EFFECT_FIELD_TILES_BINDING = 7,  ///< effects_field.comp: EffectTileGpu[] (the tiles evaluated)
    EFFECT_FIELD_LISTS_BINDING = 8,  ///< effects_field.comp: per tile, its explosions, then its wakes
    EFFECT_GRIDS_BINDING = 9,       ///< effects_sample.glsl: vec4 (centre - camera, radius, 0) per drawn grid
    SEA_QUERY_POINTS_BINDING = 10,  ///< sea_query.comp: vec2 camera-relative points (GpuQueries.h)
    SEA_QUERY_HEIGHTS_BINDING = 11, ///< sea_query.comp: float heights, written
};

/// Image units, given to the shaders as #defines like the storage bindings. The compute passes that use
/// them run apart, so their units may coincide; the octave combine's unit 0 and the shading pass's unit 1 are
/// the ones left changed for the host (Ocean.h).
enum ImageUnit : int {
    OCTAVE_COMBINE_IMAGE_UNIT = 0,      ///< octaves_combine.comp: the combined height layers, written
    OCTAVE_LIGHT_IMAGE_UNIT = 0,        ///< octaves_light_mix.comp: this frame's lighting maps, written
    SHADE_OUTPUT_IMAGE_UNIT = 1,        ///< ocean_shade.comp: the host's colour texture, written
    FFT_DISPLACEMENT_IMAGE_UNIT = 0,    ///< fft_finalize.comp: displacement, written
    FFT_SLOPE_IMAGE_UNIT = 1,           ///< fft_finalize.comp: slopes, written
    FFT_MIP_SOURCE_IMAGE_UNIT = 0,      ///< fft_mip.comp: slope level l, read
    FFT_MIP_DESTINATION_IMAGE_UNIT = 1, ///< fft_mip.comp: slope level l + 1, written
    FFT_FOAM_SAMPLES_IMAGE_UNIT = 2,    ///< fft_foam.comp: crest samples, written then read
    FFT_FOAM_MEMORY_IMAGE_UNIT = 3,     ///< fft_foam.comp: the decayed crest memory, written
    EFFECT_FIELD_IMAGE_UNIT = 2,        ///< effects_field.comp: the field's texture array, written
};

/// Clip distances the grids' vertex stages write to cut the secondary grids' holes (effects_sample.glsl
/// clipEffectGrids): GL's least GL_MAX_CLIP_DISTANCES, so every GL 4.5 driver has them. Grids past the first
/// this many are left out by the base grid's per-pixel test alone.
inline constexpr int EFFECT_GRID_CLIPS = 8;

/// One tile of 8 x 8 texels of one level of the effects field, as effects_field.comp reads it (std430, 32
/// bytes): the tile and the range of its effect list (EffectsGpu.cpp bins the effects into tiles).
struct EffectTileGpu {
    int level; ///< the field level (texture layer)
    int tileX; ///< texels [8 tileX, 8 tileX + 8)
    int tileY;
    int first;      ///< its explosions at lists[first ...], then its wakes
    int explosions; ///< 0 and 0: a tile written last frame, now cleared
    int wakes;
    int pad0, pad1;
};
static_assert(sizeof(EffectTileGpu) == 32 && offsetof(EffectTileGpu, first) == 12 &&
                  offsetof(EffectTileGpu, wakes) == 20,
              "EffectTileGpu must match effects_field.comp's std430 layout");

/// One explosion as effects.glsl reads it (std430, 56 bytes). Camera-relative metres.
struct ExplosionGpu {
    glm::vec2 centre;    ///< centre - camera
    float gridRadius;    ///< R: the secondary grid's radius; 0 = nothing yet
    float amplitude;     ///< A(tau)
    float wavenumber;    ///< k, rad/m
    float phase;         ///< w tau, wrapped to [0, 2 pi)
    float coreRadius;    ///< r0
    float front;         ///< the front's radius
    float frontWidth;    ///< the front's half-width
    float crownFoam;     ///< foam of the crown
    float crownRadius;   ///< the crown's radius
    float peakAmplitude; ///< I0
    float slick;         ///< the slick's foam strength
    float slickRadius;   ///< its e-folding radius
};
static_assert(sizeof(ExplosionGpu) == 56 && offsetof(ExplosionGpu, gridRadius) == 8 &&
                  offsetof(ExplosionGpu, wavenumber) == 16 && offsetof(ExplosionGpu, frontWidth) == 32 &&
                  offsetof(ExplosionGpu, peakAmplitude) == 44 && offsetof(ExplosionGpu, slickRadius) == 52,
              "ExplosionGpu must match effects.glsl's std430 layout");

/// One ship's wake as effects.glsl reads it (std430, 48 bytes); its points follow in the wake-point buffer
/// at [wake * MAX_WAKE_POINTS * 2 ...]: (offset from the ship x, y; sigma; age), (amplitude, k0, 0, 0).
struct WakeGpu {
    glm::vec2 ship;   ///< ship - camera
    float gridRadius; ///< the secondary grid's radius
    float points;     ///< how many points (a float: the buffer is all floats)
    float shipLength; ///< L, m
    float beam;       ///< m
    float waveLife;   ///< s
    float foamLife;   ///< s
    glm::vec2 boxMin; ///< the box outside which the wake is 0, relative to the ship
    glm::vec2 boxMax;
};
static_assert(sizeof(WakeGpu) == 48 && offsetof(WakeGpu, points) == 12 &&
                  offsetof(WakeGpu, shipLength) == 16 && offsetof(WakeGpu, boxMin) == 32 &&
                  offsetof(WakeGpu, boxMax) == 40,
              "WakeGpu must match effects.glsl's std430 layout");

} // namespace pacifica::ocean
