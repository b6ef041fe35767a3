// ObjectRenderer: procedural meshes in body units (x forward, y right, z up; length 1), one draw per object.
#include "engine/gl/ObjectRenderer.h"

#include "engine/gl/Shader.h"

#include <epoxy/gl.h>

#include <array>
#include <cmath>

namespace pacifica::gl {

namespace {

using Tri = std::vector<glm::vec3>;

void quad(Tri& t, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    t.insert(t.end(), {a, b, c, a, c, d});
}

void box(Tri& t, glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    quad(t, p[0], p[1], p[2], p[3]);
    quad(t, p[4], p[5], p[6], p[7]);
    quad(t, p[0], p[1], p[5], p[4]);
    quad(t, p[1], p[2], p[6], p[5]);
    quad(t, p[2], p[3], p[7], p[6]);
    quad(t, p[3], p[0], p[4], p[7]);
}

/// A closed body along x through cross-sections (x, half-width, bottom z, top z): a diamond per station.
void lofted(Tri& t, const std::vector<glm::vec4>& st) {
    auto ring = [](const glm::vec4& s) {
        const float mid = 0.5f * (s.z + s.w);
        return std::array<glm::vec3, 4>{glm::vec3(s.x, 0, s.w), glm::vec3(s.x, s.y, mid),
                                        glm::vec3(s.x, 0, s.z), glm::vec3(s.x, -s.y, mid)};
    };
    for (size_t i = 0; i + 1 < st.size(); ++i) {
        const auto a = ring(st[i]), b = ring(st[i + 1]);
        for (int k = 0; k < 4; ++k)
            quad(t, a[k], a[(k + 1) % 4], b[(k + 1) % 4], b[k]);
    }
}

Tri aircraft() {
    Tri t;
    lofted(t, {{0.5f, 0.0f, 0.0f, 0.0f},
               {0.35f, 0.035f, -0.03f, 0.04f},
               {0.05f, 0.06f, -0.04f, 0.05f},
               {-0.35f, 0.05f, -0.03f, 0.04f},
               {-0.5f, 0.02f, -0.01f, 0.02f}});
    // Swept wings, tailplanes and the fin: thin plates (two sided in the shader).
    t.insert(t.end(), {{0.12f, 0.0f, 0.0f}, {-0.22f, 0.42f, -0.01f}, {-0.28f, 0.0f, 0.0f}});
    t.insert(t.end(), {{0.12f, 0.0f, 0.0f}, {-0.22f, -0.42f, -0.01f}, {-0.28f, 0.0f, 0.0f}});
    t.insert(t.end(), {{-0.33f, 0.0f, 0.0f}, {-0.5f, 0.18f, 0.0f}, {-0.5f, 0.0f, 0.0f}});
    t.insert(t.end(), {{-0.33f, 0.0f, 0.0f}, {-0.5f, -0.18f, 0.0f}, {-0.5f, 0.0f, 0.0f}});
    t.insert(t.end(), {{-0.3f, 0.0f, 0.03f}, {-0.5f, 0.0f, 0.2f}, {-0.46f, 0.0f, 0.02f}});
    return t;
}

Tri rotorcraft() {
    Tri t;
    lofted(t, {{0.3f, 0.0f, -0.05f, 0.05f},
               {0.2f, 0.1f, -0.1f, 0.1f},
               {-0.05f, 0.1f, -0.1f, 0.12f},
               {-0.2f, 0.03f, -0.02f, 0.05f},
               {-0.5f, 0.015f, 0.01f, 0.04f}});
    box(t, {-0.45f, -0.45f, 0.135f}, {0.45f, 0.45f, 0.14f}); // the rotor disc, thin
    return t;
}

Tri ship(bool carrier) {
    Tri t;
    // Hull: freeboard 0.05 L, draft 0.04 L, beam 0.14 L, a pointed bow; then a superstructure or flight deck.
    const float top = 0.05f, keel = -0.04f;
    lofted(t, {{0.5f, 0.0f, keel * 0.3f, top * 1.2f},
               {0.3f, 0.06f, keel, top},
               {0.0f, 0.07f, keel, top},
               {-0.45f, 0.065f, keel, top},
               {-0.5f, 0.05f, keel * 0.5f, top}});
    if (carrier) {
        box(t, {-0.5f, -0.1f, top}, {0.48f, 0.12f, top + 0.015f});         // flight deck overhanging the hull
        box(t, {-0.1f, 0.08f, top + 0.015f}, {0.05f, 0.11f, top + 0.08f}); // island, starboard
    } else {
        box(t, {-0.2f, -0.04f, top}, {0.08f, 0.04f, top + 0.07f});
        box(t, {-0.08f, -0.015f, top + 0.07f}, {-0.02f, 0.015f, top + 0.16f}); // mast
    }
    return t;
}

/// A splash column: rings from the sea (z = 0) to the top (z = 1), narrow at the base and opening into a
/// crown, with a closed cap.
Tri plume() {
    Tri t;
    constexpr int SEG = 14, RINGS = 6;
    auto radius = [](float z) { return 0.08f + 0.22f * std::pow(z, 1.6f); };
    for (int r = 0; r < RINGS; ++r) {
        const float z0 = static_cast<float>(r) / RINGS, z1 = static_cast<float>(r + 1) / RINGS;
        for (int k = 0; k < SEG; ++k) {
            const float a0 = 6.2831853f * k / SEG, a1 = 6.2831853f * (k + 1) / SEG;
            auto p = [&](float z, float a) {
                return glm::vec3(radius(z) * std::cos(a), radius(z) * std::sin(a), z);
            };
            quad(t, p(z0, a0), p(z0, a1), p(z1, a1), p(z1, a0));
            if (r == RINGS - 1)
                t.insert(t.end(), {p(1.0f, a0), p(1.0f, a1), glm::vec3(0.0f, 0.0f, 0.93f)});
        }
    }
    return t;
}

Tri weapon() {
    Tri t;
    lofted(t, {{0.5f, 0.0f, 0.0f, 0.0f},
               {0.35f, 0.04f, -0.04f, 0.04f},
               {-0.5f, 0.04f, -0.04f, 0.04f},
               {-0.5f, 0.0f, 0.0f, 0.0f}});
    return t;
}

constexpr const char* VERT = R"(layout(location = 0) in vec3 aPos;
uniform mat4 uViewProj;
uniform mat3 uAxes;   // body -> world, columns forward, right, up, scaled by the length
uniform vec3 uOffset; // camera-relative position of the body origin (curvature drop applied)
out vec3 vRel;
void main() {
    vRel = uOffset + uAxes * aPos;
    gl_Position = uViewProj * vec4(vRel, 1.0);
}
)";

constexpr const char* FRAG = R"(in vec3 vRel;
uniform vec3 uSun;
uniform vec3 uAlbedo;
uniform float uLight; // ObjectRenderer::draw's lightScale
layout(location = 0) out vec4 oColor;
void main() {
    vec3 n = normalize(cross(dFdx(vRel), dFdy(vRel)));
    if (dot(n, vRel) > 0.0) n = -n; // face the camera: thin plates are two sided
    // Sun (Lambert) plus a sky ambient that is brighter from above; scene-linear, same scale as the sea's sky.
    float sun = max(dot(n, uSun), 0.0) * (uSun.z > 0.0 ? 1.0 : 0.0);
    float sky = 0.35 + 0.25 * n.z;
    oColor = vec4(uAlbedo * (uLight * (2.2 * sun + sky)), 1.0);
}
)";

} // namespace

