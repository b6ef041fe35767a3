// ProjectedGrid: the projector of Johanson 2004 §2.4 for an infinite reverse-Z frustum and a curved sea, and
// the (u, v) mesh it maps. All maths is double and camera-relative: the camera sits at the origin, the base
// plane is z = -h (h = camera height), and the world position never enters.
//
// Why not Johanson's construction verbatim: he intersects the 12 edges of a *finite* frustum with the two
// flat bound planes. Here the far plane is at infinity, and with Earth curvature the bound surfaces are
// z = -h +- D - d^2/2R (d: horizontal distance), which meet a frustum face in curves, not at its edges. So:
//  - Each ray t * dir (t: depth along the view axis) meets the volume V between the bound surfaces in one
//    segment that can be seen: it starts where the ray enters the upper surface (or at the near plane when
//    the camera is inside V) and ends where it first dips below the lower surface (below that lies water
//    whatever the waves do, so nothing farther along the ray can be seen) or leaves V through the upper
//    surface again after grazing the lower one (curved sea), or at the flat sea's cap. The segment's ends,
//    projected vertically onto the base plane, are the base-plane points the grid must contain for that ray
//    (the vertex shader moves vertices only vertically, by the drop and the waves).
//  - V is symmetric about the camera's vertical, so a ray's segment depends only on its elevation, and the
//    farthest point is reached on the ray tangent to the lower surface: at horizontal distance
//    sqrt(2R(h+D)) + sqrt(4RD) (tangent point, then up to the upper surface). For a given azimuth the
//    nearest and farthest points over the rays in view therefore lie on the frustum's side faces, on the
//    nadir ray, or on that farthest rim. Those three sets are traced: the 4 side faces as fans of rays (the
//    4 frustum edges among them: Johanson's edge intersections), the nadir when it is in view, and the rim
//    arc where it is in view (exactly, then sampled on a circumscribed polygon).
//  - The flat sea (R = 0) reaches eye level only at infinity; it is cut at the distance where it lies
//    FLAT_HORIZON_GAP below eye level, and the cut is the rim.
// The curved horizon is thus handled by extending the grid's far edge to the farthest rim: the grid covers
// every base-plane point whose dropped (and displaced) sea can be seen. Lowering Johanson's lower plane by
// curvatureDrop(horizon distance) instead would also cover it, but a plane 15 km lower (from 15 km
// altitude) swells the footprint looking straight down twofold, and it still needs a far limit.
#include "ocean/ProjectedGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace pacifica::ocean {
namespace {

constexpr double PI = std::numbers::pi;
constexpr double INF = std::numeric_limits<double>::infinity();
/// Rays traced per frustum side face (the face's two edges included).
constexpr int FACE_RAYS = 64;
/// Ratio of successive offsets of the rays clustered about a tangent elevation (see boundaryRays()).
constexpr double CLUSTER_RATIO = 0.7;
/// Largest azimuth step of the rim polygon (1 degree: its circumscribed radius is 1.00004 times the rim's).
constexpr double RIM_STEP = PI / 180.0;
/// Every point the grid must cover lies within this angle of the projector's axis where possible, so the
/// range stays bounded (tan 85 deg = 11.4).
constexpr double MAX_PROJECTOR_ANGLE = 85.0 * PI / 180.0;
/// Successive distances from v = 1 of the rows that subdivide the grid's last cell (see the constructor).
constexpr double HORIZON_ROW_RATIO = 0.75;
/// Aiming a raised projector: the share of the way from the steepest allowed pitch to the camera's.
constexpr double LOW_AIM_BLEND = 0.5;

void require(bool ok, const std::string& message) {
    if (!ok)
        throw std::invalid_argument(message);
}

/// {t >= 0 : a t^2 + b t + c <= 0} for a >= 0 as [lo, hi] (hi may be infinite); lo > hi when empty.
struct Interval {
    double lo = INF, hi = -INF;
    bool empty() const { return !(lo <= hi); }
};

Interval nonPositive(double a, double b, double c) {
    Interval r;
    if (a > 0.0) {
        const double disc = b * b - 4.0 * a * c;
        if (disc < 0.0)
            return r;
        // Numerically stable roots (no cancellation between -b and sqrt(disc)).
        const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        double r1 = q / a, r2 = q != 0.0 ? c / q : r1;
        if (r1 > r2)
            std::swap(r1, r2);
        if (r2 < 0.0)
            return r;
        r.lo = std::max(r1, 0.0);
        r.hi = r2;
        return r;
    }
    if (b < 0.0) {
        r.lo = std::max(-c / b, 0.0);
        r.hi = INF;
    } else if (b > 0.0) {
        if (-c / b >= 0.0) {
            r.lo = 0.0;
            r.hi = -c / b;
        }
    } else if (c <= 0.0) {
        r.lo = 0.0;
        r.hi = INF;
    }
    return r;
}

/// The displaceable volume seen from the camera (camera-relative, the camera at the origin).
struct Volume {
    double h = 0.0;            ///< camera height above the base plane
    double maxD = 0.0;         ///< bound surfaces at +-maxD about the (dropped) base
    double invTwoR = 0.0;      ///< 1 / 2R, 0 when flat
    double cap = INF;          ///< flat sea: largest horizontal distance; INF when curved
    double zNear = 0.1;        ///< nothing nearer than the near plane is drawn
    double rimRadius = 0;      ///< farthest horizontal distance of a visible point of V
    double rimElevation = 0;   ///< elevation (radians) of the ray that reaches rimRadius
    double grazeElevation = 0; ///< elevation of the ray tangent to the upper bound surface (0 if none)

