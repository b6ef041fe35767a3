// sea_query.comp: the asynchronous GPU height queries (OceanRenderer::queueHeights; ocean/src/gpu/
// GpuQueries.h), a compute pass: on an H100/H200 only 4 of 132 SMs run vertex work, every SM runs this. For
// each camera-relative world point p, the height the sea is drawn at there: the grid point x0 whose displaced
// image lies above p (Broyden's method below: at most SEA_QUERY_ITERATIONS steps, 0 for a model without
// horizontal displacement, until a step moves x0 less than SEA_QUERY_TOLERANCE metres),
// then modelDisplacement(x0).z, plus the effects field at p as the grids add it (ocean.vert adds
// effectFieldAt(rel + d.xy), the displaced point, which is p).

layout(local_size_x = 64) in;
layout(std430, binding = SEA_QUERY_POINTS_BINDING) readonly buffer QueryPoints { vec2 uPoints[]; };
layout(std430, binding = SEA_QUERY_HEIGHTS_BINDING) writeonly buffer QueryHeights { float uHeights[]; };
uniform uint uQueryCount;
uniform float uDisplaceRadius; // the displaced grid's radius (ocean.vert's)

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uQueryCount)
        return;
    vec2 p = uPoints[i];
    // Beyond the displaced grid (OceanDesc::grid.rMax) the drawn sea is flat, its effects too (ocean.vert).
    if (length(p) > uDisplaceRadius) {
        uHeights[i] = 0.0;
        return;
    }
    // Broyden's method on F(x0) = x0 + d_xy(x0) - p (C. G. Broyden, "A class of methods for solving
    // nonlinear simultaneous equations", Math. Comp. 19, 1965, the "good" update of the inverse Jacobian H):
    // its first step, with H = I, is the fixed point x0 = p - d_xy(p); later steps learn the surface's
    // horizontal strain, so they converge superlinearly where the plain fixed point crawls (steep, choppy
    // seas), without the displacement's derivatives.
    vec2 x0 = p;
#if SEA_QUERY_ITERATIONS > 0
    vec2 f = modelDisplacement(x0).xy;
    mat2 inverseJacobian = mat2(1.0);
    for (int k = 0; k < SEA_QUERY_ITERATIONS; ++k) {
        vec2 step = -(inverseJacobian * f);
        x0 += step;
        if (length(step) < SEA_QUERY_TOLERANCE)
            break;
        vec2 next = x0 + modelDisplacement(x0).xy - p;
        vec2 hdf = inverseJacobian * (next - f);
        float denominator = dot(step, hdf);
        if (abs(denominator) > 1e-12)
            inverseJacobian += outerProduct(step - hdf, step * inverseJacobian) / denominator;
        f = next;
    }
#endif
    float h = modelDisplacement(x0).z;
#ifdef EFFECT_FIELD
    h += effectFieldAt(p).x;
#endif
    uHeights[i] = h;
}
