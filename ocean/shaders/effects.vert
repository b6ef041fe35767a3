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

out vec3 vRel;    // camera-relative displaced position
out vec2 vGrid;   // camera-relative undisplaced point (the base model's lighting lookup)
out vec3 vEffect; // (dE/dx, dE/dy, foam)
out vec2 vLocal;  // the displaced point relative to this grid's effect (tests compare it with the CPU)

void main() {
    vec2 center;
    float radius;
    if (uKind == 0) {
        center = uExplosions[gl_InstanceID].a.xy;
        radius = uExplosions[gl_InstanceID].a.z;
    } else {
        center = uWakes[gl_InstanceID].a.xy;
        radius = uWakes[gl_InstanceID].a.z;
    }
    bool skirt = dot(aDisc, aDisc) > 2.0;
    vec2 local = (skirt ? 0.5 * aDisc : aDisc) * radius;
    vec2 rel = center + local;
    float drop = dot(rel, rel) * uCurvature;
    vec3 d = dot(rel, rel) <= uDisplaceRadius * uDisplaceRadius ? modelDisplacement(rel) : vec3(0.0);
    vec2 qLocal = local + d.xy;
    vec4 e = effectField(rel + d.xy, qLocal, uKind, gl_InstanceID);
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