    /// The visible part of ray t * dir inside V, t in depth units (dir's component along the view axis is
    /// 1); empty when the ray misses V.
    Interval segment(const glm::dvec3& dir) const {
        const double rho2 = dir.x * dir.x + dir.y * dir.y;
        const double a = rho2 * invTwoR;
        // Ray z = t dir.z; bound surfaces z = -h +- maxD - a t^2 (with a = rho^2 / 2R).
        const Interval inside = nonPositive(a, dir.z, h - maxD); // at or below the upper surface
        if (inside.empty())
            return {};
        const Interval below = nonPositive(a, dir.z, h + maxD); // at or below the lower surface
        double end = std::min(inside.hi, below.empty() ? INF : below.lo);
        if (cap < INF && rho2 > 0.0)
            end = std::min(end, cap / std::sqrt(rho2));
        Interval s;
        s.lo = std::max(inside.lo, zNear);
        s.hi = end;
        if (s.hi == INF) // unreachable for a valid volume (the cap or the drop bound every ray); be safe
            s.hi = -INF;
        return s;
    }
};

/// The camera's axes in world (camera-relative) coordinates and its tangent half-extents.
struct CameraAxes {
    glm::dvec3 right, up, forward;
    double tanX, tanY; ///< tan of the half field of view, horizontally and vertically
    glm::dvec3 ray(double x, double y) const { return forward + x * right + y * up; }
};

CameraAxes cameraAxes(const CameraFrame& camera) {
    // view = transpose of (right, up, -forward) (Space.h viewRotation): its rows are the eye axes.
    const glm::dmat3 eyeToWorld = glm::transpose(glm::dmat3(glm::dmat4(camera.view)));
    CameraAxes c;
    c.forward = -glm::normalize(eyeToWorld[2]);
    c.right = glm::normalize(eyeToWorld[0] - c.forward * glm::dot(c.forward, eyeToWorld[0]));
    c.up = glm::cross(c.right, c.forward);
    c.tanX = 1.0 / double(camera.proj[0][0]);
    c.tanY = 1.0 / double(camera.proj[1][1]);
    return c;
}

/// Rays worth tracing on the boundary of the screen rectangle |x| <= X, |y| <= Y (tangent units): for each
/// side, raysPerFace evenly spaced (corners included) plus the ray of extreme elevation. Along a straight
/// edge d(s) = A + s B, sin(elevation) = (A.z + s B.z) / |A + s B| has a single stationary point,
/// s* = (a Bq - b Aq) / (b Bq - a Cq) with a = A.z, b = B.z, Aq = A.A, Bq = A.B, Cq = B.B.
void boundaryRays(const CameraAxes& c, double X, double Y, int raysPerFace,
                  std::initializer_list<double> clusterElevations, std::vector<glm::dvec3>& out) {
    const glm::dvec2 corner[4] = {{-X, -Y}, {X, -Y}, {X, Y}, {-X, Y}};
    for (int e = 0; e < 4; ++e) {
        const glm::dvec3 A = c.ray(corner[e].x, corner[e].y);
        const glm::dvec3 B = c.ray(corner[(e + 1) % 4].x, corner[(e + 1) % 4].y) - A;
        for (int i = 0; i < raysPerFace; ++i) // the next side adds s = 1
            out.push_back(A + (double(i) / raysPerFace) * B);
        const double a = A.z, b = B.z, Aq = glm::dot(A, A), Bq = glm::dot(A, B), Cq = glm::dot(B, B);
        const double den = b * Bq - a * Cq;
        if (den != 0.0) {
            const double s = (a * Bq - b * Aq) / den;
            if (s > 0.0 && s < 1.0)
                out.push_back(A + s * B);
        }
        // Where the edge crosses a tangent elevation (grazing the upper or the lower bound surface), the
        // segment ends move like the square root of the elevation difference, so even 64 rays leave chords
        // that cut inside the true boundary. Cluster rays geometrically on both sides of each crossing:
        // (a + s b)^2 = sin^2(e) |A + s B|^2 with a + s b of the sign of sin(e).
        for (double elevation : clusterElevations) {
            const double k = std::sin(elevation) * std::sin(elevation);
            const double qa = b * b - k * Cq, qb = 2.0 * (a * b - k * Bq), qc = a * a - k * Aq;
            double roots[2];
            int n = 0;
            if (qa != 0.0) {
                const double disc = qb * qb - 4.0 * qa * qc;
                if (disc >= 0.0) {
                    roots[n++] = (-qb - std::sqrt(disc)) / (2.0 * qa);
                    roots[n++] = (-qb + std::sqrt(disc)) / (2.0 * qa);
                }
            } else if (qb != 0.0) {
                roots[n++] = -qc / qb;
            }
            for (int i = 0; i < n; ++i) {
                const double s = roots[i];
                if (!(s >= 0.0 && s <= 1.0) || (a + s * b) * std::sin(elevation) < 0.0)
                    continue;
                out.push_back(A + s * B);
                for (double step = 1.0 / FACE_RAYS; step > 1e-12; step *= CLUSTER_RATIO)
                    for (double t : {s - step, s + step})
                        if (t > 0.0 && t < 1.0)
                            out.push_back(A + t * B);
            }
        }
    }
}

/// The nadir ray in tangent units, if it lies within |x| <= X, |y| <= Y.
bool nadirInView(const CameraAxes& c, double X, double Y, glm::dvec3& ray) {
    const double depth = -c.forward.z; // (0, 0, -1) . forward
    if (!(depth > 0.0))
        return false;
    const double x = -c.right.z / depth, y = -c.up.z / depth;
    if (std::abs(x) > X || std::abs(y) > Y)
        return false;
    ray = c.ray(x, y);
    return true;
}

/// Azimuth arcs on which the direction of elevation `elevation` lies inside the pyramid |x| <= X, |y| <= Y,
/// as (start, length) pairs. Each side plane n . d >= 0 is A cos(phi) + B sin(phi) + C >= 0: an arc.
std::vector<glm::dvec2> arcsInView(const CameraAxes& c, double X, double Y, double elevation) {
    const glm::dvec3 normals[4] = {c.right + X * c.forward, -c.right + X * c.forward, c.up + Y * c.forward,
                                   -c.up + Y * c.forward};
    const double ce = std::cos(elevation), se = std::sin(elevation);
    std::vector<double> cuts;
    double A[4], B[4], C[4];
    for (int i = 0; i < 4; ++i) {
        A[i] = ce * normals[i].x;
        B[i] = ce * normals[i].y;
        C[i] = se * normals[i].z;
        const double m = std::hypot(A[i], B[i]);
        if (C[i] <= -m)
            return {}; // this side excludes the whole circle
        if (C[i] < m) {
            const double centre = std::atan2(B[i], A[i]), half = std::acos(-C[i] / m);
            cuts.push_back(centre - half);
            cuts.push_back(centre + half);
        }
    }
    auto inside = [&](double phi) {
        for (int i = 0; i < 4; ++i)
            if (A[i] * std::cos(phi) + B[i] * std::sin(phi) + C[i] < 0.0)
                return false;
        return true;
    };
    std::vector<glm::dvec2> arcs;
    if (cuts.empty()) {
        arcs.emplace_back(0.0, 2.0 * PI);
        return arcs;
    }
    for (double& a : cuts)
        a = std::fmod(std::fmod(a, 2.0 * PI) + 2.0 * PI, 2.0 * PI);
    std::sort(cuts.begin(), cuts.end());
    for (size_t i = 0; i < cuts.size(); ++i) {
        const double a = cuts[i];
        const double b = i + 1 < cuts.size() ? cuts[i + 1] : cuts[0] + 2.0 * PI;
        if (b - a > 0.0 && inside(0.5 * (a + b)))
            arcs.emplace_back(a, b - a);
    }
    return arcs;
}

Volume makeVolume(double h, double maxD, double R, double zNear) {
    Volume vol;
    vol.h = h;
    vol.maxD = maxD;
    vol.zNear = zNear;
    if (R > 0.0) {
        vol.invTwoR = 0.5 / R;
        // Tangent to the lower surface (camera h + D above it), then on to the upper surface (2D above it).
        vol.rimRadius = std::sqrt(2.0 * R * (h + maxD)) + std::sqrt(4.0 * R * maxD);
        vol.rimElevation = -std::atan(std::sqrt(2.0 * (h + maxD) / R));
        vol.grazeElevation = -std::atan(std::sqrt(std::max(0.0, 2.0 * (h - maxD) / R)));
    } else {
        vol.cap = std::max(h, 1.0) / std::tan(ProjectedGrid::FLAT_HORIZON_GAP);
        vol.rimRadius = vol.cap;
        vol.rimElevation = -std::atan(h / vol.cap); // sees the base plane at the cap
        vol.grazeElevation = -std::atan(std::max(0.0, h - maxD) / vol.cap);
    }
    return vol;
}

/// The base-plane points that bound what must be covered for the pyramid |x| <= X, |y| <= Y: the vertical
/// projections of the ends of V's segments on the rays of the side faces (clustered about the tangent
/// elevations) and of the nadir ray, and the rim arcs in view (circumscribed polygon).
std::vector<glm::dvec2> coverPoints(const CameraAxes& cam, const Volume& vol, double X, double Y) {
    std::vector<glm::dvec3> rays;
    boundaryRays(cam, X, Y, FACE_RAYS, {vol.rimElevation, vol.grazeElevation}, rays);
    glm::dvec3 nadir;
    if (nadirInView(cam, X, Y, nadir))
        rays.push_back(nadir);
    std::vector<glm::dvec2> points;
    for (const glm::dvec3& r : rays) {
        const Interval s = vol.segment(r);
        if (s.empty())
            continue;
        points.emplace_back(s.lo * r.x, s.lo * r.y);
        points.emplace_back(s.hi * r.x, s.hi * r.y);
    }
    for (const glm::dvec2& arc : arcsInView(cam, X, Y, vol.rimElevation)) {
        const int n = std::max(1, int(std::ceil(arc.y / RIM_STEP)));
        const double step = arc.y / n, radius = vol.rimRadius / std::cos(0.5 * step); // circumscribed
        for (int i = 0; i <= n; ++i) {
            const double phi = arc.x + i * step;
            points.emplace_back(radius * std::cos(phi), radius * std::sin(phi));
        }
    }
    return points;
}

} // namespace

