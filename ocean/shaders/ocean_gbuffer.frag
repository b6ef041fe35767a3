// ocean_gbuffer.frag: the sea's fragment stage under compute shading (OceanDesc::computeShading). The depth
// test keeps the nearest surface and the depth itself gives ocean_shade.comp the surface point (ray times
// distance); this stage records only what the depth cannot give: the pixel's footprint in grid metres as
// the quad's derivatives take it, max(|dFdx(vGrid)|, |dFdy(vGrid)|) (the rho of GL 4.5 eq. 8.7) -- the
// compute pass cannot take it from neighbours, which may lie on another wave -- and, for models that move
// the surface sideways (Gerstner, FFT), the grid point's offset from the surface point. Half floats: the
// footprint's relative precision is 1e-3, the offset's (up to a few metres) better than 1 cm.
in vec3 vRel;
in vec2 vGrid;
layout(location = 0) out vec4 gFootprint; // (dFdx(vGrid), dFdy(vGrid))
layout(location = 1) out vec4 gOffset;    // (vGrid - vRel.xy, 0, 0): GBUFFER_DISPLACED only

void main() {
#if defined(EFFECT_HOLES) && !defined(EFFECT_HOLES_CLIPPED) // else cut by the clipper
    if (insideEffectGrid(vGrid))
        discard;
#endif
    gFootprint = vec4(dFdx(vGrid), dFdy(vGrid));
    gOffset = vec4(vGrid - vRel.xy, 0.0, 0.0);
}
