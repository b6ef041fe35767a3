// EffectsGpu: packs the effects into the effects.glsl buffers and draws their secondary radial grids.
#include "gpu/EffectsGpu.h"

#include "GridOrder.h"
#include "gpu/GpuInterface.h"

#include "ocean/OceanConstants.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <numbers>

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

/// Where an effect can be non-zero, camera-relative: its disc, and (wakes) the box of its path.
struct Footprint {
    glm::dvec2 centre;
    double radius;
    glm::dvec2 boxMin, boxMax;
};

bool discMeetsBox(const glm::dvec2& c, double r, const glm::dvec2& lo, const glm::dvec2& hi) {
    const glm::dvec2 nearest = glm::clamp(c, lo, hi);
    return glm::dot(c - nearest, c - nearest) < r * r;
}

/// For each effect g (explosions 0..E-1, then wakes), the effects whose field can reach g's grid: ranges
/// (offset, count of explosions, offset, count of wakes) at [4 g, 4 g + 4), then the index lists. A grid's
/// vertices lie within its disc plus the base surface's horizontal displacement (< pad), and an effect's
/// field is 0 outside its footprint, so leaving the others out changes no value (effects.glsl
/// effectField) while the work per vertex stops growing with the number of effects far away.
std::vector<int32_t> neighbourLists(const std::vector<Footprint>& f, int explosions, double pad) {
    const size_t n = f.size();
    std::vector<int32_t> out(4 * n);
    for (size_t g = 0; g < n; ++g) {
        const double reach = f[g].radius + pad;
        for (int kind = 0; kind < 2; ++kind) {
            const size_t first = kind == 0 ? 0 : static_cast<size_t>(explosions);
            const size_t last = kind == 0 ? static_cast<size_t>(explosions) : n;
            out[4 * g + 2 * kind] = static_cast<int32_t>(out.size());
            int32_t count = 0;
            for (size_t j = first; j < last; ++j) {
                const glm::dvec2 d = f[j].centre - f[g].centre;
                const double r = reach + f[j].radius;
                if (glm::dot(d, d) < r * r && discMeetsBox(f[g].centre, reach, f[j].boxMin, f[j].boxMax)) {
                    out.push_back(static_cast<int32_t>(j - first));
                    ++count;
                }
            }
            out[4 * g + 2 * kind + 1] = count;
        }
    }
    return out;
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

/// Every explosion under way at t, packed (GpuInterface.h), the ones in view first (instance i of the
/// draw is explosion i); `drawn` gets how many are in view.
std::vector<ExplosionGpu> packExplosions(ecs::Registry& registry, const glm::dvec3& cam, double t,
                                         const ViewTest& inView, int& drawn) {
    std::vector<ExplosionGpu> visible, hidden;
    registry.view<Explosion>().each([&](ecs::Entity, Explosion& e) {
        const ExplosionState s = explosionState(e, t);
        if (s.radius <= 0.0)
            return;
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
        (inView(rel, s.radius) ? visible : hidden).push_back(g);
    });
    drawn = static_cast<int>(visible.size());
    visible.insert(visible.end(), hidden.begin(), hidden.end());
    return visible;
}

/// One wake: its header and its 2 * MAX_WAKE_POINTS point vec4s.
struct PackedWake {
    WakeGpu header;
    std::vector<glm::vec4> points;
};

PackedWake packWake(const WakeState& s, const glm::dvec2& rel) {
    PackedWake p;
    p.header.ship = glm::vec2(static_cast<float>(rel.x), static_cast<float>(rel.y));
    p.header.gridRadius = static_cast<float>(s.radius);
    p.header.points = static_cast<float>(s.offsets.size());
    p.header.shipLength = static_cast<float>(s.length);
    p.header.beam = static_cast<float>(s.beam);
    p.header.waveLife = static_cast<float>(s.waveLife);
    p.header.foamLife = static_cast<float>(s.foamLife);
    p.header.boxMin = glm::vec2(s.boxMin);
    p.header.boxMax = glm::vec2(s.boxMax);
    p.points.assign(2 * MAX_WAKE_POINTS, glm::vec4(0.0f));
    for (size_t i = 0; i < s.offsets.size(); ++i) {
        p.points[2 * i] = glm::vec4(static_cast<float>(s.offsets[i].x), static_cast<float>(s.offsets[i].y),
                                    static_cast<float>(s.sigma[i]), static_cast<float>(s.age[i]));
        p.points[2 * i + 1] =
            glm::vec4(static_cast<float>(s.amplitude[i]), static_cast<float>(s.k0[i]), 0.0f, 0.0f);
    }
    return p;
}

/// Every active trail at t, packed, the ones in view first; `drawn` gets how many are in view.
std::vector<PackedWake> packWakes(ecs::Registry& registry, const glm::dvec3& cam, double t,
                                  const ViewTest& inView, int& drawn) {
    std::vector<PackedWake> visible, hidden;
    registry.view<Ship, ShipTrail>().each([&](ecs::Entity, Ship& ship, ShipTrail& trail) {
        if (!trail.active)
            return;
        const WakeState s = wakeState(ship, trail, t);
        if (s.radius <= 0.0)
            return;
        const glm::dvec2 rel = s.ship - glm::dvec2(cam);
        (inView(rel, s.radius) ? visible : hidden).push_back(packWake(s, rel));
    });
    drawn = static_cast<int>(visible.size());
    for (PackedWake& p : hidden)
        visible.push_back(std::move(p));
    return visible;
}

} // namespace