ProjectedGrid::ProjectedGrid(const ProjectedGridDesc& desc) : mDesc(desc) {
    require(desc.resolutionX >= 2 && desc.resolutionX <= 8192,
            "ProjectedGridDesc.resolutionX must be in [2, 8192], got " + std::to_string(desc.resolutionX));
    require(desc.resolutionY >= 2 && desc.resolutionY <= 8192,
            "ProjectedGridDesc.resolutionY must be in [2, 8192], got " + std::to_string(desc.resolutionY));
    require(std::isfinite(desc.maxDisplacement) && desc.maxDisplacement >= 0.0 && desc.maxDisplacement <= 1e4,
            "ProjectedGridDesc.maxDisplacement must be in [0, 1e4] metres, got " +
                std::to_string(desc.maxDisplacement));
    require(std::isfinite(desc.guardBand) && desc.guardBand >= 0.0 && desc.guardBand <= 1.0,
            "ProjectedGridDesc.guardBand must be in [0, 1] (NDC units), got " +
                std::to_string(desc.guardBand));

    const int nx = desc.resolutionX, ny = desc.resolutionY;
    // Rows: evenly spaced in v (the projector's image), except that the last cell is subdivided towards
    // v = 1 at HORIZON_ROW_RATIO: there the far edge lies at the farthest rim of V, which can be 10 times
    // the distance of the row before (the waves' rim lies sqrt(4 R D) beyond the horizon), and the drawn
    // horizon is the highest vertex of each column (triangles are flat), so a coarse last cell would draw
    // the horizon up to 1e-3 rad (a 1080p pixel) too low. With rows 1 / 0.75 apart in distance there it
    // stays within ~1e-4 rad.
    std::vector<double> rows;
    for (int j = 0; j + 1 < ny; ++j)
        rows.push_back(double(j) / (ny - 1));
    for (int k = 1; k <= HORIZON_ROWS; ++k)
        rows.push_back(1.0 - std::pow(HORIZON_ROW_RATIO, k) / (ny - 1));
    rows.push_back(1.0);
    const int rowCount = int(rows.size());
    mVertices.reserve(size_t(2) * nx * rowCount);
    for (double v : rows)
        for (int i = 0; i < nx; ++i) {
            mVertices.push_back(static_cast<float>(double(i) / (nx - 1)));
            mVertices.push_back(static_cast<float>(v));
        }
    mIndices.reserve(size_t(6) * (nx - 1) * (rowCount - 1));
    for (int j = 0; j + 1 < rowCount; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            const uint32_t a = uint32_t(j * nx + i), b = a + 1, c = a + uint32_t(nx), d = c + 1;
            mIndices.insert(mIndices.end(), {a, b, d, a, d, c}); // counter-clockwise in (u, v)
        }
}

