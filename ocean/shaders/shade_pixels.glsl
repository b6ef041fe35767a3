// shade_pixels.glsl: what compute shading's passes share (OceanDesc::computeShading): the host's depth, the
// pixel's ray and surface point, and the tile lists of OceanDesc::shadeTiles. Included after sky.frag by
// ocean_shade.comp and by ocean_shade_tiles.comp, the pass that sorts the screen's 8x8 tiles into them.
uniform sampler2D uDepth; // the host's 32-bit float depth, reverse-Z: 0 where no grid was drawn
uniform int uDepthLevel;  // its attached level
uniform ivec2 uShadeSize; // the viewport, pixels

// Tile kinds. A software rasteriser (llvmpipe) runs both sides of every branch of a shader for its whole
// SIMD vector of pixels, so one program lighting sea and sky pays for both at every pixel. Sorted by what
// their pixels hold, tiles of one kind run a program with only their part: the sea, the open sky above the
// sea's horizon, the sky and the sea beyond the grid (sky.frag's skyColor), or all of it (tiles on an edge).
// The kinds' numbers SHADE_TILE_MIXED, _SEA, _SKY, _BEYOND, their count SHADE_TILE_KINDS, the tile size
// SHADE_TILE_SIZE is #defined by ComputeShading::tileDefines(), the buffer's SHADE_TILE_BINDING by
// shaderConstantDefines() (gpu/GpuInterface.h).
// A tile is open sky when every pixel's ray rises above this (its z, unit ray): a ray of z >= 0 misses the
// sea (seaHitDistance), and the margin keeps rounding between the two programs on the same side.
#define SHADE_TILE_SKY_MIN_Z 1e-4
#ifdef SHADE_TILES
// Per kind k: the indirect dispatch (tiles, 1, 1) at header[3k], then its tiles' indices (y * tilesX + x)
// from tiles[k * uTileCapacity] (ComputeShading.cpp fills the header, the sorting pass counts).
layout(std430, binding = SHADE_TILE_BINDING) SHADE_TILE_ACCESS buffer ShadeTiles {
    uint header[3 * SHADE_TILE_KINDS];
    uint tiles[];
} uTiles;
uniform int uTilesX;         // tiles across the viewport
uniform uint uTileCapacity;  // entries per kind: every tile of the viewport
#endif

vec2 pixelNdc(ivec2 p) { return (vec2(p) + 0.5) / vec2(uShadeSize) * 2.0 - 1.0; }

// The unit ray through pixel p's centre (sky.frag: the inverse view-projection at NDC depth 0.5).
vec3 pixelRay(ivec2 p) {
    vec4 q = uInvViewProj * vec4(pixelNdc(p), 0.5, 1.0);
    return normalize(q.xyz / q.w);
}

// The host's depth at pixel q: > 0 where a grid was drawn.
float pixelDepth(ivec2 q) { return texelFetch(uDepth, q, uDepthLevel).r; }
