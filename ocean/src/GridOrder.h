// GridOrder: the order in which the sea's quad grids (the radial grid's rings x columns, the effects' discs)
// list their triangles and lay out their vertices, so that a vertex shared by neighbouring triangles is
// shaded once rather than once per row of quads it touches (internal to the ocean module).
//
// A triangle list names each grid vertex in up to six triangles; how often its vertex shader runs depends
// on the renderer's post-transform reuse. Mesa's draw module (llvmpipe's vertex stage, single-threaded)
// cuts an indexed draw into segments of 1024 indices and shades each segment's distinct vertices once,
// found through a 256-entry table indexed by (vertex index mod 256) (gallium/auxiliary/draw/
// draw_pt_vsplit.c); hardware keeps a small cache of recent vertices. Row after row of a 513-vertex ring
// (513 = 1 mod 256) meets neither: a ring's vertex j + 1 and the next ring's vertex j share a table entry,
// so every vertex was shaded twice (1.0 vertex per triangle). Here the quads go in blocks of
// BLOCK_COLUMNS columns, each block ring by ring (a vertex is then reused while the block's next row is
// drawn), and each row of vertices is padded to a stride = ROW_PHASE (mod 256), so up to 256 / ROW_PHASE
// consecutive rows of a block (BLOCK_COLUMNS + 1 <= ROW_PHASE vertices each) never share an entry. Modelled
// (test_radial_grid): 0.59 vertex shadings per triangle in Mesa's scheme and 0.55 in a 32-entry FIFO
// cache, against 1.0 for row order; measured on llvmpipe: docs/PERFORMANCE.md. Padding vertices are never
// indexed: they cost memory (6% for the 513-vertex rings), not shading.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace pacifica::ocean::gridorder {

inline constexpr int BLOCK_COLUMNS = 12;
inline constexpr int ROW_PHASE = 16;
static_assert(BLOCK_COLUMNS + 1 <= ROW_PHASE, "a block's row of vertices must fit in its table phase");

/// The padded row stride for rows of `rowVertices` vertices: the smallest s >= rowVertices with
/// s = ROW_PHASE (mod 256).
inline int rowStride(int rowVertices) {
    const int r = ((rowVertices - ROW_PHASE) % 256 + 256) % 256;
    return r == 0 ? rowVertices : rowVertices + 256 - r;
}

/// Appends two counter-clockwise triangles (a, c, d), (a, d, b) per quad between consecutive rows of
/// `rows` and columns j, j + 1 for j in [0, columns), in column blocks: for each block of BLOCK_COLUMNS
/// columns, the rows' quads in order. at(row, column) gives a vertex index (column may be `columns`).
template <class At>
void appendQuadsInBlocks(std::vector<uint32_t>& out, const std::vector<int>& rows, int columns, At at) {
    for (int j0 = 0; j0 < columns; j0 += BLOCK_COLUMNS) {
        const int j1 = std::min(j0 + BLOCK_COLUMNS, columns);
        for (size_t k = 0; k + 1 < rows.size(); ++k) {
            const int i = rows[k], n = rows[k + 1];
            for (int j = j0; j < j1; ++j) {
                const uint32_t a = at(i, j), b = at(i, j + 1), c = at(n, j), d = at(n, j + 1);
                out.insert(out.end(), {a, c, d, a, d, b});
            }
        }
    }
}

} // namespace pacifica::ocean::gridorder
