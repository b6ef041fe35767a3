// ocean.vert: the radial grid (GPU Gems 2 §18.2.3, listing 18-1) displaced by the surface model's
// modelDisplacement() (octaves, Gerstner or FFT; ocean/src/gpu/SurfaceGpu.h). Everything is camera-relative:
// the grid is centred under the camera and the GPU never sees world coordinates (model phases and offsets
// were wrapped in double on the CPU).

layout(location = 0) in vec3 aGrid; // cos(theta), sin(theta), r (metres)

uniform mat4 uViewProj;        // camera-relative: rotation and projection only
uniform float uCameraHeight;   // camera z above mean sea level, metres
uniform float uDisplaceRadius; // beyond this radius (the skirt) vertices stay flat
uniform float uCurvature;      // 1 / (2 R) with Earth curvature, else 0 (OceanConstants.h curvatureDrop)

out vec3 vRel;  // camera-relative position of the displaced vertex
out vec2 vGrid; // camera-relative undisplaced grid point (the model's lookup coordinate for lighting)

void main() {
    vec2 rel = aGrid.xy * aGrid.z;
    vec3 d = aGrid.z <= uDisplaceRadius ? modelDisplacement(rel) : vec3(0.0);
    float drop = aGrid.z * aGrid.z * uCurvature; // d^2 / (2 R)
    vRel = vec3(rel + d.xy, d.z - drop - uCameraHeight);
    vGrid = rel;
    gl_Position = uViewProj * vec4(vRel, 1.0);
}
