// ProjectedGrid: the projected grid of Johanson 2004 ("Real-time water rendering - introducing the projected
// grid concept", §2.3-2.4), an alternative to the radial grid (RadialGrid.h), in plain C++ (no GL).
//
// A regular (u, v) grid is laid over the screen-facing image of a *projector* and mapped onto the sea's base
// plane z = 0 (camera-relative: z = -cameraHeight), so its vertices are spread evenly over the sea the camera
// sees, out to the horizon, at any altitude and attitude. The vertex shader (ocean_projected.vert) then
// drops each vertex by the Earth-curvature sagitta and displaces it with the surface model, exactly as the
// radial grid's ocean.vert does.
//
// STEP BY STEP (the renderer)
//   1. Once:   ProjectedGrid grid({});  upload grid.vertices() (2 floats per vertex: u, v) and
//              grid.indices() (GL_TRIANGLES, uint32); VAO attribute 0 = vec2 aUV.
//   2. Frame:  ProjectedGrid::Frame f = grid.frame(camera, earthCurvature ? EARTH_RADIUS : 0.0);
//              if (!f.visible) skip the sea's draw (no part of the displaceable volume is in view).
//   3. Frame:  set uniform vec4 uCorners[4] = f.cornerUniforms() plus ocean.vert's uniforms (uViewProj,
//              uCameraHeight, uDisplaceRadius, uCurvature, uCull) and the surface model's; draw the elements.
//
// Everything is camera-relative and computed in double: only the camera's height enters the grid, so a
// camera 10^7 m from the origin gets the same grid as one above it. The algorithm (Johanson §2.4.1, adapted
// to an infinite reverse-Z frustum and a curved sea; details in ProjectedGrid.cpp):
//   a. The displaceable volume V is the sea between the bound surfaces z = +-maxDisplacement, each dropped
//      by d^2 / 2R with horizontal distance d (flat planes when R = 0), and truncated where it can no longer
//      be seen: behind the horizon (curved) or, flat, where it lies less than 1e-5 rad below eye level.
//   b. The frustum (enlarged by the guard band) is traced against V along its four side faces (a fan of
//      rays per face, including Johanson's 4 frustum edges), plus the nadir ray when it is in view, plus
//      the farthest rim of V (the horizon arc) where it is in view; each ray contributes the ends of its
//      segment inside V, projected vertically onto the base plane. These points bound the base-plane region
//      whose sea can be seen.
//   c. The projector is the camera, raised above the upper bound surface when it is inside or near V, with
//      zero roll, pitched as the camera (Johanson's ideal: the range is then the screen) or, when raised,
//      aimed lower at the base plane (§2.4.1's "aim point", which also keeps it from looking along the
//      plane); always so that every point of b lies within 85 degrees of its axis.
//   d. The bounding box of the points in the projector's image (the range, §2.4.1) gives the 4 grid
//      corners as homogeneous base-plane points; the grid interpolates them bilinearly and divides by w,
//      which is exact for the projector's perspective (§2.4.2).
#pragma once

#include "engine/Space.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace pacifica::ocean {

struct ProjectedGridDesc {
    int resolutionX = 256; ///< vertices across the grid (u), >= 2
    /// Rows along the grid (v, from the near edge to the horizon), >= 2, evenly spaced in v; the mesh adds
    /// HORIZON_ROWS more that subdivide the last cell towards the horizon.
    int resolutionY = 512;
    /// Bound of the surface model's vertical displacement, metres: the upper and lower bound surfaces of the
    /// displaceable volume (Johanson's S_upper / S_lower) are +-maxDisplacement about the mean sea.
    double maxDisplacement = 3.0;
    /// Extra margin around the screen, in NDC units (the screen spans [-1, 1]), so vertices displaced
    /// sideways at the screen edges do not open gaps there.
    double guardBand = 0.05;
};

class ProjectedGrid {
public:
    /// Throws std::invalid_argument naming the bad field, e.g.
    /// "ProjectedGridDesc.resolutionX must be in [2, 8192], got 1".
    explicit ProjectedGrid(const ProjectedGridDesc& desc);

