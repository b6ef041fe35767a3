// GL tests of the engine's GL layer under headless EGL (llvmpipe in CI): program building, with compile and
// link errors mapped back to source names and lines. The binary's files share one context and the GlTest
// fixture (GlLayerTest.h).
#include "GlLayerTest.h"

namespace {

using namespace pacifica::gltest;

// Shader building
// ---------------------------------------------------------------------------------------------------------

using ShaderTest = GlTest;

TEST_F(ShaderTest, VertexFragmentPairBuilds) {
    gl::Program p =
        gl::buildProgram({{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
                          {gl::ShaderStage::Fragment,
                           {{"tint.frag", "uniform vec4 uTint;\nout vec4 c;\nvoid main() { c = uTint; }"}}}},
                         "tint");
    ASSERT_NE(p.id(), 0u);
    EXPECT_TRUE(p.owned());
    EXPECT_TRUE(glIsProgram(p.id()));
    GLint linked = 0;
    glGetProgramiv(p.id(), GL_LINK_STATUS, &linked);
    EXPECT_EQ(linked, GL_TRUE);
    EXPECT_GE(p.uniformLocation("uTint"), 0);
    EXPECT_EQ(p.uniformLocation("uNoSuchUniform"), -1);
}

TEST_F(ShaderTest, ComputeProgramBuilds) {
    gl::Program p = gl::buildProgram(
        {{gl::ShaderStage::Compute,
          {{"<defines>", "#define N 4"}, {"fill.comp", "layout(local_size_x = N) in;\nvoid main() {}"}}}},
        "fill");
    ASSERT_NE(p.id(), 0u);
    GLint size[3] = {};
    glGetProgramiv(p.id(), GL_COMPUTE_WORK_GROUP_SIZE, size);
    EXPECT_EQ(size[0], 4) << "the <defines> source must be compiled before fill.comp";
}

// Semantic errors (undeclared identifiers, type errors) are the common kind. Mesa reports them with source
// string 0 whatever `#line L N` said (its parser's YYLLOC_DEFAULT resets the source number; only token-level
// syntax and preprocessor errors keep N), so a mapping that trusts N alone names "<source 0>" here.
TEST_F(ShaderTest, CompileErrorNamesTheFileAndLine) {
    mExpectGlDebugErrors = true;
    const std::string brokenFrag = "out vec4 fragColor;\n"                         // line 1
                                   "void main() {\n"                               // line 2
                                   "    fragColor = vec4(undeclaredThing, 1.0);\n" // line 3
                                   "}\n";
    const std::string message = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram({{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
                                {gl::ShaderStage::Fragment, {{"broken.frag", brokenFrag}}}},
                               "brokenProgram");
    });
    EXPECT_TRUE(hasLocation(message, "broken.frag", 3)) << message;
    EXPECT_TRUE(message.starts_with("brokenProgram: fragment shader failed to compile")) << message;
    EXPECT_TRUE(contains(message, "undeclaredThing")) << message;
}

TEST_F(ShaderTest, ErrorInTheSecondSourceIsAttributedToIt) {
    mExpectGlDebugErrors = true;
    // Three lines of defines: a location counted across the concatenation would say line 5, not 2.
    const std::string defines = "#define GAIN 2.0\n#define BIAS 0.5\n#define UNUSED 1\n";
    const std::string second = "out vec4 fragColor;\n"                                // line 1
                               "void main() { fragColor = vec4(GAIN * missing); }\n"; // line 2
    const std::string message = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
             {gl::ShaderStage::Fragment, {{"<defines>", defines}, {"second.frag", second}}}},
            "twoSources");
    });
    EXPECT_TRUE(hasLocation(message, "second.frag", 2)) << message;
    EXPECT_FALSE(contains(message, "<defines>:")) << message;
    EXPECT_TRUE(contains(message, "twoSources")) << message;
}

// Syntax errors are located at a token, and Mesa keeps the `#line` source number for those.
TEST_F(ShaderTest, SyntaxErrorInTheSecondSourceIsAttributedToIt) {
    mExpectGlDebugErrors = true;
    const std::string defines = "#define GAIN 2.0\n#define BIAS 0.5\n#define UNUSED 1\n";
    const std::string second = "out vec4 fragColor;\n"            // line 1
                               "void main() {\n"                  // line 2
                               "    fragColor = vec4(GAIN) + ;\n" // line 3
                               "}\n";
    const std::string message = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
             {gl::ShaderStage::Fragment, {{"<defines>", defines}, {"syntax.frag", second}}}},
            "syntaxError");
    });
    EXPECT_TRUE(hasLocation(message, "syntax.frag", 3)) << message;
    EXPECT_FALSE(contains(message, "<defines>:")) << message;
    EXPECT_FALSE(contains(message, "<source")) << message;
}

TEST_F(ShaderTest, ErrorInAVertexShaderNamesTheVertexStage) {
    mExpectGlDebugErrors = true;
    const std::string message = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex, {{"bad.vert", "void main() {\n  gl_Position = vec4(1.0) + ;\n}"}}},
             {gl::ShaderStage::Fragment, {{"solid.frag", SOLID_FRAG}}}},
            "badVertex");
    });
    EXPECT_TRUE(message.starts_with("badVertex: vertex shader failed to compile")) << message;
    EXPECT_TRUE(hasLocation(message, "bad.vert", 2)) << message;
}

TEST_F(ShaderTest, LinkErrorsSayLink) {
    mExpectGlDebugErrors = true;
    // Interface mismatch: the vertex stage writes a vec3, the fragment stage reads a vec4.
    const std::string mismatch = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex,
              {{"out3.vert", "out vec3 vColor;\nvoid main() { vColor = vec3(1.0); "
                             "gl_Position = vec4(0.0); }"}}},
             {gl::ShaderStage::Fragment,
              {{"in4.frag", "in vec4 vColor;\nout vec4 c;\nvoid main() { c = vColor; }"}}}},
            "mismatchedVaryings");
    });
    EXPECT_TRUE(contains(mismatch, "link")) << mismatch;
    EXPECT_TRUE(mismatch.starts_with("mismatchedVaryings: link failed")) << mismatch;

    // A fragment stage without main() compiles but cannot link.
    const std::string noMain = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
             {gl::ShaderStage::Fragment, {{"nomain.frag", "out vec4 c;\nvoid notMain() {}"}}}},
            "missingMain");
    });
    EXPECT_TRUE(noMain.starts_with("missingMain: link failed")) << noMain;
}

// mapShaderLog needs no context: pure string rewriting. Source index 0 is the "#version" line that
// buildProgram prepends, so sources[k] is driver string k+1.

} // namespace
