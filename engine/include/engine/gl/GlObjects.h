// GlObjects: move-only RAII wrappers for OpenGL objects (GL 4.5 DSA), after Magnum's GL::Buffer.
//
// Every wrapper has an explicit empty state (default-constructed: id 0, owns nothing), is created with
// X::create(...), and can adopt a host's object without owning it (X::wrap(id)) so a host engine can lend
// its framebuffer or textures; release() gives up ownership and returns the id. Only the engine's GL layer
// includes GL headers; these types expose ids as plain unsigned ints.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace pacifica::gl {

using GLid = unsigned int;
using GLenumT = unsigned int;

/// The kinds of GL object the layer counts (liveObjects).
enum class ObjectKind : int { Buffer, Texture, Framebuffer, VertexArray, Program, Query, Sampler, Sync };
inline constexpr int OBJECT_KIND_COUNT = 8;
/// "buffer", "texture", ... (the soak benchmark's column names).
const char* toString(ObjectKind kind) noexcept;

/// GL objects alive in the process by kind: made through this layer (the handles' create/adopt, and the raw
/// samplers and fences of the ocean, which call noteCreated/noteDeleted) and not yet deleted or released,
/// summed over every context. Borrowed objects (wrap) are not counted. Always on: one relaxed atomic add
/// per create or delete, next to a driver call that costs microseconds.
struct LiveObjects {
    std::array<long long, OBJECT_KIND_COUNT> count{};
    long long of(ObjectKind kind) const { return count[static_cast<std::size_t>(kind)]; }
    long long total() const {
        long long t = 0;
        for (long long c : count)
            t += c;
        return t;
    }
};
LiveObjects liveObjects() noexcept;
void noteCreated(ObjectKind kind) noexcept;
void noteDeleted(ObjectKind kind) noexcept;

/// Owning-or-borrowing handle. Deleter is a stateless functor taking the id.
template <typename Deleter>
class Handle {
public:
    Handle() = default;
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& o) noexcept : mId(std::exchange(o.mId, 0)), mOwned(std::exchange(o.mOwned, false)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            mId = std::exchange(o.mId, 0);
            mOwned = std::exchange(o.mOwned, false);
        }
        return *this;
    }
    ~Handle() { reset(); }

    GLid id() const { return mId; }
    bool owned() const { return mOwned; }
    explicit operator bool() const { return mId != 0; }
    /// Gives up ownership; the caller now owns the returned id (no longer counted by liveObjects).
    GLid release() {
        if (mId && mOwned)
            noteDeleted(Deleter::KIND);
        mOwned = false;
        return std::exchange(mId, 0);
    }
    void reset() {
        if (mId && mOwned) {
            Deleter{}(mId);
            noteDeleted(Deleter::KIND);
        }
        mId = 0;
        mOwned = false;
    }

protected:
    Handle(GLid id, bool owned) : mId(id), mOwned(owned) {
        if (mId && mOwned)
            noteCreated(Deleter::KIND);
    }

private:
    GLid mId = 0;
    bool mOwned = false;
};

struct BufferDeleter {
    static constexpr ObjectKind KIND = ObjectKind::Buffer;
    void operator()(GLid id) const;
};
struct TextureDeleter {
    static constexpr ObjectKind KIND = ObjectKind::Texture;
    void operator()(GLid id) const;
};
struct FramebufferDeleter {
    static constexpr ObjectKind KIND = ObjectKind::Framebuffer;
    void operator()(GLid id) const;
};
struct VertexArrayDeleter {
    static constexpr ObjectKind KIND = ObjectKind::VertexArray;
    void operator()(GLid id) const;
};
struct ProgramDeleter {
    static constexpr ObjectKind KIND = ObjectKind::Program;
    void operator()(GLid id) const;
};
struct QueryDeleter {
    static constexpr ObjectKind KIND = ObjectKind::Query;
    void operator()(GLid id) const;
};

class Buffer : public Handle<BufferDeleter> {
public:
    Buffer() = default;
    Buffer(Buffer&& o) noexcept : Handle(std::move(o)), mSize(std::exchange(o.mSize, 0)) {}
    Buffer& operator=(Buffer&& o) noexcept {
        Handle::operator=(std::move(o));
        mSize = std::exchange(o.mSize, 0);
        return *this;
    }
    /// glCreateBuffers + immutable glNamedBufferStorage (flags: GL_DYNAMIC_STORAGE_BIT etc.; 0 = static).
    static Buffer create(std::size_t bytes, const void* data, unsigned flags = 0);
    static Buffer wrap(GLid id) { return Buffer(id, false); }
    /// glNamedBufferSubData; requires GL_DYNAMIC_STORAGE_BIT at creation.
    void upload(std::size_t offset, std::size_t bytes, const void* data);
    std::size_t size() const { return mSize; }

private:
    Buffer(GLid id, bool owned) : Handle(id, owned) {}
    std::size_t mSize = 0;
};