ObjectRenderer::ObjectRenderer() {
    mProgram = buildProgram(
        {{ShaderStage::Vertex, {{"objects.vert", VERT}}}, {ShaderStage::Fragment, {{"objects.frag", FRAG}}}},
        "replay objects");
    std::vector<glm::vec3> all;
    const Tri meshes[OBJECT_SHAPES] = {aircraft(), rotorcraft(), ship(false), ship(true), weapon(), plume()};
    for (int i = 0; i < OBJECT_SHAPES; ++i) {
        mRanges[i] = {static_cast<int>(all.size()), static_cast<int>(meshes[i].size())};
        all.insert(all.end(), meshes[i].begin(), meshes[i].end());
    }
    mVertices = Buffer::create(all.size() * sizeof(glm::vec3), all.data());
    mVao = VertexArray::create();
    glVertexArrayVertexBuffer(mVao.id(), 0, mVertices.id(), 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(mVao.id(), 0);
    glVertexArrayAttribFormat(mVao.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(mVao.id(), 0, 0);
}

int ObjectRenderer::draw(const std::vector<DrawnObject>& objects, const CameraFrame& camera, unsigned fbo,
                         int w, int h, const glm::dvec3& sunDirection, double earthRadius,
                         double lightScale) {
    if (objects.empty())
        return 0;
    StateGuard guard;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE); // reverse-Z, as the ocean draws (engine/Space.h)
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    const GLuint p = mProgram.id();
    glUseProgram(p);
    glBindVertexArray(mVao.id());
    glUniformMatrix4fv(glGetUniformLocation(p, "uViewProj"), 1, GL_FALSE, &camera.viewProj[0][0]);
    const glm::vec3 sun = glm::normalize(glm::vec3(sunDirection));
    glUniform3f(glGetUniformLocation(p, "uSun"), sun.x, sun.y, sun.z);
    glUniform1f(glGetUniformLocation(p, "uLight"), static_cast<float>(lightScale));
    const GLint axesLoc = glGetUniformLocation(p, "uAxes"), offLoc = glGetUniformLocation(p, "uOffset"),
                albedoLoc = glGetUniformLocation(p, "uAlbedo");
    int drawn = 0;
    for (const DrawnObject& o : objects) {
        glm::dvec3 rel = o.pose.position - camera.origin;
        if (earthRadius > 0.0) { // the same drop d^2 / 2R as the sea (ocean/OceanConstants.h)
            const double d = std::hypot(rel.x, rel.y);
            rel.z -= d * d / (2.0 * earthRadius);
        }
        // Too far to cover a pixel (a 19 m aircraft beyond ~38 km): skip.
        const double dist = glm::length(rel);
        if (dist > 2000.0 * o.length + 1.0)
            continue;
        const glm::dmat3 axes = attitudeMatrix(o.pose.headingDeg, o.pose.pitchDeg, o.pose.rollDeg) * o.length;
        const glm::mat3 axesF(axes);
        glUniformMatrix3fv(axesLoc, 1, GL_FALSE, &axesF[0][0]);
        glUniform3f(offLoc, static_cast<float>(rel.x), static_cast<float>(rel.y), static_cast<float>(rel.z));
        const int k = static_cast<int>(o.shape);
        const glm::vec3 albedo = o.albedo.x >= 0.0f ? o.albedo
                                 : o.shape == ObjectShape::Ship || o.shape == ObjectShape::Carrier
                                     ? glm::vec3(0.22f, 0.23f, 0.25f)
                                     : glm::vec3(0.30f, 0.32f, 0.35f);
        glUniform3f(albedoLoc, albedo.x, albedo.y, albedo.z);
        glDrawArrays(GL_TRIANGLES, mRanges[k].first, mRanges[k].count);
        ++drawn;
    }
    return drawn;
}

} // namespace pacifica::gl
