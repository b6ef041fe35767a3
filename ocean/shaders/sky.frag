// sky.frag: the sky behind the sea, one ray per pixel through the inverse camera rotation: the procedural
// sky or the environment map, fogged from the camera's altitude (sky.glsl). Rays that reach the sea beyond
// the grid (a host's smaller grid, or altitudes where the horizon lies past the skirt) see a flat, distant
// sea with the same water shading and fog as ocean.frag, so the two meet without a seam.
// With SHADE_COMPUTE (ocean_shade.comp) only the functions are compiled: the compute pass calls skyColor().
#ifndef SHADE_COMPUTE
in vec2 vNdc;
out vec4 fragColor;
#endif
uniform mat4 uInvViewProj; // inverse of the camera-relative view-projection

// Distance along dir (unit) from the camera to the sea on a sphere (surface drop k x^2 at horizontal
// distance x, k = uCurvature): the nearer root of k c^2 s^2 + mu s + z0 = 0 in the cancellation-free form
// 2 z0 / (-mu + sqrt(mu^2 - 4 k c^2 z0)); negative when the ray misses.
float seaHitDistance(vec3 dir, float z0) {
    float mu = dir.z;
    if (mu >= 0.0)
        return -1.0;
    float c2 = 1.0 - mu * mu;
    float disc = mu * mu - 4.0 * uCurvature * c2 * z0;
    return disc < 0.0 ? -1.0 : 2.0 * z0 / (-mu + sqrt(disc));
}

// A flat sea far away: its waves are far below a pixel, so the surface is the mean plane with the slope
// variance of a moderate sea as roughness (mean-square slope ~0.02, Cox & Munk 1954 at ~5 m/s wind).
vec3 distantSea(vec3 dir) {
    const float m2 = 0.02;
    vec3 n = vec3(0.0, 0.0, 1.0);
    vec3 v = -dir;
    float fresnel = fresnelSchlick(clamp(v.z, 0.0, 1.0));
    vec3 r = reflect(dir, n);
    vec3 sea = fresnel * reflectedSky(r, m2, 0.0) + (1.0 - fresnel) * waterBody(v, n) +
               sunSpecular(n, v, m2, sunLightAt(0.0));
    return sea;
}

// The spots' beams in the fog along dir out to distance s (spot.glsl); none without spots.
vec3 skyBeams(vec3 dir, float s) {
#ifdef SPOT_LIGHTS
    return min(spotScatter(dir, s), vec3(SPOT_RADIANCE_MAX));
#else
    return vec3(0.0);
#endif
}

// The sky above the sea's horizon in direction dir (unit) from altitude z0: rays that miss the sea.
vec3 openSkyRadiance(vec3 dir, float z0) {
    // The physical sky's map holds every ray that misses the sea, those that pass below the horizontal over
    // the curved sea included (ClearSky::skyMap integrates from the sea's dipped horizon up), and the haze.
    if (uSkyHoldsFog)
        return backgroundRadiance(dir);
    if (uPhysicalSky)
        return mix(fogColor(dir), backgroundRadiance(dir), skyTransmittance(z0, dir));
    // Below the horizontal (rays from altitude that pass over the curved sea) there is no sky to show -- a
    // map has its ground there -- so the horizon's haze colour, blended in over half a degree.
    vec3 sky = backgroundRadiance(dir.z < 0.0 ? normalize(vec3(dir.xy, 1e-4)) : dir);
    sky = mix(sky, fogColor(dir), smoothstep(0.0, 0.009, -dir.z));
    return mix(fogColor(dir), sky, skyTransmittance(z0, dir));
}
vec3 openSkyColor(vec3 dir, float z0) {
    return openSkyRadiance(dir, z0) + skyBeams(dir, 1e30);
}

// The sea beyond the grid, hit at distance s along dir from altitude z0.
vec3 beyondGridColor(vec3 dir, float z0, float s) {
    // No noise factor: beyond the grid it has averaged out to 1 (its mipmaps), and the texture()
    // derivatives would be undefined inside this branch.
    float tau = fogOpticalDepth(z0, 0.0, s);
    return mix(fogColor(dir), distantSea(dir), exp(-tau)) + skyBeams(dir, s);
}

// The camera's altitude as the sky sees it (above the sea, so every ray upward misses it).
float skyEyeHeight() { return max(uCameraHeight, 0.01); }

// What a ray from the camera in direction dir (unit) sees beyond the grid: the sky, or the distant sea.
// (Compute shading's tiles call the two parts alone where a tile holds only one: ocean_shade.comp.)
vec3 skyColor(vec3 dir) {
    float z0 = skyEyeHeight();
    float s = seaHitDistance(dir, z0);
    if (s > 0.0) // a branch, not a select: a GPU then runs one side per warp
        return beyondGridColor(dir, z0, s);
    return openSkyColor(dir, z0);
}

#ifndef SHADE_COMPUTE
void main() {
    vec4 p = uInvViewProj * vec4(vNdc, 0.5, 1.0);
    fragColor = vec4(skyColor(normalize(p.xyz / p.w)), 1.0);
}
#endif