glm::dvec2 ProjectedGrid::Frame::gridPoint(glm::dvec2 uv) const {
    const glm::dvec4 p =
        glm::mix(glm::mix(corners[0], corners[1], uv.x), glm::mix(corners[2], corners[3], uv.x), uv.y);
    return glm::dvec2(p) / p.w;
}

std::array<glm::vec4, 4> ProjectedGrid::Frame::cornerUniforms() const {
    double largest = 0.0;
    for (const glm::dvec4& c : corners)
        for (int k = 0; k < 4; ++k)
            largest = std::max(largest, std::abs(c[k]));
    const double s = largest > 0.0 ? 1.0 / largest : 1.0;
    std::array<glm::vec4, 4> out;
    for (int i = 0; i < 4; ++i)
        out[i] = glm::vec4(corners[i] * s);
    return out;
}

namespace {

void requireCamera(const CameraFrame& camera, double curvatureRadius) {
    const double p00 = camera.proj[0][0], p11 = camera.proj[1][1];
    require(
        std::isfinite(p00) && std::isfinite(p11) && p00 > 0.0 && p11 > 0.0 && camera.proj[2][3] == -1.0f,
        "ProjectedGrid::frame(): camera.proj must be a perspective projection (Space.h), got proj[0][0] " +
            std::to_string(p00) + ", proj[1][1] " + std::to_string(p11));
    require(std::isfinite(camera.origin.z),
            "ProjectedGrid::frame(): camera.origin.z must be finite, got " + std::to_string(camera.origin.z));
    require(std::isfinite(curvatureRadius) && curvatureRadius >= 0.0,
            "ProjectedGrid::frame(): curvatureRadius must be finite and >= 0 (0 = flat), got " +
                std::to_string(curvatureRadius));
    require(std::isfinite(camera.zNear) && camera.zNear > 0.0,
            "ProjectedGrid::frame(): camera.zNear must be > 0, got " + std::to_string(camera.zNear));
}

/// Visible: a ray of the screen (no guard band) meets V. Seen from above V that depends only on the ray's
/// elevation, lowest at a corner, at an edge's stationary point or at the nadir, all among these rays.
bool screenMeetsVolume(const CameraAxes& cam, const Volume& vol) {
    std::vector<glm::dvec3> rays;
    boundaryRays(cam, cam.tanX, cam.tanY, FACE_RAYS, {}, rays);
    glm::dvec3 nadir;
    if (nadirInView(cam, cam.tanX, cam.tanY, nadir))
        rays.push_back(nadir);
    rays.push_back(cam.forward);
    return std::any_of(rays.begin(), rays.end(),
                       [&](const glm::dvec3& r) { return !vol.segment(r).empty(); });
}

/// Zero roll, heading along the camera's forward; within 3 degrees of vertical, blend towards the screen's
/// up direction so looking straight down still has a heading (and it turns smoothly).
glm::dvec2 projectorHeading(const CameraAxes& cam) {
    glm::dvec2 heading(cam.forward.x, cam.forward.y);
    const double flatness = glm::length(heading);
    if (flatness < 0.05) {
        const double blend = 1.0 - flatness / 0.05;
        const glm::dvec2 screenUp = glm::dvec2(cam.up.x, cam.up.y) * (cam.forward.z < 0.0 ? 1.0 : -1.0);
        heading += blend * screenUp;
    }
    return glm::length(heading) > 1e-12 ? glm::normalize(heading) : glm::dvec2(0.0, 1.0);
}

/// The pitches [lo, hi] that keep every point within MAX_PROJECTOR_ANGLE of the projector's axis. A point at
/// (along, across, -H) from the projector has dot = M cos(p - theta) with M = |(along, H)|, theta =
/// atan2(-H, along); within the angle asks cos(p - theta) >= cos(MAX) L / M, L its full distance. Looking
/// straight down (p = -90 deg) every point is in front, so when the bound cannot hold for all, settle for
/// "in front" (cos(p - theta) > 0).
void pitchRange(const std::vector<glm::dvec2>& points, const glm::dvec2& heading, const glm::dvec2& side,
                double H, double& lo, double& hi) {
    auto pitchWithin = [&](double cosBound) {
        lo = -0.5 * PI;
        hi = 0.5 * PI - 1e-6;
        for (const glm::dvec2& q : points) {
            const double along = glm::dot(q, heading), across = glm::dot(q, side);
            const double m = std::hypot(along, H), l = std::hypot(m, across);
            const double c = cosBound * l / m;
            if (c >= 1.0)
                return false;
            const double theta = std::atan2(-H, along), half = std::acos(c);
            lo = std::max(lo, theta - half);
            hi = std::min(hi, theta + half);
        }
        return lo <= hi;
    };
    if (!pitchWithin(std::cos(MAX_PROJECTOR_ANGLE))) {
        pitchWithin(0.0); // contains -90 degrees: theta lies in (-180, 0) for every point
        const double margin = std::min(1e-3, 0.25 * (hi - lo));
        lo += margin;
        hi -= margin;
    }
}

/// Aim. When the projector is the camera (h well above the bound surface) its pitch is the camera's: the
/// range is then the screen's view of the sea, Johanson's ideal, with the vertices spread evenly over the
/// screen. From inside or just above the wave volume the projector had to be raised by H / h, and the water
/// under the bound surfaces down to the camera's feet must be covered as well as the horizon. Looking level,
/// the camera's pitch then gives most rows to that near water (7% of the vertices land on the screen from
/// 2 m), while the steepest pitch that keeps the rim in bounds (lo) crowds them at the horizon, which the
/// raised projector sees H / h times larger than the camera does (0.05 rows per pixel at the bottom of a
/// 1080p screen, 20 at the horizon, from 0.5 m). Half-way (in angle) spreads them fairly evenly (from 2 m:
/// 0.3 to 0.9 rows per pixel, 35% on the screen). The blend into the camera's pitch between 1 and 3 times
/// the raising threshold (the bound surface plus the clearance) keeps the grid continuous with altitude.
double aimPitch(const CameraAxes& cam, double h, double threshold, double lo, double hi) {
    const double cameraPitch = std::asin(std::clamp(cam.forward.z, -1.0, 1.0));
    const double s = std::clamp((h - threshold) / (2.0 * threshold), 0.0, 1.0);
    const double cameraWeight = s * s * (3.0 - 2.0 * s); // smoothstep
    const double lowPitch = glm::mix(lo, std::clamp(cameraPitch, lo, hi), LOW_AIM_BLEND);
    return std::clamp(glm::mix(lowPitch, cameraPitch, cameraWeight), lo, hi);
}

/// The range: the points' bounding box in the projector's image (tangent units), never degenerate (all
/// points on one line would leave the homography without an inverse).
glm::dvec4 imageRange(const std::vector<glm::dvec2>& points, double h, const glm::dvec3& position,
                      const glm::dvec3& fwd, const glm::dvec3& right, const glm::dvec3& up) {
    glm::dvec4 range(INF, -INF, INF, -INF);
    for (const glm::dvec2& q : points) {
        const glm::dvec3 v = glm::dvec3(q, -h) - position;
        const double w = glm::dot(v, fwd);
        const double x = glm::dot(v, right) / w, y = glm::dot(v, up) / w;
        range = glm::dvec4(std::min(range.x, x), std::max(range.y, x), std::min(range.z, y),
                           std::max(range.w, y));
    }
    const double minExtent = 1e-9 * (1.0 + std::abs(range.x) + std::abs(range.y) + std::abs(range.z));
    if (range.y - range.x < minExtent) {
        range.x -= minExtent;
        range.y += minExtent;
    }
    if (range.w - range.z < minExtent)
        range.z -= minExtent; // downwards: the top stays below the projector's horizon
    return range;
}

} // namespace

