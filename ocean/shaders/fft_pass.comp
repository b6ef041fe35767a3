// fft_pass.comp: passes 2 and 3 of FftGpu — unnormalised inverse DFT,
//   out[x] = sum_p in[p] e^{+2 pi i p x / N},
// along rows (uDirection = 0) or columns (1) of every complex plane, in place in the Planes buffer.
// One workgroup transforms one whole line: it loads the line into shared memory in bit-reversed order, runs
// the log2(N) radix-2 decimation-in-time butterfly stages there (Cooley & Tukey 1965) with a barrier between
// stages, and writes the line back. Lines are disjoint, so in-place is safe across workgroups; shared memory
// is N complex floats (8 KiB at N = 1024, well inside GL's 32 KiB minimum). One dispatch per direction.
// Twiddles e^{+2 pi i j / N}, j < N/2, come precomputed in double (rounded once) from the CPU.
// Defines: FFT_N, FFT_LOG2N, FFT_THREADS (min(N/2, 64)), FFT_PLANES.

layout(local_size_x = FFT_THREADS) in;

layout(std430, binding = FFT_PLANES_BINDING) buffer Planes { vec2 planes[]; };              // [plane][y][x]
layout(std430, binding = FFT_TWIDDLES_BINDING) readonly buffer Twiddles { vec2 twiddles[]; }; // e^{2 pi i j / N}

uniform int uDirection; // 0: transform along x (one row per workgroup), 1: along y (one column)
uniform uint uPlaneBase;      // the first plane of each layer transformed: the foam memory's samples
uniform uint uPlanesPerLayer; // transform plane 1 (h) alone; workgroup y = layer * uPlanesPerLayer + the
                              // plane's index among them (layer l's planes start at plane FFT_PLANES l)

shared vec2 sLine[FFT_N];

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

void main() {
    uint line = gl_WorkGroupID.x;
    uint layer = gl_WorkGroupID.y / uPlanesPerLayer;
    uint plane = layer * FFT_PLANES + uPlaneBase + gl_WorkGroupID.y % uPlanesPerLayer;
    uint base = plane * FFT_N * FFT_N + (uDirection == 0 ? line * FFT_N : line);
    uint stride = uDirection == 0 ? 1u : FFT_N;
    uint tid = gl_LocalInvocationID.x;

    for (uint i = tid; i < FFT_N; i += uint(FFT_THREADS))
        sLine[bitfieldReverse(i) >> (32u - FFT_LOG2N)] = planes[base + i * stride];
    memoryBarrierShared();
    barrier();

    for (uint s = 1u; s <= FFT_LOG2N; ++s) {
        uint halfSpan = 1u << (s - 1u); // butterflies of stage s join blocks of 2 * halfSpan
        for (uint b = tid; b < FFT_N / 2u; b += uint(FFT_THREADS)) {
            uint j = b & (halfSpan - 1u);
            uint i0 = ((b >> (s - 1u)) << s) + j;
            uint i1 = i0 + halfSpan;
            vec2 w = twiddles[j << (FFT_LOG2N - s)]; // e^{2 pi i j / (2 halfSpan)}
            vec2 a = sLine[i0];
            vec2 c = cmul(w, sLine[i1]);
            sLine[i0] = a + c;
            sLine[i1] = a - c;
        }
        memoryBarrierShared();
        barrier();
    }

    for (uint i = tid; i < FFT_N; i += uint(FFT_THREADS))
        planes[base + i * stride] = sLine[i];
}
