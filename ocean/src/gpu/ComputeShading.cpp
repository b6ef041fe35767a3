// ComputeShading: see ComputeShading.h.
#include "gpu/ComputeShading.h"

#include <epoxy/gl.h>

namespace pacifica::ocean {

namespace {

/// The GLSL image format of a colour texture's internal format, or nullptr when images cannot store it.
const char* imageFormatName(GLint format) {
    switch (format) {
    case GL_RGBA16F:
        return "rgba16f";
    case GL_RGBA32F:
        return "rgba32f";
    case GL_RGBA8:
        return "rgba8";
    case GL_RGB10_A2:
        return "rgb10_a2";
    case GL_R11F_G11F_B10F:
        return "r11f_g11f_b10f";
    default:
        return nullptr;
    }
}

GLint attachmentParameter(GLuint fbo, GLenum attachment, GLenum pname) {
    GLint v = 0;
    glGetNamedFramebufferAttachmentParameteriv(fbo, attachment, pname, &v);
    return v;
}

} // namespace

ComputeShading::~ComputeShading() {
    if (mDepthSampler) {
        glDeleteSamplers(1, &mDepthSampler);
        gl::noteDeleted(gl::ObjectKind::Sampler);
    }
}

bool ComputeShading::attach(unsigned hostFbo, int width, int height, bool displaced) {
    if (hostFbo == 0 || width <= 0 || height <= 0)
        return false;
    GLint drawBuffer = GL_NONE;
    glGetIntegerv(GL_DRAW_BUFFER0, &drawBuffer);
    if (drawBuffer < GL_COLOR_ATTACHMENT0 || drawBuffer > GL_COLOR_ATTACHMENT0 + 7)
        return false;
    // A single-level view of a 2D texture: its internal format, or 0.
    auto texture2D = [&](GLenum attachment, unsigned& name, int& level) -> GLint {
        if (attachmentParameter(hostFbo, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) != GL_TEXTURE ||
            attachmentParameter(hostFbo, attachment, GL_FRAMEBUFFER_ATTACHMENT_LAYERED) == GL_TRUE)
            return 0;
        name = static_cast<unsigned>(
            attachmentParameter(hostFbo, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME));
        level = attachmentParameter(hostFbo, attachment, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL);
        GLint target = 0, w = 0, h = 0, format = 0;
        glGetTextureParameteriv(name, GL_TEXTURE_TARGET, &target);
        if (target != GL_TEXTURE_2D)
            return 0;
        glGetTextureLevelParameteriv(name, level, GL_TEXTURE_INTERNAL_FORMAT, &format);
        glGetTextureLevelParameteriv(name, level, GL_TEXTURE_WIDTH, &w);
        glGetTextureLevelParameteriv(name, level, GL_TEXTURE_HEIGHT, &h);
        return w >= width && h >= height ? format : 0;
    };
    Key key;
    key.format = texture2D(static_cast<GLenum>(drawBuffer), key.color, key.colorLevel);
    const char* format = imageFormatName(key.format);
    const GLint depthFormat = texture2D(GL_DEPTH_ATTACHMENT, key.depth, key.depthLevel);
    if (!format || (depthFormat != GL_DEPTH_COMPONENT32F && depthFormat != GL_DEPTH32F_STENCIL8))
        return false;
    key.width = width;
    key.height = height;
    key.displaced = displaced;
    mFormatName = format;
    if (!mFbo || key.width != mKey.width || key.height != mKey.height || key.displaced != mKey.displaced) {
        mGeometry = gl::Texture::create2D(GL_RGBA16F, width, height);
        mOffset = displaced ? gl::Texture::create2D(GL_RG16F, width, height) : gl::Texture();
        mFbo = gl::Framebuffer::create();
        mFbo.attachColor(0, mGeometry);
        if (mOffset)
            mFbo.attachColor(1, mOffset);
    }
    if (!mDepthSampler) { // the host's depth read as values, whatever comparison its texture has set
        glCreateSamplers(1, &mDepthSampler);
        gl::noteCreated(gl::ObjectKind::Sampler);
        glSamplerParameteri(mDepthSampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
        glSamplerParameteri(mDepthSampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(mDepthSampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    mKey = key;
    // The host's depth is attached every frame: a host may delete its target and get the same name back
    // for a new one, and a cached attachment would keep the old object.
    glNamedFramebufferTexture(
        mFbo.id(), depthFormat == GL_DEPTH32F_STENCIL8 ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
        key.depth, key.depthLevel);
    return glCheckNamedFramebufferStatus(mFbo.id(), GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

void ComputeShading::beginGeometry() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, mFbo.id());
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0,
                               mOffset ? GLenum(GL_COLOR_ATTACHMENT1) : GLenum(GL_NONE)};
    glNamedFramebufferDrawBuffers(mFbo.id(), 2, buffers);
}

std::string ComputeShading::tileDefines() {
    std::string d = "#define SHADE_TILE_SIZE " + std::to_string(TILE_SIZE) + "\n#define SHADE_TILE_KINDS " +
                    std::to_string(TILE_KINDS) + "\n";
    const char* names[TILE_KINDS] = {"MIXED", "SEA", "SKY", "BEYOND"};
    for (int k = 0; k < TILE_KINDS; ++k)
        d += std::string("#define SHADE_TILE_") + names[k] + " " + std::to_string(k) + "\n";
    return d;
}

void ComputeShading::bindTextures() {
    glBindTextureUnit(DEPTH_UNIT, mKey.depth);
    glBindSampler(DEPTH_UNIT, mDepthSampler);
    glBindTextureUnit(GEOMETRY_UNIT, mGeometry.id());
    glBindTextureUnit(OFFSET_UNIT, mOffset ? mOffset.id() : 0);
}

void ComputeShading::setInputUniforms(unsigned program, bool drawSky) {
    glProgramUniform1i(program, glGetUniformLocation(program, "uDepth"), DEPTH_UNIT);
    glProgramUniform1i(program, glGetUniformLocation(program, "uDepthLevel"), mKey.depthLevel);
    glProgramUniform1i(program, glGetUniformLocation(program, "uGeometry"), GEOMETRY_UNIT);
    glProgramUniform1i(program, glGetUniformLocation(program, "uOffset"), OFFSET_UNIT);
    glProgramUniform2i(program, glGetUniformLocation(program, "uShadeSize"), mKey.width, mKey.height);
    glProgramUniform1i(program, glGetUniformLocation(program, "uShadeSky"), drawSky ? 1 : 0);
}

void ComputeShading::barrierAfterShading() {
    // The host reads or draws over its colour next, by any path.
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                    GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_PIXEL_BUFFER_BARRIER_BIT);
    glBindImageTexture(OUTPUT_IMAGE_UNIT, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glBindSampler(DEPTH_UNIT, 0);
}

void ComputeShading::shade(unsigned program, bool drawSky) {
    bindTextures();
    setInputUniforms(program, drawSky);
    glBindImageTexture(OUTPUT_IMAGE_UNIT, mKey.color, mKey.colorLevel, GL_FALSE, 0, GL_WRITE_ONLY,
                       static_cast<GLenum>(mKey.format));
    glUseProgram(program);
    glDispatchCompute(static_cast<GLuint>((mKey.width + TILE_SIZE - 1) / TILE_SIZE),
                      static_cast<GLuint>((mKey.height + TILE_SIZE - 1) / TILE_SIZE), 1);
    barrierAfterShading();
}

void ComputeShading::shadeTiles(unsigned sortProgram, const unsigned (&kindPrograms)[TILE_KINDS],
                                bool drawSky) {
    const int tilesX = (mKey.width + TILE_SIZE - 1) / TILE_SIZE;
    const int tileCount = tilesX * ((mKey.height + TILE_SIZE - 1) / TILE_SIZE);
    constexpr std::size_t headerBytes = 3 * TILE_KINDS * sizeof(GLuint);
    if (!mTiles || mTileCapacity != tileCount) {
        mTileCapacity = tileCount;
        mTiles =
            gl::Buffer::create(headerBytes + sizeof(GLuint) * TILE_KINDS * std::size_t(tileCount), nullptr);
    }
    if (!mTileReset) { // every kind's dispatch starts at (0 tiles, 1, 1): copied on the GPU, no upload a
                       // frame
        GLuint header[3 * TILE_KINDS];
        for (int k = 0; k < TILE_KINDS; ++k) {
            header[3 * k] = 0;
            header[3 * k + 1] = header[3 * k + 2] = 1;
        }
        mTileReset = gl::Buffer::create(headerBytes, header);
    }
    glCopyNamedBufferSubData(mTileReset.id(), mTiles.id(), 0, 0, headerBytes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TILE_BINDING, mTiles.id());
    bindTextures();
    auto setTileUniforms = [&](unsigned program) {
        setInputUniforms(program, drawSky);
        glProgramUniform1i(program, glGetUniformLocation(program, "uTilesX"), tilesX);
        glProgramUniform1ui(program, glGetUniformLocation(program, "uTileCapacity"),
                            static_cast<GLuint>(tileCount));
    };
    setTileUniforms(sortProgram);
    glProgramUniform1i(sortProgram, glGetUniformLocation(sortProgram, "uTileCount"), tileCount);
    glUseProgram(sortProgram);
    glDispatchCompute(static_cast<GLuint>((tileCount + 63) / 64), 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);

    glBindImageTexture(OUTPUT_IMAGE_UNIT, mKey.color, mKey.colorLevel, GL_FALSE, 0, GL_WRITE_ONLY,
                       static_cast<GLenum>(mKey.format));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, mTiles.id());
    for (int k = 0; k < TILE_KINDS; ++k) {
        setTileUniforms(kindPrograms[k]);
        glUseProgram(kindPrograms[k]);
        glDispatchComputeIndirect(static_cast<GLintptr>(3 * k * sizeof(GLuint)));
    }
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TILE_BINDING, 0);
    barrierAfterShading();
}

std::array<int, ComputeShading::TILE_KINDS> ComputeShading::tileCounts() const {
    std::array<int, TILE_KINDS> counts{};
    if (!mTiles)
        return counts;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint header[3 * TILE_KINDS] = {};
    glGetNamedBufferSubData(mTiles.id(), 0, sizeof header, header);
    for (int k = 0; k < TILE_KINDS; ++k)
        counts[static_cast<std::size_t>(k)] = static_cast<int>(header[3 * k]);
    return counts;
}

} // namespace pacifica::ocean
