// octaves_combine.comp: pass 1 of the combined displacement (GPU Gems 2 §18.2.5, "combining the height maps
// into a single texture in a separate pass"): evaluates the per-vertex path displacedHeight() of octaves.glsl
// (with the selected vertex filter) at every node of every combined level and stores it in an R32F array
// layer per level. Nodes that no vertex can read — inside the next finer level's reach by two texels of
// margin — are skipped (about a quarter of each level above 0). Sources: the ocean constants, the
// filter's octaves_variant_*.glsl, octaves.glsl, this file (OctavesGpu).

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(r32f, binding = OCTAVE_COMBINE_IMAGE_UNIT) writeonly uniform image2DArray uCombinedImage;

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= uCombinedSize || id.y >= uCombinedSize)
        return;
    int k = id.z;
    vec2 rel = combinedNodeRel(id.xy, k);
    // A vertex reads level k only if its Chebyshev distance r exceeds the reach of level k - 1, and then
    // only nodes within one texel of it (HeightOctaves::combinedLevelFor / combinedHeight).
    if (k > 0 && max(abs(rel.x), abs(rel.y)) + 2.0 * combinedTexel(k) <= combinedReach(k - 1))
        return;
    imageStore(uCombinedImage, id, vec4(displacedHeight(rel), 0.0, 0.0, 0.0));
}
