// sky.frag: the procedural sky behind the sea, one ray per pixel through the inverse camera rotation.
in vec2 vNdc;
out vec4 fragColor;
uniform mat4 uInvViewProj; // inverse of the camera-relative view-projection
void main() {
    vec4 p = uInvViewProj * vec4(vNdc, 0.5, 1.0);
    vec3 dir = normalize(p.xyz / p.w);
    fragColor = vec4(skyRadiance(dir), 1.0);
}
