// RadialGrid: the camera-centred radial grid of GPU Gems 2 ch.18 §18.2.3 (Kryachko 2005), plain C++.
//
//   r_i = a0 + a1 * i^4,  x_ij = r_i cos(2*pi*j/M),  y_ij = r_i sin(2*pi*j/M),   i = 0..N-1, j = 0..M-1
//   with a0 = r_min (10 cm) and a0 + a1 (N-1)^4 = r_max (40 km).
//
// The grid gives distance-based tessellation for free. Two additions to the seed: a centre vertex at r = 0
// (so looking straight down from 0.5 m shows no 10 cm hole) and undisplaced skirt rings far beyond r_max
// so the sea reaches the horizon at any altitude. Radii are computed in double and stored as float; the
// grid is drawn camera-relative, so float precision at 40 km is ~4 mm. The angular coordinate is a fraction u
// of the view sector (computeViewSector): all M segments are spent where the camera looks, and no vertex
// lies behind the camera unless the frustum sees every azimuth (looking down at the nadir).
#pragma once

#include "engine/Space.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace pacifica::ocean {

struct RadialGridDesc {
    int rings = 256;          ///< N: rings from r_min to r_max
    int segments = 512;       ///< M: vertices around each ring
    double rMin = 0.1;        ///< r_0, metres (seed: 10 cm)
    double rMax = 40000.0;    ///< r_{N-1}, metres (seed: 40 km)
    double skirtRadius = 1e6; ///< undisplaced outer rings reach this radius for the horizon; 0 disables them
    int skirtRings = 16; ///< rings from rMax to skirtRadius, geometrically spaced, so the Earth-curvature
                         ///< drop (d^2 / 2R, interpolated linearly per triangle) follows the sphere
    /// Screen-space ring thinning (docs/PERFORMANCE.md): per frame, a ring is drawn only if it lies at least
    /// this many pixels (vertically, on the screen) beyond the last drawn ring, seen from the camera's height
    /// plus the waves' reach; the rings in between are skipped (their vertices are not shaded). From 20 m up
    /// most of the fixed i^4 rings beyond ~500 m are sub-pixel slivers. 0 = draw every ring (GPU Gems 2).
    double minRingPixels = 0.0;
};

/// What ring thinning sees of a frame: the camera's height above mean sea level plus the vertical reach of
/// the waves (2 Hs), the screen's pixels per radian (vertical), the Earth's radius (0 = flat).
struct RingView {
    double height = 0.0;
    double pixelsPerRadian = 0.0;
    double earthRadius = 0.0;
};

/// The horizontal directions a camera can see: azimuths center +- halfWidth (radians, atan2(y, x) of the
/// camera-relative position). halfWidth = pi is the whole circle.
struct ViewSector {
    double center = 0.0;
    double halfWidth = 3.14159265358979323846;
};

/// The sector of the camera's frustum projected onto the horizontal plane, widened by guardRad on each side
/// (the whole circle when the frustum contains the nadir or the zenith). Issue: "no vertices behind the
/// camera".
ViewSector computeViewSector(const CameraFrame& camera, double guardRad);

/// The radius of the disc around the camera's nadir none of whose sea can be in view: every point within
/// horizontal distance R of the camera, at any height from verticalReach above mean sea level down (the
/// Earth's curvature only lowers the sea), lies outside one of the frustum's side planes. The rings inside
/// it need not be drawn (OceanDesc::skipHiddenRings). 0 when there is none: the camera within the reach,
/// looking up, or the nadir in view.
double hiddenDiscRadius(const CameraFrame& camera, double verticalReach);

/// Camera-relative position of grid vertex (u, r) in `sector`, exactly as ocean.vert computes it.
glm::dvec2 sectorPosition(double u, double r, const ViewSector& sector, double guardDistance);

class RadialGrid {
public:
    /// Throws std::invalid_argument naming the bad field (e.g. "RadialGridDesc.rings must be >= 2, got 1").
    explicit RadialGrid(const RadialGridDesc& desc);
    /// The constructor's checks without building the mesh: throws std::invalid_argument naming the field.
    static void validate(const RadialGridDesc& desc);

    const RadialGridDesc& desc() const { return mDesc; }
    double a0() const { return mA0; }
    double a1() const { return mA1; }
    /// r_i = a0 + a1 * i^4 in double (§18.2.3).
    double radius(int ring) const;

    /// Interleaved vertex data, 2 floats per vertex: u in [0, 1] across the view sector, r in metres.
    /// Vertex 0 is the centre; ring i's column j (u = j / M, j = 0..M) is vertex vertexIndex(i, j) =
    /// 1 + i S + j. The ring stride S >= M + 1 pads each ring for vertex reuse (ocean/src/GridOrder.h):
    /// the padding repeats the ring's last vertex (u = 1) and is never indexed.
    const std::vector<float>& vertices() const { return mVertices; }
    /// Triangle list indices (counter-clockwise seen from above, +z up): the centre fan, then the quads
    /// between rings in blocks of columns, each block ring by ring outward (GridOrder.h).
    const std::vector<uint32_t>& indices() const { return mIndices; }

    /// Ring thinning (RadialGridDesc::minRingPixels): the rings to draw for `view`, ascending. Ring 0 (the
    /// centre fan's), the last displaced ring (rMax) and every skirt ring are always kept; ring i in between
    /// is kept when the depression angle below the horizon, atan((h + r^2 / 2R) / r), differs from the last
    /// kept ring's by at least minPixels / pixelsPerRadian, or when ring i + 1 lies more than 1.1 times the
    /// last kept ring's radius out (short chords: the horizon stays put). minPixels <= 0 keeps every ring.
    std::vector<int> ringsFor(const RingView& view, double minPixels) const;
    /// Triangle list indices joining consecutive rings of `rings` (from ringsFor), same winding as indices();
    /// ringsFor(view, 0) gives exactly indices().
    std::vector<uint32_t> indicesFor(const std::vector<int>& rings) const;
    /// A range of indices (first, count) of indicesFor().
    struct IndexRange {
        size_t first = 0, count = 0;
    };
    /// The ranges of indicesFor(rings) (rings.size() == ringsDrawn) that draw the quads between rings
    /// firstPair .. ringsDrawn - 1 of the selection, leaving out the centre fan and the ring pairs inside
    /// (one range per block of columns); firstPair 0 gives the whole list. Empty when every pair is left out.
    std::vector<IndexRange> rangesFrom(size_t ringsDrawn, size_t firstPair) const;
    /// Ring i's radius as stored (the skirt's included), metres.
    double ringRadius(int ring) const;
    /// Rings including the skirt.
    int ringCount() const;
    /// Index of ring `ring`'s vertex in column `column` (0..M) in vertices().
    uint32_t vertexIndex(int ring, int column) const;
    /// Vertices in vertices(), padding included.
    size_t vertexCount() const { return mVertices.size() / 2; }
    /// Vertices the indices name (the centre and every ring's M + 1 columns): those a draw shades.
    size_t indexedVertexCount() const;
    /// S, the distance between consecutive rings' vertices.
    int ringStride() const { return mRingStride; }
    /// The ring stride of a grid of `segments` segments, without building it.
    static int ringStrideFor(int segments);

private:
    RadialGridDesc mDesc;
    double mA0 = 0.0, mA1 = 0.0;
    int mRingStride = 0;
    std::vector<float> mVertices;
    std::vector<uint32_t> mIndices;
};

} // namespace pacifica::ocean
