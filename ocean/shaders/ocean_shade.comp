// ocean_shade.comp: compute shading (OceanDesc::computeShading). One invocation per pixel rebuilds the
// surface point from the host's depth and the G-buffer (ocean_gbuffer.frag) and writes the host's colour
// texture directly: the sea lit by ocean.frag's shadeSea() where a grid was drawn, the sky (sky.frag's
// skyColor()) elsewhere when the ocean draws it. Texture footprints: the grid lookups' (the model's lighting
// maps, the foam) from the G-buffer, which took it from the pixel quad; the fog noise's from neighbouring
// pixels (screenDerivative).
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

// The camera-relative surface point drawn at pixel q (the depth unprojected), false where none was.
bool seaAt(ivec2 q, out vec3 rel) {
    rel = vec3(0.0);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, uShadeSize)))
        return false;
    float depth = texelFetch(uDepth, q, uDepthLevel).r;
    if (depth <= 0.0)
        return false;
    vec4 h = uInvViewProj * vec4(pixelNdc(q), depth, 1.0);
    rel = h.xyz / h.w;
    return true;
}

// The derivative along one screen axis of the surface point at p, for the fog noise's footprint. A pixel
// quad differences the triangle's own interpolants; here the neighbours may lie on another wave (a crest
// hiding the trough behind it), so of the two one-sided differences the smaller is taken, as deferred
// renderers do (a discontinuity makes the other large). Off the sea on one side: the other; alone: 0.
vec3 screenDerivative(ivec2 p, ivec2 axis, vec3 rel) {
    vec3 ra, rb;
    bool a = seaAt(p + axis, ra), b = seaAt(p - axis, rb);
    vec3 da = ra - rel, db = rel - rb;
    return a && (!b || dot(da, da) <= dot(db, db)) ? da : (b ? db : vec3(0.0));
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
        gRelDx = screenDerivative(p, ivec2(1, 0), rel);
        gRelDy = screenDerivative(p, ivec2(0, 1), rel);
        color = shadeSea();
    } else {
        if (!uShadeSky)
            return;
        color = skyColor(pixelRay(p));
    }
    imageStore(uShadeOutput, p, vec4(color, 1.0));
}
