// ObjectRenderer: draws aircraft, ships and weapons (a recording's in replay, the game's own in the game) as
// simple procedural meshes into the frame the ocean was rendered to, depth-tested against the sea (a ship's
// hull below the waterline is hidden), so a chase or orbit replay shows what it follows. Lit by the ocean's
// sun with a sky ambient; flat-shaded from screen-space derivatives. It saves and restores the GL state it
// touches (gl::StateGuard), like the ocean.
#pragma once

#include "engine/Pose.h"
#include "engine/Space.h"
#include "engine/gl/GlObjects.h"

#include <glm/glm.hpp>

#include <vector>

namespace pacifica::gl {

/// Plume: a splash column standing on its origin, `length` tall, widening to a crown (a game's impacts).
enum class ObjectShape { Aircraft, Rotorcraft, Ship, Carrier, Weapon, Plume };
inline constexpr int OBJECT_SHAPES = 6;

struct DrawnObject {
    ObjectShape shape = ObjectShape::Aircraft;
    double length = 19.0;    ///< metres, nose to tail / bow to stern
    Pose pose;               ///< world pose (heading, pitch, roll: engine/Pose.h)
    glm::vec3 albedo{-1.0f}; ///< scene-linear colour; negative = the shape's default grey
};

class ObjectRenderer {
public:
    ObjectRenderer();
    /// Draws into framebuffer fbo (colour + the ocean's depth, reverse-Z) of size w x h. Positions are made
    /// camera-relative in double and dropped by the ocean's Earth-curvature term (earthRadius; 0 = flat), as
    /// the sea is. `lightScale` scales the light (sun and sky ambient): the scene's sun intensity over the
    /// default one, so objects follow a dimmer sun, a moonlit night and a pre-exposure as the sea does.
    /// Returns the number of objects drawn (in front of the camera).
    int draw(const std::vector<DrawnObject>& objects, const CameraFrame& camera, unsigned fbo, int w, int h,
             const glm::dvec3& sunDirection, double earthRadius, double lightScale = 1.0);

private:
    struct Range {
        int first = 0, count = 0;
    };
    Program mProgram;
    VertexArray mVao;
    Buffer mVertices;
    Range mRanges[OBJECT_SHAPES];
};

} // namespace pacifica::gl