ProjectedGrid::Frame ProjectedGrid::frame(const CameraFrame& camera, double curvatureRadius) const {
    requireCamera(camera, curvatureRadius);
    Frame out;
    const CameraAxes cam = cameraAxes(camera);
    const double h = camera.origin.z;
    if (!(h + mDesc.maxDisplacement > 0.0))
        return out; // the camera is below every trough: no sea surface seen from above
    const Volume vol = makeVolume(h, mDesc.maxDisplacement, curvatureRadius, camera.zNear);
    if (!screenMeetsVolume(cam, vol))
        return out;
    // The base-plane points to cover: V's, traced with the guard band.
    const double X = cam.tanX * (1.0 + mDesc.guardBand), Y = cam.tanY * (1.0 + mDesc.guardBand);
    const std::vector<glm::dvec2> points = coverPoints(cam, vol, X, Y);
    if (points.empty())
        return out; // V is only in the screen's rays nearer than the near plane
    out.visible = true;
    out.farDistance = vol.rimRadius;

    // The projector (Johanson §2.4.1): above the camera, at least a margin above the upper bound surface.
    const double clearance = 0.1 * vol.maxD + 0.1;
    const double H = std::max(h, vol.maxD + clearance); // projector height above the base plane
    out.projectorPosition = glm::dvec3(0.0, 0.0, H - h);
    const glm::dvec2 heading = projectorHeading(cam);
    const glm::dvec2 side(heading.y, -heading.x); // heading x up = right
    const glm::dvec3 right(side, 0.0);
    double lo, hi;
    pitchRange(points, heading, side, H, lo, hi);
    const double pitch = aimPitch(cam, h, vol.maxD + clearance, lo, hi);
    const glm::dvec3 fwd(heading * std::cos(pitch), std::sin(pitch));
    const glm::dvec3 up(-heading * std::sin(pitch), std::cos(pitch));
    out.projectorForward = fwd;
    out.range = imageRange(points, h, out.projectorPosition, fwd, right, up);

    // Corners: the base-plane point hit by the projector ray through (x, y) is P + (H / -dir.z) dir; times
    // w = -dir.z it is the homogeneous (H dir.xy, -h w, w) (P.xy = 0), linear in (x, y) and so in (u, v).
    const glm::dvec4& range = out.range;
    const glm::dvec2 cornerXY[4] = {
        {range.x, range.z}, {range.y, range.z}, {range.x, range.w}, {range.y, range.w}};
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 dir = fwd + cornerXY[i].x * right + cornerXY[i].y * up;
        const double w = -dir.z;
        out.corners[i] = glm::dvec4(H * dir.x, H * dir.y, -h * w, w);
    }
    return out;
}

} // namespace pacifica::ocean
