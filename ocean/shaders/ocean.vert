// ocean.vert: the radial grid (GPU Gems 2 §18.2.3, listing 18-1) spread over the view sector and displaced
// by the surface model's modelDisplacement() (octaves, Gerstner or FFT; ocean/src/gpu/SurfaceGpu.h), with
// the per-vertex frustum test of §18.2.5 skipping the displacement work of vertices outside a guard-banded
// frustum. Everything is camera-relative: the grid is centred under the camera and the GPU never sees world
// coordinates (model phases and offsets were wrapped in double on the CPU).

layout(location = 0) in vec2 aGrid; // u in [0, 1] across the view sector, r (metres)

uniform mat4 uViewProj;        // camera-relative: rotation and projection only
uniform float uCameraHeight;   // camera z above mean sea level, metres
uniform float uDisplaceRadius; // beyond this radius (the skirt) vertices stay flat
uniform float uCurvature;      // 1 / (2 R) with Earth curvature, else 0 (OceanConstants.h curvatureDrop)
uniform vec3 uSector;          // (centre azimuth, half width, guard distance): RadialGrid.h sectorPosition()
uniform vec3 uCull;            // (enabled, C0, C1): displace only if |clip.xy| < clip.w * C0 + C1 (§18.2.5)

out vec3 vRel;  // camera-relative position of the displaced vertex
out vec2 vGrid; // camera-relative undisplaced grid point (the model's lookup coordinate for lighting)

void main() {
    float r = aGrid.y;
    // A horizontal displacement of up to g turns a point at radius r by at most asin(g / r), and by anything
    // when r <= g: widen the sector by that much so points displaced into view exist.
    float halfWidth = r <= uSector.z ? 3.14159265358979 : min(3.14159265358979, uSector.y + asin(uSector.z / r));
    float theta = uSector.x + (2.0 * aGrid.x - 1.0) * halfWidth;
    vec2 rel = vec2(cos(theta), sin(theta)) * r;
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
