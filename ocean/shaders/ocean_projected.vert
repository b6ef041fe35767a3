// ocean_projected.vert: the projected grid (Johanson 2004 §2.3-2.4; ocean/include/ocean/ProjectedGrid.h)
// displaced by the surface model's modelDisplacement(), an alternative to ocean.vert's radial grid with the
// same outputs and uniforms (plus uCorners; uSector does not apply). The CPU's projector gives the grid's 4
// corners as homogeneous camera-relative points of the base plane; a vertex blends them bilinearly and
// divides by w, which is exact for the projector's perspective (Johanson §2.4.2), then drops by the
// Earth-curvature sagitta and adds the model's displacement. Everything is camera-relative.

layout(location = 0) in vec2 aUV; // (u, v) in [0, 1]^2: across the view, near edge to horizon

uniform vec4 uCorners[4];      // ProjectedGrid::Frame::cornerUniforms(): (u, v) = (0,0), (1,0), (0,1), (1,1)
uniform mat4 uViewProj;        // camera-relative: rotation and projection only
uniform float uCameraHeight;   // camera z above mean sea level, metres
uniform float uDisplaceRadius; // beyond this distance from the camera vertices stay flat
uniform float uCurvature;      // 1 / (2 R) with Earth curvature, else 0 (OceanConstants.h curvatureDrop)
uniform vec3 uCull;            // (enabled, C0, C1): displace only if |clip.xy| < clip.w * C0 + C1 (as ocean.vert)

out vec3 vRel;  // camera-relative position of the displaced vertex
out vec2 vGrid; // camera-relative undisplaced grid point (the model's lookup coordinate for lighting)

void main() {
    vec4 h = mix(mix(uCorners[0], uCorners[1], aUV.x), mix(uCorners[2], uCorners[3], aUV.x), aUV.y);
    vec2 rel = h.xy / h.w; // w > 0 over the whole grid (the range lies below the projector's horizon)
    float r = length(rel);
    float drop = r * r * uCurvature; // d^2 / (2 R)
    vec3 base = vec3(rel, -drop - uCameraHeight);
    bool displace = r <= uDisplaceRadius;
    if (uCull.x > 0.5) {
        vec4 c = uViewProj * vec4(base, 1.0);
        displace = displace && all(lessThan(abs(c.xy), vec2(c.w * uCull.y + uCull.z))) && c.w > -uCull.z;
    }
    vec3 d = displace ? modelDisplacement(rel) : vec3(0.0);
#ifdef EFFECT_FIELD
    // The effects (Effects.h): the field's height at the displaced point (effects_sample.glsl).
    if (displace)
        d.z += effectFieldAt(rel + d.xy).x;
#endif
    vRel = base + d;
    vGrid = rel;
#ifdef EFFECT_GRID_CLIP
    clipEffectGrids(rel, uEffectGridCount); // the holes where the secondary grids draw
#endif
    gl_Position = uViewProj * vec4(vRel, 1.0);
}