class Texture : public Handle<TextureDeleter> {
public:
    Texture() = default;
    Texture(Texture&& o) noexcept
        : Handle(std::move(o)), mTarget(std::exchange(o.mTarget, 0)), mWidth(std::exchange(o.mWidth, 0)),
          mHeight(std::exchange(o.mHeight, 0)), mDepth(std::exchange(o.mDepth, 0)) {}
    Texture& operator=(Texture&& o) noexcept {
        Handle::operator=(std::move(o));
        mTarget = std::exchange(o.mTarget, 0);
        mWidth = std::exchange(o.mWidth, 0);
        mHeight = std::exchange(o.mHeight, 0);
        mDepth = std::exchange(o.mDepth, 0);
        return *this;
    }
    /// glCreateTextures(target) + glTextureStorage2D/3D. depth = 0 for 2D targets.
    static Texture create2D(GLenumT internalFormat, int width, int height, int levels = 1);
    static Texture create3D(GLenumT internalFormat, int width, int height, int depth, int levels = 1);
    /// glCreateTextures(GL_TEXTURE_2D_ARRAY) + glTextureStorage3D.
    static Texture createArray2D(GLenumT internalFormat, int width, int height, int layers, int levels = 1);
    static Texture wrap(GLid id, GLenumT target) { return Texture(id, false, target); }
    /// Takes ownership of an existing texture object.
    static Texture adopt(GLid id, GLenumT target) { return Texture(id, true, target); }
    GLenumT target() const { return mTarget; }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int depth() const { return mDepth; }
    /// Sets min/mag filter and wrap mode on all axes (e.g. GL_LINEAR, GL_REPEAT).
    void setSampling(GLenumT minFilter, GLenumT magFilter, GLenumT wrap);

private:
    Texture(GLid id, bool owned, GLenumT target) : Handle(id, owned), mTarget(target) {}
    GLenumT mTarget = 0;
    int mWidth = 0, mHeight = 0, mDepth = 0;
};

class Framebuffer : public Handle<FramebufferDeleter> {
public:
    Framebuffer() = default;
    static Framebuffer create();
    /// Adopts a host's framebuffer (0 = the default framebuffer) without owning it.
    static Framebuffer wrap(GLid id) { return Framebuffer(id, false); }
    void attachColor(int index, const Texture& texture, int level = 0);
    void attachDepth(const Texture& texture);
    /// Throws std::runtime_error naming the incomplete status.
    void checkComplete(const char* what) const;

private:
    Framebuffer(GLid id, bool owned) : Handle(id, owned) {}
};

class VertexArray : public Handle<VertexArrayDeleter> {
public:
    VertexArray() = default;
    static VertexArray create();
    static VertexArray wrap(GLid id) { return VertexArray(id, false); }

private:
    VertexArray(GLid id, bool owned) : Handle(id, owned) {}
};

class Program : public Handle<ProgramDeleter> {
public:
    Program() = default;
    static Program adopt(GLid id) { return Program(id, true); }
    static Program wrap(GLid id) { return Program(id, false); }
    /// -1 when the uniform does not exist or was optimised away.
    int uniformLocation(const char* name) const;

private:
    Program(GLid id, bool owned) : Handle(id, owned) {}
};

class Query : public Handle<QueryDeleter> {
public:
    Query() = default;
    static Query create(GLenumT target);
    static Query wrap(GLid id) { return Query(id, false); }

private:
    Query(GLid id, bool owned) : Handle(id, owned) {}
};

/// Saves the GL state the ocean component changes and restores it on destruction, so a host's state
/// survives a frame of ours (viewport, draw framebuffer, program, VAO, depth/blend/cull enables,
/// depth func and mask, clip control, the first 8 clip-distance enables, separate blend factors, polygon
/// offset (fill), clear values, active texture unit). Texture bindings are not saved.
class StateGuard {
public:
    StateGuard();
    ~StateGuard();
    StateGuard(const StateGuard&) = delete;
    StateGuard& operator=(const StateGuard&) = delete;

private:
    int mViewport[4]{};
    int mDrawFbo = 0, mReadFbo = 0, mProgram = 0, mVao = 0, mActiveTexture = 0;
    int mDepthFunc = 0, mClipOrigin = 0, mClipDepth = 0;
    int mBlendSrcRgb = 0, mBlendDstRgb = 0, mBlendSrcAlpha = 0, mBlendDstAlpha = 0;
    float mPolygonOffsetFactor = 0.0f, mPolygonOffsetUnits = 0.0f;
    unsigned char mDepthMask = 1;
    bool mDepthTest = false, mBlend = false, mCull = false, mScissor = false, mPolygonOffsetFill = false;
    static constexpr int CLIP_DISTANCES = 8; // GL's least GL_MAX_CLIP_DISTANCES
    bool mClipDistance[CLIP_DISTANCES]{};
    float mClearColor[4]{};
    double mClearDepth = 1.0;
};

} // namespace pacifica::gl
