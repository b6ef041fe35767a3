// GridMesh (internal): an indexed 2D grid on the GPU — one vec2 attribute at location 0 and 32-bit
// indices — as the sea's grids (RadialGrid, ProjectedGrid) and the effects' secondary grids use it.
#pragma once

#include "engine/gl/GlObjects.h"

#include <epoxy/gl.h>

#include <cstdint>
#include <vector>

namespace pacifica::ocean {

struct GridMesh {
    gl::Buffer vertices, indices;
    gl::VertexArray vao;
    int indexCount = 0, vertexCount = 0;

    /// Uploads `vertices` (x, y pairs) and `indices` (2 buffer uploads) and builds the vertex array.
    static GridMesh upload(const std::vector<float>& vertices, const std::vector<uint32_t>& indices) {
        GridMesh m;
        m.vertices = gl::Buffer::create(vertices.size() * sizeof(float), vertices.data());
        m.indices = gl::Buffer::create(indices.size() * sizeof(uint32_t), indices.data());
        m.vao = gl::VertexArray::create();
        const GLuint vao = m.vao.id();
        glVertexArrayVertexBuffer(vao, 0, m.vertices.id(), 0, 2 * sizeof(float));
        glVertexArrayElementBuffer(vao, m.indices.id());
        glEnableVertexArrayAttrib(vao, 0);
        glVertexArrayAttribFormat(vao, 0, 2, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao, 0, 0);
        m.indexCount = static_cast<int>(indices.size());
        m.vertexCount = static_cast<int>(vertices.size() / 2);
        return m;
    }
};

} // namespace pacifica::ocean