    /// One frame's projector, from the camera's pose and projection.
    struct Frame {
        /// False when no part of the displaceable volume V is in view (then nothing else is set and the
        /// sea need not be drawn). With maxDisplacement > 0 a camera inside V (altitude < maxDisplacement)
        /// always sees part of V, even looking straight up: a wave crest could rise into view.
        bool visible = false;
        /// The grid's corners as homogeneous camera-relative points (x, y, z, w) of the base plane
        /// z = -cameraHeight (so z = -cameraHeight * w): bottom-left (u, v) = (0, 0), bottom-right (1, 0),
        /// top-left (0, 1), top-right (1, 1); v = 0 is the near edge, v = 1 the far edge at the horizon.
        /// The grid point at (u, v) is the bilinear blend of the four, divided by its w (perspective-correct,
        /// Johanson §2.4.2: the blend is affine in (u, v) because corners[3] = corners[1] + corners[2] -
        /// corners[0]). Every w is > 0.
        glm::dvec4 corners[4]{};
        glm::dvec3 projectorPosition{0.0};           ///< camera-relative; directly above the camera
        glm::dvec3 projectorForward{0.0, 0.0, -1.0}; ///< unit; zero roll: its right vector is horizontal
        /// The range (Johanson §2.4.1): the box the grid spans in the projector's image plane, in tangent
        /// units (x = right / forward, y = up / forward): xMin, xMax, yMin, yMax.
        glm::dvec4 range{0.0};
        /// The farthest horizontal distance from the camera at which V can be seen (the grid reaches at
        /// least this far wherever the horizon is in view): past the curved horizon, or the flat sea's cap.
        double farDistance = 0.0;

        /// The camera-relative base-plane point (x, y) of grid coordinate uv (the shader's mapping, in
        /// double). Only meaningful when visible.
        glm::dvec2 gridPoint(glm::dvec2 uv) const;
        /// The corners for `uniform vec4 uCorners[4]`, scaled together so the largest component is 1 (any
        /// common positive scale gives the same grid).
        std::array<glm::vec4, 4> cornerUniforms() const;
    };

    /// The projector for this camera. curvatureRadius: 0 for a flat sea; else the sea drops by d^2 / 2R
    /// with horizontal distance d (OceanConstants.h curvatureDrop, the same drop ocean_projected.vert
    /// applies), which moves the horizon down and nearer; the grid still reaches it. Pass the radius the
    /// shader's uCurvature = 1 / 2R uses. Throws std::invalid_argument if the camera's projection is not a
    /// finite perspective one (Space.h), its height is not finite, its zNear is not > 0, or curvatureRadius
    /// is negative or not finite. Costs 30-150 microseconds (a few thousand rays traced in double).
    Frame frame(const CameraFrame& camera, double curvatureRadius) const;

    const ProjectedGridDesc& desc() const { return mDesc; }
    /// 2 floats per vertex: (u, v) in [0, 1]^2, row-major from v = 0 (resolutionX vertices per row);
    /// resolutionY + HORIZON_ROWS rows.
    const std::vector<float>& vertices() const { return mVertices; }
    /// Triangle list (uint32), counter-clockwise in (u, v), which is counter-clockwise seen from above.
    const std::vector<uint32_t>& indices() const { return mIndices; }
    size_t vertexCount() const { return mVertices.size() / 2; }

    /// Rows added between the last two evenly spaced rows, their distances from v = 1 shrinking by 0.75 each:
    /// the drawn horizon is the highest vertex of each column, and near the horizon the even rows are far
    /// apart on the sea (ProjectedGrid.cpp).
    static constexpr int HORIZON_ROWS = 16;

    /// Below the flat sea (curvatureRadius = 0), the grid stops where the sea lies this far below eye level
    /// (radians): 1/7 of a pixel of an 8K display with a 30 degree field of view.
    static constexpr double FLAT_HORIZON_GAP = 1e-5;

private:
    ProjectedGridDesc mDesc;
    std::vector<float> mVertices;
    std::vector<uint32_t> mIndices;
};

} // namespace pacifica::ocean
