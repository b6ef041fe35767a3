// ocean_shade.comp: compute shading (OceanDesc::computeShading). One invocation per pixel rebuilds the
// surface point from the host's depth and the G-buffer (ocean_gbuffer.frag) and writes the host's colour
// texture directly: the sea lit by ocean.frag's shadeSea() where a grid was drawn, the sky (sky.frag's
// skyColor()) elsewhere when the ocean draws it. Texture footprints: the grid lookups' (the model's lighting
// maps, the foam) from the G-buffer, which took it from the pixel quad; the fog noise's from the same
// derivatives of the grid point (below). With SHADE_TILES it lights one kind of tile only, from its list
// (OceanDesc::shadeTiles, ocean_shade_tiles.comp).
layout(local_size_x = SHADE_TILE_SIZE, local_size_y = SHADE_TILE_SIZE) in;
layout(binding = SHADE_OUTPUT_IMAGE_UNIT, SHADE_OUTPUT_FORMAT) uniform writeonly image2D uShadeOutput;
uniform sampler2D uGeometry; // (dFdx, dFdy of the grid point)
#ifdef GBUFFER_DISPLACED
uniform sampler2D uOffset; // grid point - surface point (.xy)
#endif
uniform bool uShadeSky; // OceanDesc::drawSky

// The camera-relative surface point drawn at pixel q (inside the viewport: main() checks) -- the depth
// unprojected -- false where none was.
bool seaAt(ivec2 q, out vec3 rel) {
    rel = vec3(0.0);
    float depth = pixelDepth(q);
    if (depth <= 0.0)
        return false;
    vec4 h = uInvViewProj * vec4(pixelNdc(q), depth, 1.0);
    rel = h.xyz / h.w;
    return true;
}

// The tiles of sky alone are lit by a program without the sea's code (nor the surface model's): one such
// program serves every model and effect variant.
#if !defined(SHADE_TILES) || SHADE_TILE_KIND == SHADE_TILE_MIXED || SHADE_TILE_KIND == SHADE_TILE_SEA
// The lit sea at pixel p, whose surface point is rel.
vec3 seaColor(ivec2 p, vec3 rel) {
    vec4 g = texelFetch(uGeometry, p, 0);
    vRel = rel;
#ifdef GBUFFER_DISPLACED
    vGrid = rel.xy + texelFetch(uOffset, p, 0).xy;
#else
    vGrid = rel.xy; // vertical displacement only: the grid point is the surface point's
#endif
    // The lighting and foam lookups: the quad's derivatives the G-buffer kept.
    gGridDx = g.xy;
    gGridDy = g.zw;
    // The fog noise's footprint: the quad's derivatives of the grid point, taken for the surface point's
    // horizontal ones and 0 vertically. Rebuilding them from neighbouring pixels' depths (the smaller
    // one-sided difference, as deferred renderers do) cost 4 more depth fetches a pixel (llvmpipe 640x360:
    // shade pass 62 -> 55 ms without them) and matched the fragment stage less well: mean luminance
    // difference to forward shading 0.0056% -> 0.0015% (octaves, the issue's view; test_compute_shading_gl)
    // -- a crest beside the trough behind it made the neighbours' footprint too wide.
    gRelDx = vec3(g.xy, 0.0);
    gRelDy = vec3(g.zw, 0.0);
    return shadeSea();
}
#endif

void main() {
#ifdef SHADE_TILES
    // This kind's list (ocean_shade_tiles.comp): one work group per tile.
    int t = int(uTiles.tiles[uint(SHADE_TILE_KIND) * uTileCapacity + gl_WorkGroupID.x]);
    ivec2 p = ivec2(t % uTilesX, t / uTilesX) * SHADE_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
#else
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
#endif
    if (any(greaterThanEqual(p, uShadeSize)))
        return;
    vec3 color;
#if defined(SHADE_TILES) && SHADE_TILE_KIND == SHADE_TILE_SEA
    vec3 rel;
    seaAt(p, rel); // every pixel of the tile has the sea
    color = seaColor(p, rel);
#elif defined(SHADE_TILES) && SHADE_TILE_KIND == SHADE_TILE_SKY
    color = openSkyColor(pixelRay(p), skyEyeHeight()); // every ray rises: none reaches the sea
#elif defined(SHADE_TILES) && SHADE_TILE_KIND == SHADE_TILE_BEYOND
    color = skyColor(pixelRay(p));
#else
    vec3 rel;
    if (seaAt(p, rel)) {
        color = seaColor(p, rel);
    } else {
        if (!uShadeSky)
            return;
        color = skyColor(pixelRay(p));
    }
#endif
    imageStore(uShadeOutput, p, vec4(color, 1.0));
}
