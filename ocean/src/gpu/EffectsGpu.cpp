// EffectsGpu: packs the effects into the effects.glsl buffers, bins them into the effects field's tiles,
// evaluates the field, and draws the secondary radial grids it chose.
#include "gpu/EffectsGpu.h"

#include "GridOrder.h"
#include "gpu/GpuInterface.h"

#include "ocean/OceanConstants.h"

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <thread>
#include <utility>

namespace pacifica::ocean {

namespace {

/// Bounding-sphere test against the side planes of the frustum and the camera's front (reverse-Z infinite
/// projection: no far plane). Planes from the rows of viewProj (Gribb & Hartmann 2001).
bool sphereInView(const glm::mat4& m, const glm::vec3& c, float r) {
    const glm::vec4 row0(m[0][0], m[1][0], m[2][0], m[3][0]);
    const glm::vec4 row1(m[0][1], m[1][1], m[2][1], m[3][1]);
    const glm::vec4 row3(m[0][3], m[1][3], m[2][3], m[3][3]);
    const glm::vec4 planes[5] = {row3 + row0, row3 - row0, row3 + row1, row3 - row1, row3};
    for (const glm::vec4& p : planes) {
        const float len = glm::length(glm::vec3(p));
        if (len > 0.0f && glm::dot(glm::vec3(p), c) + p.w < -r * len)
            return false;
    }
    return true;
}

} // namespace

void EffectsGpu::ensureMesh(Mesh& mesh, int rings, int segments, double exponent, int& uploads) {
    if (mesh.vao && mesh.rings == rings && mesh.segments == segments)
        return;
    // The unit disc: a centre vertex and rings at rho_i = (i / N)^p (GPU Gems 2 §18.2.3's radial grid with
    // a gentler exponent than its i^4: an effect's waves fill its whole disc). Rings are padded to a stride
    // for vertex reuse (GridOrder.h: an effect vertex's shading is the dearest of all, a wake's walks its
    // path); the padding repeats the ring's first vertex and is never indexed.
    const int stride = gridorder::rowStride(segments);
    std::vector<float> v{0.0f, 0.0f};
    auto addRing = [&](double rho) {
        for (int j = 0; j < stride; ++j) {
            const double a = 2.0 * std::numbers::pi * (j < segments ? j : 0) / segments;
            v.push_back(static_cast<float>(rho * std::cos(a)));
            v.push_back(static_cast<float>(rho * std::sin(a)));
        }
    };
    for (int i = 1; i <= rings; ++i)
        addRing(std::pow(static_cast<double>(i) / rings, exponent));
    // The skirt: the rim again, marked by length 2 (effects.vert hangs it below the surface). The base grid
    // and the effect grid tessellate the base surface differently, so along the rim their heights differ by
    // the interpolation error; a grazing ray could slip through that sliver. The skirt closes it, the way
    // terrain LOD closes cracks between tiles.
    addRing(2.0);
    auto at = [segments, stride](int ring, int j) {
        return static_cast<uint32_t>(1 + (ring - 1) * stride + (j % segments));
    };
    std::vector<uint32_t> idx;
    for (int j = 0; j < segments; ++j)
        idx.insert(idx.end(), {0u, at(1, j), at(1, j + 1)});
    std::vector<int> rows(static_cast<size_t>(rings + 1));
    for (int i = 1; i <= rings + 1; ++i)
        rows[static_cast<size_t>(i - 1)] = i; // the disc's rings, then the skirt
    gridorder::appendQuadsInBlocks(idx, rows, segments, at);
    static_cast<GridMesh&>(mesh) = GridMesh::upload(v, idx);
    mesh.skirtCount = stride;
    mesh.rings = rings;
    mesh.segments = segments;
    uploads += 2;
}

void EffectsGpu::upload(gl::Buffer& buffer, size_t& capacity, const void* data, size_t bytes, int& uploads) {
    if (!buffer || capacity < bytes) {
        capacity = std::max<size_t>(bytes, 2 * capacity);
        buffer = gl::Buffer::create(capacity, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    buffer.upload(0, bytes, data);
    ++uploads;
}

namespace {

/// Whether an effect's disc (raised by the height bound, dropped by the Earth's curvature) can be in view.
struct ViewTest {
    const OceanFrame& frame;
    double heightBound;
    bool operator()(const glm::dvec2& rel, double radius) const {
        const double k = 1.0 / (2.0 * EARTH_RADIUS);
        const double d = glm::length(rel);
        const double drop = d * d * k;
        const double r = radius + heightBound + (2.0 * d * radius + radius * radius) * k;
        return sphereInView(frame.camera.viewProj, glm::vec3(rel.x, rel.y, -frame.camera.origin.z - drop),
                            static_cast<float>(r));
    }
};

/// An effect as packed for the GPU, with what the grid choice and the tile binning need.
struct Candidate {
    glm::dvec2 lo, hi;   ///< camera-relative box where its field can be non-zero
    glm::dvec2 centre;   ///< camera-relative grid centre
    double radius = 0.0; ///< grid radius
    double size = 0.0;   ///< radius / distance from the camera; < 0: not in view
    double pixels = 0.0; ///< the largest wave amplitude's height on screen, pixels
};

Candidate candidate(const glm::dvec2& rel, double radius, const glm::dvec2& boxMin, const glm::dvec2& boxMax,
                    double amplitude, const OceanFrame& frame, const ViewTest& inView) {
    Candidate c;
    c.centre = rel;
    c.radius = radius;
    c.lo = rel + glm::max(boxMin, glm::dvec2(-radius));
    c.hi = rel + glm::min(boxMax, glm::dvec2(radius));
    const double distance = std::max(glm::length(glm::dvec3(rel, frame.camera.origin.z)), 1.0);
    c.size = inView(rel, radius) ? radius / distance : -1.0;
    // The focal length in pixels (the projection's y scale times half the height), as ring thinning takes it.
    const double focalPixels = std::abs(frame.camera.proj[1][1]) * 0.5 * frame.height;
    c.pixels = std::abs(amplitude) * focalPixels / distance;
    return c;
}

/// Every explosion under way at t, packed (GpuInterface.h).
std::vector<ExplosionGpu> packExplosions(std::span<const Explosion> explosions, const OceanFrame& frame,
                                         const ViewTest& inView, std::vector<Candidate>& out) {
    std::vector<ExplosionGpu> packed;
    const glm::dvec3 cam = frame.camera.origin;
    for (const Explosion& e : explosions) {
        const ExplosionState s = explosionState(e, frame.time);
        if (s.radius <= 0.0)
            continue;
        const glm::dvec2 rel = e.center - glm::dvec2(cam);
        ExplosionGpu g;
        g.centre = glm::vec2(static_cast<float>(rel.x), static_cast<float>(rel.y));
        g.gridRadius = static_cast<float>(s.radius);
        g.amplitude = static_cast<float>(s.amplitude);
        g.wavenumber = static_cast<float>(e.params.wavenumber);
        g.phase = static_cast<float>(s.phase);
        g.coreRadius = static_cast<float>(e.params.coreRadius);
        g.front = static_cast<float>(s.front);
        g.frontWidth = static_cast<float>(s.frontWidth);
        g.crownFoam = static_cast<float>(s.foam);
        g.crownRadius = static_cast<float>(s.crownRadius);
        g.peakAmplitude = static_cast<float>(e.params.amplitude);
        g.slick = static_cast<float>(s.slick);
        g.slickRadius = static_cast<float>(s.slickRadius);
        packed.push_back(g);
        out.push_back(candidate(rel, s.radius, glm::dvec2(-s.radius), glm::dvec2(s.radius), s.amplitude,
                                frame, inView));
    }
    return packed;
}

/// One wake: its header and its 2 * MAX_WAKE_POINTS point vec4s.
void packWake(const WakeState& s, const glm::dvec2& rel, std::vector<WakeGpu>& headers,
              std::vector<glm::vec4>& points) {
    WakeGpu h;
    h.ship = glm::vec2(static_cast<float>(rel.x), static_cast<float>(rel.y));
    h.gridRadius = static_cast<float>(s.radius);
    h.points = static_cast<float>(s.offsets.size());
    h.shipLength = static_cast<float>(s.length);
    h.beam = static_cast<float>(s.beam);
    h.waveLife = static_cast<float>(s.waveLife);
    h.foamLife = static_cast<float>(s.foamLife);
    h.boxMin = glm::vec2(s.boxMin);
    h.boxMax = glm::vec2(s.boxMax);
    headers.push_back(h);
    const size_t first = points.size();
    points.resize(first + 2 * MAX_WAKE_POINTS, glm::vec4(0.0f));
    for (size_t i = 0; i < s.offsets.size(); ++i) {
        points[first + 2 * i] =
            glm::vec4(static_cast<float>(s.offsets[i].x), static_cast<float>(s.offsets[i].y),
                      static_cast<float>(s.sigma[i]), static_cast<float>(s.age[i]));
        points[first + 2 * i + 1] =
            glm::vec4(static_cast<float>(s.amplitude[i]), static_cast<float>(s.k0[i]), 0.0f, 0.0f);
    }
}

/// The indices of the effects that get a grid: in view, at least `minSize` on screen with waves at least
/// `minPixels` tall there (EffectGridDesc), the largest first, at most `max`.
std::vector<int> chooseGrids(const std::vector<Candidate>& c, size_t first, size_t last, double minSize,
                             double minPixels, int max) {
    std::vector<int> chosen;
    for (size_t i = first; i < last; ++i)
        if (c[i].size >= minSize && c[i].size >= 0.0 && c[i].pixels >= minPixels)
            chosen.push_back(static_cast<int>(i));
    std::stable_sort(chosen.begin(), chosen.end(), [&](int a, int b) { return c[a].size > c[b].size; });
    if (chosen.size() > static_cast<size_t>(max))
        chosen.resize(static_cast<size_t>(max));
    return chosen;
}

} // namespace

struct EffectsGpu::Footprint {
    glm::dvec2 lo, hi;              // camera-relative box
    std::vector<glm::dvec2> points; // wakes: the path, camera-relative, newest first
    std::vector<double> reach;      // wakes: per segment, how far from it the field can be non-zero
};

namespace {

/// A wake's path for the tile test: its points and, per segment j (points j, j + 1), the distance from it
/// within which the wake can be non-zero at a point whose nearest segment it is: the Kelvin wedge
/// |y| < sqrt(1/8) x (plus the slope stencil's 0.1 m) up to the segment's older end, or the foam strip's
/// 3 widths (wakeFoam) plus a beam ahead of the ship, whichever is wider.
void wakePath(const WakeState& s, const glm::dvec2& rel, std::vector<glm::dvec2>& points,
              std::vector<double>& reach) {
    for (const glm::dvec2& o : s.offsets)
        points.push_back(rel + o);
    for (size_t j = 0; j + 1 < s.offsets.size(); ++j) {
        const double sigma = s.sigma[j + 1];
        const double wave = std::sqrt(KELVIN_TAN2) * (sigma + 0.1) + 0.1;
        const double foam = 3.0 * s.beam * (1.0 + sigma / 400.0) + s.beam;
        reach.push_back(std::max(wave, foam) + 0.01);
    }
}

/// The path segments of a wake that can be nearest to a point within `half` of `centre` (camera-relative),
/// searched among segments first..last: {first, last} of those, or {-1, -1} when no such point is within a
/// segment's reach widened by `widen` (3 F of the level's foam prefilter: wakeFoam) (the wake is 0 there).
/// Distances from the centre bound those from any point within
/// +-half. A segment left out is farther from every such point than the nearest one by more than
/// effects.glsl's tie margin (1e-4 on squared distances) and float rounding, so a walk over the range finds
/// what the whole walk finds; and the nearest segment is always in the range, so checking the reach over the
/// range suffices. Segment 0 is the half-line through the ship, as wakeCoords() takes it.
std::pair<int, int> wakeSegments(const std::vector<glm::dvec2>& p, const std::vector<double>& reach,
                                 int first, int last, const glm::dvec2& centre, double half, double widen) {
    double dist[MAX_WAKE_POINTS];
    double best = std::numeric_limits<double>::infinity();
    for (int j = first; j <= last; ++j) {
        const glm::dvec2 ab = p[j + 1] - p[j];
        const double len2 = glm::dot(ab, ab);
        const double u = len2 > 0.0 ? glm::dot(centre - p[j], ab) / len2 : 0.0;
        const double uc = j == 0 ? std::min(u, 1.0) : std::clamp(u, 0.0, 1.0);
        dist[j] = glm::length(centre - (p[j] + uc * ab));
        best = std::min(best, dist[j] + half);
    }
    const double limit = best * 1.0002 + 0.01 + 1e-6 * glm::length(centre);
    int from = -1, to = -1;
    bool reached = false;
    for (int j = first; j <= last; ++j)
        if (dist[j] - half <= limit) {
            from = from < 0 ? j : from;
            to = j;
            reached = reached || dist[j] - half <= reach[static_cast<size_t>(j)] + widen;
        }
    return reached ? std::pair{from, to} : std::pair{-1, -1};
}

} // namespace

void EffectsGpu::ensureField(const EffectFieldDesc& field) {
    if (mField && mFieldDesc.size == field.size && mFieldDesc.levels == field.levels)
        return;
    mField = gl::Texture::createArray2D(GL_RGBA32F, field.size, field.size, field.levels, 1);
    glTextureParameteri(mField.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(mField.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(mField.id(), 0, GL_RGBA, GL_FLOAT, zero);
    mFieldDesc = field;
    const int tiles = field.size / 8;
    mWritten.assign(static_cast<size_t>(field.levels) * tiles * tiles, 0);
    ++mFieldStats.uploads;
}

/// The tiles of each level that the effects touch (their box, widened by a texel for the bilinear read),
/// skipping the tiles no read reaches: those inside the part of the next finer level that is read alone.
/// Tiles written last frame and touched by none now are listed with no effects (effects_field.comp clears
/// them).
namespace {

/// The field's tiles of 8 x 8 texels: level l's tile (tx, ty) is index(l, tx, ty). Positions are
/// camera-relative.
struct TileGrid {
    struct Range {
        int x0, y0, x1, y1;
    };
    const EffectFieldLayout& layout;
    glm::dvec2 camera;
    int size, perSide;
    size_t perLevel;

    TileGrid(const EffectFieldLayout& l, const glm::dvec2& cam)
        : layout(l), camera(cam), size(l.desc().size), perSide(l.desc().size / 8),
          perLevel(static_cast<size_t>(perSide) * perSide) {}
    size_t count() const { return perLevel * static_cast<size_t>(layout.levels()); }
    size_t index(int l, int tx, int ty) const {
        return static_cast<size_t>(l) * perLevel + static_cast<size_t>(ty * perSide + tx);
    }
    /// The tiles of level l a box touches, widened by a texel (the bilinear read), [x0, x1] x [y0, y1].
    Range range(const glm::dvec2& boxLo, const glm::dvec2& boxHi, int l) const {
        const EffectFieldLevel& level = layout.level(l);
        const glm::dvec2 origin = level.centre - camera;
        const glm::dvec2 lo = (boxLo - origin) / level.texel + 0.5 * size - 1.5;
        const glm::dvec2 hi = (boxHi - origin) / level.texel + 0.5 * size + 0.5;
        return {std::max(0, static_cast<int>(std::floor(lo.x / 8.0))),
                std::max(0, static_cast<int>(std::floor(lo.y / 8.0))),
                std::min(perSide - 1, static_cast<int>(std::floor(hi.x / 8.0))),
                std::min(perSide - 1, static_cast<int>(std::floor(hi.y / 8.0)))};
    }
    /// The centre of tile (tx, ty) of level l (fractional: of a block of tiles); its texel centres lie
    /// within +-3.5 texels.
    glm::dvec2 centre(int l, double tx, double ty) const {
        const EffectFieldLevel& level = layout.level(l);
        return level.centre - camera + (glm::dvec2(tx, ty) * 8.0 + 4.0 - 0.5 * size) * level.texel;
    }
    /// Per tile, whether any read reaches it: not those inside the part of the next finer level that is
    /// read alone, nor (FieldReads) those out of the reach of the view sector and of every drawn grid's disc
    /// (each tile widened by a texel for the bilinear read). Only the tiles that the camera-relative box
    /// [boxLo, boxHi] (all the effects' footprints) touches are judged: no other tile is binned.
    std::vector<uint8_t> neededMask(const FieldReads& reads, const std::vector<glm::vec4>& grids,
                                    const glm::dvec2& boxLo, const glm::dvec2& boxHi) const {
        std::vector<uint8_t> needed(count(), 0);
        const SectorTest sector(reads.sector);
        for (int l = 0; l < layout.levels(); ++l) {
            const EffectFieldLevel& level = layout.level(l);
            const EffectFieldLevel* finer = l > 0 ? &layout.level(l - 1) : nullptr;
            // Read alone within this (Chebyshev) of the finer level's centre.
            const double pure = finer ? finer->inner - finer->band : -1.0;
            const Range r = range(boxLo, boxHi, l);
            for (int ty = r.y0; ty <= r.y1; ++ty)
                for (int tx = r.x0; tx <= r.x1; ++tx) {
                    const glm::dvec2 lo =
                        level.centre + (glm::dvec2(tx, ty) * 8.0 - 0.5 * size - 1.0) * level.texel;
                    const glm::dvec2 hi = lo + (8.0 + 2.0) * level.texel;
                    if (finer) {
                        const glm::dvec2 a = glm::abs(lo - finer->centre), b = glm::abs(hi - finer->centre);
                        if (std::max({a.x, a.y, b.x, b.y}) <= pure)
                            continue;
                    }
                    needed[index(l, tx, ty)] =
                        sector.all || reached(lo - camera, hi - camera, reads.guard, sector, grids);
                }
        }
        return needed;
    }

    /// Whether a box meets the cone from the camera over a sector's azimuths. Conservative for sectors
    /// narrower than a half-plane (a box can be kept that straddles both edges' lines behind the camera),
    /// exact otherwise.
    struct SectorTest {
        bool all = false;           ///< the whole circle
        bool wide = false;          ///< wider than a half-plane
        glm::dvec2 left{}, right{}; ///< the edges' directions, counter-clockwise and clockwise
        explicit SectorTest(const ViewSector& s) : all(s.halfWidth >= std::numbers::pi) {
            wide = s.halfWidth > 0.5 * std::numbers::pi;
            left = {std::cos(s.center + s.halfWidth), std::sin(s.center + s.halfWidth)};
            right = {std::cos(s.center - s.halfWidth), std::sin(s.center - s.halfWidth)};
        }
        bool meets(const glm::dvec2& lo, const glm::dvec2& hi) const {
            if (all)
                return true;
            int beyondLeft = 0, beyondRight = 0, beyondBoth = 0;
            for (const glm::dvec2& v : {lo, hi, glm::dvec2(lo.x, hi.y), glm::dvec2(hi.x, lo.y)}) {
                const bool l = left.x * v.y - left.y * v.x > 0.0;   // counter-clockwise of the left edge
                const bool r = right.x * v.y - right.y * v.x < 0.0; // clockwise of the right edge
                beyondLeft += l;
                beyondRight += r;
                beyondBoth += l && r;
            }
            // Up to a half-plane the sector is the intersection of the edges' half-planes; wider, what it
            // leaves out is the (convex) intersection of their outsides.
            return wide ? beyondBoth < 4 : beyondLeft < 4 && beyondRight < 4;
        }
    };

    /// Whether a reader can sample the camera-relative box [lo, hi]: it lies within `guard` of the view
    /// sector, or meets a drawn grid's disc widened by the guard.
    static bool reached(glm::dvec2 lo, glm::dvec2 hi, double guard, const SectorTest& sector,
                        const std::vector<glm::vec4>& grids) {
        lo -= guard;
        hi += guard;
        if (sector.meets(lo, hi))
            return true;
        for (const glm::vec4& g : grids) {
            const glm::dvec2 c(g.x, g.y);
            if (glm::length(glm::clamp(c, lo, hi) - c) <= static_cast<double>(g.z))
                return true;
        }
        return false;
    }
};

/// (tile, list entry) pairs of one kind.
using TileEntries = std::vector<std::pair<uint32_t, int32_t>>;

/// An explosion's entries: every needed tile its box touches, on every level.
void binExplosion(const TileGrid& grid, const std::vector<uint8_t>& needed, const glm::dvec2& lo,
                  const glm::dvec2& hi, int index, TileEntries& out) {
    for (int l = 0; l < grid.layout.levels(); ++l) {
        const TileGrid::Range r = grid.range(lo, hi, l);
        for (int ty = r.y0; ty <= r.y1; ++ty)
            for (int tx = r.x0; tx <= r.x1; ++tx)
                if (needed[grid.index(l, tx, ty)])
                    out.emplace_back(static_cast<uint32_t>(grid.index(l, tx, ty)), index);
    }
}

/// A wake's entries, (index, first, last segment) packed (wakeSegments()): blocks of 4 x 4 tiles first
/// (their segment range bounds their tiles', and a block out of reach is skipped whole), then each tile.
void binWake(const TileGrid& grid, const std::vector<uint8_t>& needed, const glm::dvec2& lo,
             const glm::dvec2& hi, const std::vector<glm::dvec2>& points, const std::vector<double>& reach,
             int index, TileEntries& out) {
    const int segments = static_cast<int>(reach.size());
    if (segments == 0)
        return;
    for (int l = 0; l < grid.layout.levels(); ++l) {
        const TileGrid::Range r = grid.range(lo, hi, l);
        const double texel = grid.layout.level(l).texel;
        const double widen = 3.0 * std::sqrt(grid.layout.level(l).foamFilter2);
        for (int by = r.y0 / 4; by <= r.y1 / 4; ++by)
            for (int bx = r.x0 / 4; bx <= r.x1 / 4; ++bx) {
                const auto [bFirst, bLast] = wakeSegments(points, reach, 0, segments - 1,
                                                          grid.centre(l, 4.0 * bx + 1.5, 4.0 * by + 1.5),
                                                          (16.0 - 0.5) * std::sqrt(2.0) * texel, widen);
                if (bFirst < 0)
                    continue;
                for (int ty = std::max(r.y0, 4 * by); ty <= std::min(r.y1, 4 * by + 3); ++ty)
                    for (int tx = std::max(r.x0, 4 * bx); tx <= std::min(r.x1, 4 * bx + 3); ++tx) {
                        if (!needed[grid.index(l, tx, ty)])
                            continue;
                        const auto [first, last] =
                            wakeSegments(points, reach, bFirst, bLast, grid.centre(l, tx, ty),
                                         3.5 * std::sqrt(2.0) * texel, widen);
                        if (first >= 0)
                            out.emplace_back(static_cast<uint32_t>(grid.index(l, tx, ty)),
                                             index | first << 16 | last << 23);
                    }
            }
    }
}

/// Every wake's entries, in wake order (footprints: the explosions' first, then the wakes'). A wake's
/// binning costs about its tiles (~8,600 for a 1.2 km trail seen from 100 m at 1080p, ~60 ns each), so a
/// fleet's is split over threads: contiguous runs of wakes, each into its own list, joined in order (the same
/// entries as one thread). At least 4 wakes per thread keep a thread's start (tens of microseconds) small
/// against its work.
template <class Footprints>
void binWakes(const TileGrid& grid, const std::vector<uint8_t>& needed, const Footprints& footprints,
              int explosions, TileEntries& out) {
    const int wakes = static_cast<int>(footprints.size()) - explosions;
    auto run = [&](int from, int to, TileEntries& into) {
        for (int w = from; w < to; ++w) {
            const auto& f = footprints[static_cast<size_t>(explosions + w)];
            binWake(grid, needed, f.lo, f.hi, f.points, f.reach, w, into);
        }
    };
    constexpr int MIN_WAKES_PER_THREAD = 4;
    const int cores = static_cast<int>(std::thread::hardware_concurrency());
    const int threads = std::clamp(std::min(cores, wakes / MIN_WAKES_PER_THREAD), 1, 16);
    if (threads == 1) {
        run(0, wakes, out);
        return;
    }
    std::vector<TileEntries> parts(static_cast<size_t>(threads));
    std::vector<std::thread> workers;
    for (int t = 1; t < threads; ++t)
        workers.emplace_back(run, wakes * t / threads, wakes * (t + 1) / threads, std::ref(parts[size_t(t)]));
    run(0, wakes / threads, parts[0]);
    for (std::thread& w : workers)
        w.join();
    for (const TileEntries& p : parts)
        out.insert(out.end(), p.begin(), p.end());
}

} // namespace

void EffectsGpu::binTiles(const std::vector<Footprint>& footprints, int explosions, const FieldReads& reads,
                          const std::vector<glm::vec4>& grids) {
    const TileGrid grid(mLayout, mCamera);
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (const Footprint& f : footprints) {
        lo = glm::min(lo, f.lo);
        hi = glm::max(hi, f.hi);
    }
    const std::vector<uint8_t> needed = grid.neededMask(reads, grids, lo, hi);
    TileEntries entries[2]; // explosions', wakes'
    for (int g = 0; g < explosions; ++g)
        binExplosion(grid, needed, footprints[size_t(g)].lo, footprints[size_t(g)].hi, g, entries[0]);
    binWakes(grid, needed, footprints, explosions, entries[1]);
    std::vector<int> counts(2 * grid.count(), 0); // [tile][kind]
    for (int kind = 0; kind < 2; ++kind)
        for (const auto& [t, e] : entries[kind])
            ++counts[2 * t + kind];
    // The tiles to write (with effects, or written last frame: cleared) and each one's list.
    std::vector<EffectTileGpu> tiles;
    std::vector<int> cursor(2 * grid.count(), -1);
    int listSize = 0;
    // Per level, the box of its tiles with effects: every texel outside is 0 this frame.
    mLevelBoxes.assign(static_cast<size_t>(mLayout.levels()), glm::vec4(1e30f, 1e30f, -1e30f, -1e30f));
    for (size_t t = 0; t < grid.count(); ++t) {
        const int e = counts[2 * t], w = counts[2 * t + 1];
        if (e + w == 0 && !mWritten[t])
            continue;
        const int l = static_cast<int>(t / grid.perLevel), within = static_cast<int>(t % grid.perLevel);
        const int tx = within % grid.perSide, ty = within / grid.perSide;
        if (e + w > 0) {
            const glm::dvec2 c = grid.centre(l, tx, ty);
            const double half = 3.5 * mLayout.level(l).texel;
            glm::vec4& box = mLevelBoxes[static_cast<size_t>(l)];
            box = glm::vec4(glm::min(glm::vec2(box), glm::vec2(c - half)),
                            glm::max(glm::vec2(box.z, box.w), glm::vec2(c + half)));
        }
        tiles.push_back({l, tx, ty, listSize, e, w, 0, 0});
        mFieldStats.cleared += e + w == 0;
        cursor[2 * t] = listSize;
        cursor[2 * t + 1] = listSize + e;
        listSize += e + w;
        mWritten[t] = e + w > 0;
    }
    std::vector<int32_t> lists(static_cast<size_t>(std::max(listSize, 1)), 0);
    for (int kind = 0; kind < 2; ++kind)
        for (const auto& [t, e] : entries[kind])
            lists[static_cast<size_t>(cursor[2 * t + kind]++)] = e;
    mTileCount = static_cast<int>(tiles.size());
    mFieldStats.tiles = mTileCount;
    mFieldStats.texels = 64LL * mTileCount;
    if (mTileCount > 0) {
        upload(mTileBuffer, mTileCapacity, tiles.data(), tiles.size() * sizeof(EffectTileGpu),
               mFieldStats.uploads);
        upload(mListBuffer, mListCapacity, lists.data(), lists.size() * sizeof(int32_t), mFieldStats.uploads);
    }
}

void EffectsGpu::prepare(const EffectsView& effects, const OceanFrame& frame, double heightBound,
                         const EffectGridDesc& grids, const EffectFieldDesc& field, const FieldReads& reads) {
    mExplosionUploads = mWakeUploads = 0;
    mExplosionCount = mWakeCount = mExplosionsDrawn = mWakesDrawn = 0;
    mFieldStats = {};
    mTileCount = 0;
    mGridCentres.clear();
    const glm::dvec3 cam = frame.camera.origin;
    mCamera = glm::dvec2(cam);
    mLayout = effectFieldLayout(field, frame);
    const ViewTest inView{frame, heightBound};
    std::vector<Candidate> candidates;
    const std::vector<ExplosionGpu> explosions =
        packExplosions(effects.explosions, frame, inView, candidates);
    std::vector<WakeGpu> wakes;
    std::vector<glm::vec4> points;
    std::vector<Footprint> wakePaths;
    for (const WakeRef& wake : effects.wakes) {
        if (!wake.trail->active)
            continue;
        const WakeState s = wakeState(*wake.ship, *wake.trail, frame.time);
        if (s.radius <= 0.0)
            continue;
        const glm::dvec2 rel = s.ship - mCamera;
        packWake(s, rel, wakes, points);
        candidates.push_back(candidate(rel, s.radius, s.boxMin, s.boxMax, s.peak, frame, inView));
        wakePaths.emplace_back();
        wakePath(s, rel, wakePaths.back().points, wakePaths.back().reach);
    }
    mExplosionCount = static_cast<int>(explosions.size());
    mWakeCount = static_cast<int>(wakes.size());
    if (!any())
        return;
    ensureField(field);
    if (mExplosionCount > 0)
        upload(mExplosionBuffer, mExplosionCapacity, explosions.data(),
               explosions.size() * sizeof(ExplosionGpu), mExplosionUploads);
    if (mWakeCount > 0) {
        upload(mWakeBuffer, mWakeCapacity, wakes.data(), wakes.size() * sizeof(WakeGpu), mWakeUploads);
        upload(mWakePointBuffer, mWakePointCapacity, points.data(), points.size() * sizeof(glm::vec4),
               mWakeUploads);
    }
    std::vector<Footprint> footprints;
    for (size_t i = 0; i < candidates.size(); ++i) {
        Footprint f = i < explosions.size() ? Footprint{} : std::move(wakePaths[i - explosions.size()]);
        f.lo = candidates[i].lo;
        f.hi = candidates[i].hi;
        footprints.push_back(std::move(f));
    }
    // The grids: explosions' then wakes', each (centre - camera, radius, 0).
    const size_t e = static_cast<size_t>(mExplosionCount);
    const std::vector<int> explosionGrids = chooseGrids(candidates, 0, e, grids.minAngularSize,
                                                        grids.minAmplitudePixels, grids.maxExplosionGrids);
    const std::vector<int> wakeGrids = chooseGrids(candidates, e, candidates.size(), grids.minAngularSize,
                                                   grids.minAmplitudePixels, grids.maxWakeGrids);
    mExplosionsDrawn = static_cast<int>(explosionGrids.size());
    mWakesDrawn = static_cast<int>(wakeGrids.size());
    std::vector<glm::vec4> gridList;
    mGridCentres.clear();
    for (const std::vector<int>* chosen : {&explosionGrids, &wakeGrids})
        for (int i : *chosen) {
            mGridCentres.push_back(mCamera + candidates[i].centre);
            gridList.emplace_back(static_cast<float>(candidates[i].centre.x),
                                  static_cast<float>(candidates[i].centre.y),
                                  static_cast<float>(candidates[i].radius), 0.0f);
        }
    binTiles(footprints, mExplosionCount, reads, gridList);
    if (gridList.empty())
        gridList.emplace_back(0.0f); // a bound buffer, never read (uEffectGridCount = 0)
    upload(mGridBuffer, mGridCapacity, gridList.data(), gridList.size() * sizeof(glm::vec4),
           mFieldStats.uploads);
    if (mExplosionsDrawn > 0)
        ensureMesh(mExplosionMesh, grids.explosionRings, grids.explosionSegments, grids.explosionExponent,
                   mExplosionUploads);
    if (mWakesDrawn > 0)
        ensureMesh(mWakeMesh, grids.wakeRings, grids.wakeSegments, grids.wakeExponent, mWakeUploads);
}

std::string EffectsGpu::defines() const {
    std::string d;
    if (mExplosionCount > 0)
        d += "#define EFFECTS_EXPLOSIONS\n";
    if (mWakeCount > 0)
        d += "#define EFFECTS_WAKES\n";
    return d;
}

namespace {

/// (level centre - camera, texel) of each level, as effects_field.comp and effects_sample.glsl take them.
void setLevelUniforms(unsigned program, const EffectFieldLayout& layout, const glm::dvec2& camera,
                      const std::vector<glm::vec4>& boxes) {
    if (!boxes.empty()) {
        glProgramUniform4fv(program, glGetUniformLocation(program, "uEffectFieldBoxes"),
                            static_cast<GLsizei>(boxes.size()), glm::value_ptr(boxes[0]));
        glm::vec4 bounds(1e30f, 1e30f, -1e30f, -1e30f);
        for (size_t l = 0; l < boxes.size(); ++l) {
            const float texel = static_cast<float>(layout.level(static_cast<int>(l)).texel);
            if (boxes[l].x <= boxes[l].z)
                bounds = glm::vec4(glm::min(glm::vec2(bounds), glm::vec2(boxes[l]) - 2.0f * texel),
                                   glm::max(glm::vec2(bounds.z, bounds.w),
                                            glm::vec2(boxes[l].z, boxes[l].w) + 2.0f * texel));
        }
        glProgramUniform4fv(program, glGetUniformLocation(program, "uEffectFieldBounds"), 1,
                            glm::value_ptr(bounds));
    }
    std::vector<glm::vec3> levels;
    for (int l = 0; l < layout.levels(); ++l) {
        const glm::dvec2 c = layout.level(l).centre - camera;
        levels.emplace_back(static_cast<float>(c.x), static_cast<float>(c.y),
                            static_cast<float>(layout.level(l).texel));
    }
    glProgramUniform3fv(program, glGetUniformLocation(program, "uEffectFieldLevels"),
                        static_cast<GLsizei>(levels.size()), glm::value_ptr(levels[0]));
    glProgramUniform1i(program, glGetUniformLocation(program, "uEffectFieldLevelCount"), layout.levels());
    glProgramUniform1f(program, glGetUniformLocation(program, "uEffectFieldSize"),
                       static_cast<float>(layout.desc().size));
}

} // namespace

void EffectsGpu::computeField(unsigned program) {
    if (mTileCount == 0)
        return;
    glUseProgram(program);
    if (mExplosionBuffer)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_EXPLOSIONS_BINDING, mExplosionBuffer.id());
    if (mWakeBuffer) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_WAKES_BINDING, mWakeBuffer.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_WAKE_POINTS_BINDING, mWakePointBuffer.id());
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_FIELD_TILES_BINDING, mTileBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_FIELD_LISTS_BINDING, mListBuffer.id());
    glBindImageTexture(EFFECT_FIELD_IMAGE_UNIT, mField.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    setLevelUniforms(program, mLayout, mCamera, {});
    const int groupsX = std::min(mTileCount, 65535);
    glProgramUniform1i(program, glGetUniformLocation(program, "uTileCount"), mTileCount);
    glProgramUniform1i(program, glGetUniformLocation(program, "uTileGroupsX"), groupsX);
    glDispatchCompute(static_cast<GLuint>(groupsX), static_cast<GLuint>((mTileCount + groupsX - 1) / groupsX),
                      1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    mFieldStats.passes = 1;
}

void EffectsGpu::bindField(unsigned program) const {
    glBindTextureUnit(FIELD_TEXTURE_UNIT, mField.id());
    glProgramUniform1i(program, glGetUniformLocation(program, "uEffectField"), FIELD_TEXTURE_UNIT);
    setLevelUniforms(program, mLayout, mCamera, mLevelBoxes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_GRIDS_BINDING, mGridBuffer.id());
    glProgramUniform1i(program, glGetUniformLocation(program, "uEffectGridCount"),
                       mExplosionsDrawn + mWakesDrawn);
}

long long EffectsGpu::gridVertices(EffectKind kind) const {
    const Mesh& mesh = kind == EffectKind::Explosion ? mExplosionMesh : mWakeMesh;
    return mesh.vertexCount - mesh.skirtCount;
}

long long EffectsGpu::draw(unsigned program, EffectKind kind, unsigned mode) {
    const int instances = drawn(kind);
    if (instances == 0)
        return 0;
    const Mesh& mesh = kind == EffectKind::Explosion ? mExplosionMesh : mWakeMesh;
    glProgramUniform1i(program, glGetUniformLocation(program, "uFirstGrid"),
                       kind == EffectKind::Explosion ? 0 : mExplosionsDrawn);
    glBindVertexArray(mesh.vao.id());
    if (mode == GL_POINTS)
        glDrawArraysInstanced(GL_POINTS, 0, mesh.vertexCount - mesh.skirtCount, instances); // surface only
    else
        glDrawElementsInstanced(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr, instances);
    // Triangles shade the indexed vertices: the centre, the rings and the skirt (the rest is padding).
    return static_cast<long long>(mode == GL_POINTS ? mesh.vertexCount - mesh.skirtCount
                                                    : 1 + (mesh.rings + 1) * mesh.segments) *
           instances;
}

} // namespace pacifica::ocean
