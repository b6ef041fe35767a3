// GlObjects implementation: GL 4.5 direct-state-access creation and deletion, and the state guard.
#include "engine/gl/GlObjects.h"

#include <epoxy/gl.h>

#include <atomic>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace pacifica::gl {

namespace {
std::array<std::atomic<long long>, OBJECT_KIND_COUNT> gLive{};
} // namespace

const char* toString(ObjectKind kind) noexcept {
    static constexpr std::array<const char*, OBJECT_KIND_COUNT> NAMES = {
        "buffer", "texture", "framebuffer", "vertex_array", "program", "query", "sampler", "sync"};
    const auto i = static_cast<size_t>(kind);
    return i < NAMES.size() ? NAMES[i] : "unknown";
}

LiveObjects liveObjects() noexcept {
    LiveObjects l;
    for (size_t i = 0; i < gLive.size(); ++i)
        l.count[i] = gLive[i].load(std::memory_order_relaxed);
    return l;
}

void noteCreated(ObjectKind kind) noexcept {
    gLive[static_cast<size_t>(kind)].fetch_add(1, std::memory_order_relaxed);
}

void noteDeleted(ObjectKind kind) noexcept {
    gLive[static_cast<size_t>(kind)].fetch_sub(1, std::memory_order_relaxed);
}

void BufferDeleter::operator()(GLid id) const {
    glDeleteBuffers(1, &id);
}
void TextureDeleter::operator()(GLid id) const {
    glDeleteTextures(1, &id);
}
void FramebufferDeleter::operator()(GLid id) const {
    glDeleteFramebuffers(1, &id);
}
void VertexArrayDeleter::operator()(GLid id) const {
    glDeleteVertexArrays(1, &id);
}
void ProgramDeleter::operator()(GLid id) const {
    glDeleteProgram(id);
}
void QueryDeleter::operator()(GLid id) const {
    glDeleteQueries(1, &id);
}

Buffer Buffer::create(std::size_t bytes, const void* data, unsigned flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
    Buffer b(id, true);
    b.mSize = bytes;
    return b;
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) {
    if (bytes > mSize || offset > mSize - bytes) // written so that offset + bytes cannot overflow
        throw std::logic_error("Buffer::upload(): range " + std::to_string(offset) + "+" +
                               std::to_string(bytes) + " exceeds size " + std::to_string(mSize));
    glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

Texture Texture::create2D(GLenumT internalFormat, int width, int height, int levels) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    glTextureStorage2D(id, levels, internalFormat, width, height);
    Texture t(id, true, GL_TEXTURE_2D);
    t.mWidth = width;
    t.mHeight = height;
    return t;
}

Texture Texture::create3D(GLenumT internalFormat, int width, int height, int depth, int levels) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &id);
    glTextureStorage3D(id, levels, internalFormat, width, height, depth);
    Texture t(id, true, GL_TEXTURE_3D);
    t.mWidth = width;
    t.mHeight = height;
    t.mDepth = depth;
    return t;
}

void Texture::setSampling(GLenumT minFilter, GLenumT magFilter, GLenumT wrap) {
    glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, static_cast<GLint>(minFilter));
    glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, static_cast<GLint>(magFilter));
    glTextureParameteri(id(), GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
    glTextureParameteri(id(), GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
    glTextureParameteri(id(), GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap));
}

Texture Texture::createArray2D(GLenumT internalFormat, int width, int height, int layers, int levels) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    glTextureStorage3D(id, levels, internalFormat, width, height, layers);
    Texture t(id, true, GL_TEXTURE_2D_ARRAY);
    t.mWidth = width;
    t.mHeight = height;
    t.mDepth = layers;
    return t;
}

Framebuffer Framebuffer::create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Framebuffer(id, true);
}

void Framebuffer::attachColor(int index, const Texture& texture, int level) {
    glNamedFramebufferTexture(id(), GL_COLOR_ATTACHMENT0 + index, texture.id(), level);
}

