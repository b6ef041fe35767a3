// Unit tests of gl::mapShaderLog (engine/gl/Shader.h): driver compile logs (Mesa's "0:LINE(COL)", NVIDIA's
// "0(LINE)") rewritten to the names and lines of the sources a program was built from. No GL context.
#include "engine/gl/Shader.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

namespace gl = pacifica::gl;

const std::vector<gl::ShaderSource> AB = {{"a", ""}, {"b", ""}};

TEST(MapShaderLogTest, MesaLocationsBecomeNameLineColumn) {
    EXPECT_EQ(gl::mapShaderLog("1:12(5): error: x", AB), "a:12:5: error: x");
    EXPECT_EQ(gl::mapShaderLog("2:3(17): warning: y", AB), "b:3:17: warning: y");
}

TEST(MapShaderLogTest, MesaMultiLineLogMapsEveryLine) {
    EXPECT_EQ(gl::mapShaderLog("1:2(3): error: p\n2:40(5): error: q\n", AB),
              "a:2:3: error: p\nb:40:5: error: q\n");
}

TEST(MapShaderLogTest, IndicesOutsideTheSourcesAreNamedByNumber) {
    // Index 0 is the builder's own "#version" line; 3 is past the two sources.
    EXPECT_EQ(gl::mapShaderLog("0:1(10): error: v", AB), "<source 0>:1:10: error: v");
    EXPECT_EQ(gl::mapShaderLog("3:7(1): error: w", AB), "<source 3>:7:1: error: w");
}

TEST(MapShaderLogTest, NvidiaLocationsBecomeNameLine) {
    EXPECT_EQ(gl::mapShaderLog("2(7) : error C1008: undefined variable \"foo\"", AB),
              "b:7 : error C1008: undefined variable \"foo\"");
    EXPECT_EQ(gl::mapShaderLog("1(3) : error C0000: syntax error\n2(9) : warning C7022: z", AB),
              "a:3 : error C0000: syntax error\nb:9 : warning C7022: z");
}

TEST(MapShaderLogTest, TextWithoutLineStartLocationsIsUnchanged) {
    EXPECT_EQ(gl::mapShaderLog("error: linking failed", AB), "error: linking failed");
    EXPECT_EQ(gl::mapShaderLog("error: see 1:2(3) above", AB), "error: see 1:2(3) above");
    EXPECT_EQ(gl::mapShaderLog("", AB), "");
}

// ---------------------------------------------------------------------------------------------------------

} // namespace
