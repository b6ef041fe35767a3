// sea_query.vert: the asynchronous GPU height queries (OceanRenderer::queueHeights; ocean/src/gpu/
// GpuQueries.h). For each camera-relative world point p, the height the sea is drawn at there: the grid
// point x0 whose displaced image lies above p, by the fixed point x0 <- p - d_xy(x0) (SEA_QUERY_ITERATIONS
// steps, 0 for a model without horizontal displacement; it contracts by |grad d_xy|, below 1 where the
// surface does not fold), then modelDisplacement(x0).z, plus the effects field at p as the grids add it
// (ocean.vert adds effectFieldAt(rel + d.xy), the displaced point, which is p). One point per vertex,
// captured by transform feedback.

layout(location = 0) in vec2 aPoint;
out float vHeight;

void main() {
    vec2 x0 = aPoint;
    for (int i = 0; i < SEA_QUERY_ITERATIONS; ++i)
        x0 = aPoint - modelDisplacement(x0).xy;
    float h = modelDisplacement(x0).z;
#ifdef EFFECT_FIELD
    h += effectFieldAt(aPoint).x;
#endif
    vHeight = h;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
