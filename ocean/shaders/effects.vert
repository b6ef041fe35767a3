// effects.vert: a secondary radial grid centred at an effect (GPU Gems 2 §18.3: "the same radial grid as
// the one used for regular water rendering, but centered at the explosion location"), one instance per
// drawn grid of the kind being drawn (uEffectGrids[uFirstGrid + instance]). Each vertex is displaced by the
// base surface model exactly as ocean.vert displaces its own, then raised by the effects field at the
// displaced point (effects_sample.glsl), so the grids and the base grid draw the same surface.

layout(location = 0) in vec2 aDisc; // a point of the unit disc (rings spaced as rho^p, see EffectsGpu.cpp);
                                    // length 2: the rim's skirt, hung below the surface

uniform mat4 uViewProj;
uniform float uCameraHeight;
uniform float uDisplaceRadius;
uniform float uCurvature;
uniform int uFirstGrid; // the kind's first grid in uEffectGrids
uniform vec3 uCull; // (enabled, C0, C1): evaluate only if |clip.xy| < clip.w * C0 + C1 (§18.2.5, as ocean.vert)

out vec3 vRel;    // camera-relative displaced position
out vec2 vGrid;   // camera-relative undisplaced point (the base model's lighting lookup)
out vec2 vLocal;  // the displaced point relative to this grid's effect (tests compare it with the CPU)

void main() {
    vec4 grid = uEffectGrids[uFirstGrid + gl_InstanceID];
    vec2 center = grid.xy;
    float radius = grid.z;
    bool skirt = dot(aDisc, aDisc) > 2.0;
    vec2 local = (skirt ? 0.5 * aDisc : aDisc) * radius;
    vec2 rel = center + local;
    float drop = dot(rel, rel) * uCurvature;
    // §18.2.5's per-vertex frustum test, as in ocean.vert, with the guard widened by the effect field's
    // reach: a vertex that cannot be in view skips the base displacement and the field, and a triangle with
    // any vertex in view has all of them displaced.
    bool inView = true;
    if (uCull.x > 0.5) {
        vec4 c = uViewProj * vec4(rel, -drop - uCameraHeight, 1.0);
        inView = all(lessThan(abs(c.xy), vec2(c.w * uCull.y + uCull.z))) && c.w > -uCull.z;
    }
    vec3 d = inView && dot(rel, rel) <= uDisplaceRadius * uDisplaceRadius ? modelDisplacement(rel) : vec3(0.0);
    vec2 qLocal = local + d.xy;
    float e = inView ? effectFieldAt(rel + d.xy).x : 0.0;
    vRel = vec3(rel, -drop - uCameraHeight) + d + vec3(0.0, 0.0, e);
    // The skirt hangs 2% of the radius (at least 0.5 m) below the rim: under the base surface, so it shows
    // only through the sliver it closes.
    if (skirt)
        vRel.z -= max(0.5, 0.02 * radius);
    vGrid = rel;
    vLocal = qLocal;
    // Where an earlier grid (explosions' before wakes', nearer first) draws, this one leaves a hole: an
    // overlap is drawn once, by the finer grid of a smaller effect.
    clipEffectGrids(rel, uFirstGrid + gl_InstanceID);
    gl_Position = uViewProj * vec4(vRel, 1.0);
}