void Framebuffer::attachDepth(const Texture& texture) {
    glNamedFramebufferTexture(id(), GL_DEPTH_ATTACHMENT, texture.id(), 0);
}

void Framebuffer::checkComplete(const char* what) const {
    const GLenum status = glCheckNamedFramebufferStatus(id(), GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04X", status);
        throw std::runtime_error(std::string("Framebuffer::checkComplete(): ") + what +
                                 " is incomplete, status " + hex);
    }
}

VertexArray VertexArray::create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArray(id, true);
}

int Program::uniformLocation(const char* name) const {
    return glGetUniformLocation(id(), name);
}

Query Query::create(GLenumT target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return Query(id, true);
}

StateGuard::StateGuard() {
    glGetIntegerv(GL_VIEWPORT, mViewport);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &mDrawFbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &mReadFbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &mProgram);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &mVao);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &mActiveTexture);
    glGetIntegerv(GL_DEPTH_FUNC, &mDepthFunc);
    glGetIntegerv(GL_CLIP_ORIGIN, &mClipOrigin);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &mClipDepth);
    glGetIntegerv(GL_BLEND_SRC_RGB, &mBlendSrcRgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &mBlendDstRgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &mBlendSrcAlpha);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &mBlendDstAlpha);
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &mPolygonOffsetFactor);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &mPolygonOffsetUnits);
    mPolygonOffsetFill = glIsEnabled(GL_POLYGON_OFFSET_FILL);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &mDepthMask);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, mClearColor);
    glGetDoublev(GL_DEPTH_CLEAR_VALUE, &mClearDepth);
    mDepthTest = glIsEnabled(GL_DEPTH_TEST);
    mBlend = glIsEnabled(GL_BLEND);
    mCull = glIsEnabled(GL_CULL_FACE);
    mScissor = glIsEnabled(GL_SCISSOR_TEST);
    for (int i = 0; i < CLIP_DISTANCES; ++i)
        mClipDistance[i] = glIsEnabled(GLenum(GL_CLIP_DISTANCE0 + i));
}

StateGuard::~StateGuard() {
    auto set = [](GLenum cap, bool on) { on ? glEnable(cap) : glDisable(cap); };
    glViewport(mViewport[0], mViewport[1], mViewport[2], mViewport[3]);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(mDrawFbo));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(mReadFbo));
    // A program the host deleted while it was current is freed once another one is used: then there is
    // nothing to restore (glUseProgram would raise GL_INVALID_VALUE), and 0 is what the host would have.
    const GLuint program = static_cast<GLuint>(mProgram);
    glUseProgram(program == 0 || glIsProgram(program) ? program : 0);
    glBindVertexArray(static_cast<GLuint>(mVao));
    glActiveTexture(static_cast<GLenum>(mActiveTexture));
    glDepthFunc(static_cast<GLenum>(mDepthFunc));
    glClipControl(static_cast<GLenum>(mClipOrigin), static_cast<GLenum>(mClipDepth));
    glBlendFuncSeparate(static_cast<GLenum>(mBlendSrcRgb), static_cast<GLenum>(mBlendDstRgb),
                        static_cast<GLenum>(mBlendSrcAlpha), static_cast<GLenum>(mBlendDstAlpha));
    glPolygonOffset(mPolygonOffsetFactor, mPolygonOffsetUnits);
    set(GL_POLYGON_OFFSET_FILL, mPolygonOffsetFill);
    glDepthMask(mDepthMask);
    glClearColor(mClearColor[0], mClearColor[1], mClearColor[2], mClearColor[3]);
    glClearDepth(mClearDepth);
    set(GL_DEPTH_TEST, mDepthTest);
    set(GL_BLEND, mBlend);
    set(GL_CULL_FACE, mCull);
    set(GL_SCISSOR_TEST, mScissor);
    for (int i = 0; i < CLIP_DISTANCES; ++i)
        set(GLenum(GL_CLIP_DISTANCE0 + i), mClipDistance[i]);
}

} // namespace pacifica::gl
