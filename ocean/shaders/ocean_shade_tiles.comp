// ocean_shade_tiles.comp: sorts the viewport's 8x8 tiles by what their pixels hold (OceanDesc::shadeTiles,
// shade_pixels.glsl's kinds) into the lists ocean_shade.comp's per-kind programs then light, one dispatch
// each (glDispatchComputeIndirect). One invocation per tile reads the tile's 64 depths and, where no grid
// was drawn, its rays; tiles of sky alone are left out when the ocean does not draw the sky.
layout(local_size_x = 64) in;
uniform int uTileCount; // tiles in the viewport
uniform bool uShadeSky; // OceanDesc::drawSky

void main() {
    int t = int(gl_GlobalInvocationID.x);
    if (t >= uTileCount)
        return;
    ivec2 origin = ivec2(t % uTilesX, t / uTilesX) * SHADE_TILE_SIZE;
    ivec2 end = min(origin + SHADE_TILE_SIZE, uShadeSize);
    bool sea = false, sky = false, low = false;
    for (int y = origin.y; y < end.y; ++y)
        for (int x = origin.x; x < end.x; ++x) {
            ivec2 p = ivec2(x, y);
            if (pixelDepth(p) > 0.0) {
                sea = true;
            } else {
                sky = true;
                low = low || pixelRay(p).z <= SHADE_TILE_SKY_MIN_Z;
            }
        }
    int kind = sea ? (sky ? SHADE_TILE_MIXED : SHADE_TILE_SEA) : (low ? SHADE_TILE_BEYOND : SHADE_TILE_SKY);
    if (!sea && !uShadeSky)
        return; // nothing of the ocean's to light here
    uint i = atomicAdd(uTiles.header[3 * kind], 1u);
    uTiles.tiles[uint(kind) * uTileCapacity + i] = uint(t);
}
