// effects.vert: a secondary radial grid centred at an effect (GPU Gems 2 §18.3: "the same radial grid as
// the one used for regular water rendering, but centered at the explosion location"), one instance per
// drawn effect of the kind uKind. Each vertex is displaced by the base surface model exactly as ocean.vert
// displaces its own, then raised by the field of all effects at the displaced point (effects.glsl), so the
// grids of overlapping effects draw the same surface.

layout(location = 0) in vec2 aDisc; // a point of the unit disc (rings spaced as rho^p, see EffectsGpu.cpp);
                                    // length 2: the rim's skirt, hung below the surface

uniform mat4 uViewProj;
uniform float uCameraHeight;
uniform float uDisplaceRadius;
uniform float uCurvature;
uniform int uKind; // 0: explosions, 1: wakes
uniform vec3 uCull; // (enabled, C0, C1): evaluate only if |clip.xy| < clip.w * C0 + C1 (§18.2.5, as ocean.vert)

out vec3 vRel;    // camera-relative displaced position
out vec2 vGrid;   // camera-relative undisplaced point (the base model's lighting lookup)
out vec3 vEffect; // (dE/dx, dE/dy, foam)
out vec2 vLocal;  // the displaced point relative to this grid's effect (tests compare it with the CPU)

void main() {
    vec2 center;
    float radius;
    if (uKind == 0) {
        center = uExplosions[gl_InstanceID].centre;
        radius = uExplosions[gl_InstanceID].gridRadius;
    } else {
        center = uWakes[gl_InstanceID].ship;
        radius = uWakes[gl_InstanceID].gridRadius;
    }
    bool skirt = dot(aDisc, aDisc) > 2.0;
    vec2 local = (skirt ? 0.5 * aDisc : aDisc) * radius;
    vec2 rel = center + local;
    float drop = dot(rel, rel) * uCurvature;
    // §18.2.5's per-vertex frustum test, as in ocean.vert, with the guard widened by the effect field's
    // reach: a vertex that cannot be in view skips the base displacement and the effect field (a wake's
    // path walk is the costly part), and a triangle with any vertex in view has all of them displaced.
    bool inView = true;
    if (uCull.x > 0.5) {
        vec4 c = uViewProj * vec4(rel, -drop - uCameraHeight, 1.0);
        inView = all(lessThan(abs(c.xy), vec2(c.w * uCull.y + uCull.z))) && c.w > -uCull.z;
    }
    vec3 d = inView && dot(rel, rel) <= uDisplaceRadius * uDisplaceRadius ? modelDisplacement(rel) : vec3(0.0);
    vec2 qLocal = local + d.xy;
    vec4 e = inView ? effectField(rel + d.xy, qLocal, uKind, gl_InstanceID) : vec4(0.0);
    vRel = vec3(rel, -drop - uCameraHeight) + d + vec3(0.0, 0.0, e.x);
    // The skirt hangs 2% of the radius (at least 0.5 m) below the rim: under the base surface, so it shows
    // only through the sliver it closes.
    if (skirt)
        vRel.z -= max(0.5, 0.02 * radius);
    vGrid = rel;
    vEffect = e.yzw;
    vLocal = qLocal;
    gl_Position = uViewProj * vec4(vRel, 1.0);
}
