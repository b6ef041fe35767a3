// ocean.frag: per-pixel sea lighting in scene-linear HDR — normals from the surface model's modelLighting()
// (for octaves: all maps light, the leading ones displace, §18.2.1), the normal tilt toward the viewer (§18.2.6), Schlick's Fresnel (Schlick 1994),
// reflection of the procedural sky, a normalised Blinn-Phong sun highlight, deep-water upwelling colour
// and exponential distance fog.

in vec3 vRel;
in vec2 vGrid;
out vec4 fragColor;

uniform float uNormalTilt;
uniform float uFogDensity;

void main() {
    float dist = length(vRel);
    vec3 v = -vRel / max(dist, 1e-6); // towards the eye
    vec3 g = modelLighting(vGrid);
    vec3 n = normalize(vec3(-g.xy, 1.0));
    // §18.2.6: the surface is lit as if flat under the displacement; tilt toward the viewer so back faces
    // of waves seen at grazing angles do not flash.
    n = normalize(n + v * uNormalTilt * (1.0 - abs(v.z)));
    if (dot(n, v) < 0.0) // viewer below the tangent plane (grazing): reflect about the view-facing normal
        n = normalize(n - (dot(n, v) - 0.01) * v);
    float ndv = clamp(dot(n, v), 0.0, 1.0);
    float fresnel = WATER_F0 + (1.0 - WATER_F0) * pow(1.0 - ndv, 5.0); // Schlick 1994
    vec3 r = reflect(-v, n);
    r.z = abs(r.z); // rays reflected into the sea would hit another wave: use the sky above instead
    vec3 reflected = skyRadiance(r);
    vec3 deep = vec3(DEEP_WATER_R, DEEP_WATER_G, DEEP_WATER_B) * uSkyIntensity *
                (0.6 + 0.4 * max(uSunDir.z, 0.0)) * 4.0;
    vec3 h = normalize(uSunDir + v);
    // Beckmann mean-square slope m^2 = resolved micro-roughness + unresolved octave slope variance; the
    // Blinn-Phong exponent that matches it is 2/m^2 - 2 (Walter et al. 2007, eq. 30).
    float m2 = 0.0012 + g.z;
    float shininess = max(2.0 / m2 - 2.0, 1.0);
    float spec = pow(max(dot(n, h), 0.0), shininess) * (shininess + 8.0) / (8.0 * 3.14159265);
    vec3 sun = vec3(1.0, 0.92, 0.80) * uSunIntensity * spec * fresnel * step(0.0, uSunDir.z);
    vec3 color = fresnel * reflected + (1.0 - fresnel) * deep + sun;
    vec3 fogColor = skyRadiance(normalize(vec3(-v.xy, 0.02)));
    float fog = exp(-uFogDensity * dist);
    fragColor = vec4(mix(fogColor, color, fog), 1.0);
}