void EffectsGpu::prepare(ecs::Registry& registry, const OceanFrame& frame, double heightBound,
                         const EffectGridDesc& grids) {
    mExplosionUploads = mWakeUploads = 0;
    mExplosionCount = mWakeCount = mExplosionsDrawn = mWakesDrawn = 0;
    const ViewTest inView{frame, heightBound};
    const std::vector<ExplosionGpu> explosions =
        packExplosions(registry, frame.camera.origin, frame.time, inView, mExplosionsDrawn);
    const std::vector<PackedWake> wakes =
        packWakes(registry, frame.camera.origin, frame.time, inView, mWakesDrawn);
    mExplosionCount = static_cast<int>(explosions.size());
    mWakeCount = static_cast<int>(wakes.size());
    std::vector<Footprint> footprints;
    for (const ExplosionGpu& g : explosions)
        footprints.push_back(
            {glm::dvec2(g.centre), double(g.gridRadius), glm::dvec2(-1e30), glm::dvec2(1e30)});
    for (const PackedWake& p : wakes) {
        const glm::dvec2 ship(p.header.ship);
        footprints.push_back({ship, double(p.header.gridRadius), ship + glm::dvec2(p.header.boxMin),
                              ship + glm::dvec2(p.header.boxMax)});
    }
    if (mExplosionCount > 0) {
        ensureMesh(mExplosionMesh, grids.explosionRings, grids.explosionSegments, grids.explosionExponent,
                   mExplosionUploads);
        upload(mExplosionBuffer, mExplosionCapacity, explosions.data(),
               explosions.size() * sizeof(ExplosionGpu), mExplosionUploads);
    }
    if (mWakeCount > 0) {
        ensureMesh(mWakeMesh, grids.wakeRings, grids.wakeSegments, grids.wakeExponent, mWakeUploads);
        std::vector<WakeGpu> headers;
        std::vector<glm::vec4> points;
        for (const PackedWake& p : wakes) {
            headers.push_back(p.header);
            points.insert(points.end(), p.points.begin(), p.points.end());
        }
        upload(mWakeBuffer, mWakeCapacity, headers.data(), headers.size() * sizeof(WakeGpu), mWakeUploads);
        upload(mWakePointBuffer, mWakePointCapacity, points.data(), points.size() * sizeof(glm::vec4),
               mWakeUploads);
    }
    if (mExplosionCount + mWakeCount > 0) {
        const std::vector<int32_t> neighbours = neighbourLists(footprints, mExplosionCount, heightBound);
        upload(mNeighbourBuffer, mNeighbourCapacity, neighbours.data(), neighbours.size() * sizeof(int32_t),
               mExplosionCount > 0 ? mExplosionUploads : mWakeUploads);
    }
}

std::string EffectsGpu::defines() const {
    std::string d;
    if (mExplosionCount > 0)
        d += "#define EFFECTS_EXPLOSIONS\n";
    if (mWakeCount > 0)
        d += "#define EFFECTS_WAKES\n";
    return d;
}

void EffectsGpu::bind(unsigned program) const {
    if (mExplosionCount > 0)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_EXPLOSIONS_BINDING, mExplosionBuffer.id());
    if (mWakeCount > 0) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_WAKES_BINDING, mWakeBuffer.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_WAKE_POINTS_BINDING, mWakePointBuffer.id());
    }
    if (mExplosionCount + mWakeCount > 0)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EFFECT_NEIGHBOURS_BINDING, mNeighbourBuffer.id());
    glProgramUniform1i(program, glGetUniformLocation(program, "uExplosionCount"), mExplosionCount);
    glProgramUniform1i(program, glGetUniformLocation(program, "uWakeCount"), mWakeCount);
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
    glProgramUniform1i(program, glGetUniformLocation(program, "uKind"),
                       kind == EffectKind::Explosion ? 0 : 1);
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
