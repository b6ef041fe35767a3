// ocean_shade.comp: compute shading (OceanDesc::computeShading). One invocation per pixel rebuilds the
// surface point from the host's depth and the G-buffer (ocean_gbuffer.frag) and writes the host's colour
// texture directly: the sea lit by ocean.frag's shadeSea() where a grid was drawn, the sky (sky.frag's
// skyColor()) elsewhere when the ocean draws it. Texture footprints: the grid lookups' (the model's lighting
// maps, the foam) from the G-buffer, which took it from the pixel quad; the fog noise's from the same
// derivatives of the grid point (below).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 1, SHADE_OUTPUT_FORMAT) uniform writeonly image2D uShadeOutput;
uniform sampler2D uDepth;    // the host's 32-bit float depth, reverse-Z: 0 where no grid was drawn
uniform int uDepthLevel;     // its attached level
uniform sampler2D uGeometry; // (dFdx, dFdy of the grid point)
#ifdef GBUFFER_DISPLACED
uniform sampler2D uOffset; // grid point - surface point (.xy)
#endif
#ifdef EFFECT_GRID
uniform sampler2D uEffectGeometry; // (dE/dx, dE/dy, foam, 1 on an effect grid)
#endif
uniform ivec2 uShadeSize; // the viewport, pixels
uniform bool uShadeSky;   // OceanDesc::drawSky

vec2 pixelNdc(ivec2 p) { return (vec2(p) + 0.5) / vec2(uShadeSize) * 2.0 - 1.0; }

// The unit ray through pixel p's centre (sky.frag: the inverse view-projection at NDC depth 0.5).
vec3 pixelRay(ivec2 p) {
    vec4 q = uInvViewProj * vec4(pixelNdc(p), 0.5, 1.0);
    return normalize(q.xyz / q.w);
}

// The camera-relative surface point drawn at pixel q (inside the viewport: main() checks) — the depth
// unprojected — false where none was.
bool seaAt(ivec2 q, out vec3 rel) {
    rel = vec3(0.0);
    float depth = texelFetch(uDepth, q, uDepthLevel).r;
    if (depth <= 0.0)
        return false;
    vec4 h = uInvViewProj * vec4(pixelNdc(q), depth, 1.0);
    rel = h.xyz / h.w;
    return true;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, uShadeSize)))
        return;
    vec3 rel;
    vec3 color;
    if (seaAt(p, rel)) {
        vec4 g = texelFetch(uGeometry, p, 0);
        vRel = rel;
#ifdef GBUFFER_DISPLACED
        vGrid = rel.xy + texelFetch(uOffset, p, 0).xy;
#else
        vGrid = rel.xy; // vertical displacement only: the grid point is the surface point's
#endif
#ifdef EFFECT_GRID
        vEffect = texelFetch(uEffectGeometry, p, 0).xyz;
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
        color = shadeSea();
    } else {
        if (!uShadeSky)
            return;
        color = skyColor(pixelRay(p));
    }
    imageStore(uShadeOutput, p, vec4(color, 1.0));
}
