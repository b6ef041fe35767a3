// The ocean's embedded shaders and generated #defines: every file under ocean/shaders is embedded byte for
// byte; no embedded string literal exceeds MSVC's 16380-byte limit (the embedder splits long files at line
// ends into adjacent literals); shaderConstantDefines() holds each constant once, with its value; the
// uniform names the C++ sets and the names the GLSL declares are the same set. No GL.
#include "ocean/OceanConstants.h"
#include "ocean/OceanShaders.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace pacifica::ocean;

namespace {

std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Every match of `re`'s first group in `text`.
std::set<std::string> matches(const std::string& text, const std::regex& re) {
    std::set<std::string> out;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
        out.insert((*it)[1].str());
    return out;
}

} // namespace

// Uniform names are strings on both sides (glGetUniformLocation, glProgramUniform*, and the names that arrays
// build, "uFoamMix[" + i + "]"): a name the C++ sets that no GLSL declares is a typo whose location is -1
// (the value is silently dropped), and a declared plain uniform the C++ never names stays 0. Checked both
// ways over the renderer's sources (ocean/src, ocean/src/gpu) and the shaders, with the GLSL the C++
// generates.
TEST(OceanShaders, UniformNamesAreTheSameOnBothSides) {
    const std::filesystem::path root(PACIFICA_SOURCE_DIR_FOR_TESTS);
    std::string cpp;
    for (const char* dir : {"ocean/src", "ocean/src/gpu"})
        for (const auto& entry : std::filesystem::directory_iterator(root / dir))
            if (entry.path().extension() == ".cpp" || entry.path().extension() == ".h")
                cpp += readFile(entry.path());
    std::string glsl;
    for (const auto& entry : std::filesystem::directory_iterator(root / "ocean" / "shaders"))
        glsl += std::string(shaderText(entry.path().filename().string())) + "\n";
    glsl = std::regex_replace(glsl, std::regex(R"(//[^\n]*)"), "");
    for (size_t open; (open = glsl.find("/*")) != std::string::npos;) // a declaration in a comment is none
        glsl.erase(open, glsl.find("*/", open) == std::string::npos ? std::string::npos
                                                                    : glsl.find("*/", open) + 2 - open);
    // Names: a string literal "uName" or "uName[" in the C++; "uniform [layout] TYPE uName" in the GLSL and
    // in the GLSL the C++ writes; opaque types (samplers, images) are bound by unit, not named.
    const std::set<std::string> named = matches(cpp, std::regex(R"re("(u[A-Z][A-Za-z0-9_]*)\[?")re"));
    std::map<std::string, std::string> declared;
    const std::regex decl(R"(\buniform\s+(?:layout\s*\([^)]*\)\s+)?(\w+)\s+(u[A-Z]\w*))");
    for (const std::string* text : {&glsl, &cpp})
        for (auto it = std::sregex_iterator(text->begin(), text->end(), decl); it != std::sregex_iterator();
             ++it)
            declared.emplace((*it)[2].str(), (*it)[1].str());
    EXPECT_GT(named.size(), 100u) << "the scan finds the renderer's uniform names";
    for (const std::string& n : named)
        EXPECT_TRUE(declared.count(n)) << n << " is set by the C++ but declared by no shader";
    for (const auto& [n, type] : declared) {
        if (type.find("sampler") == std::string::npos && type.find("image") == std::string::npos) {
            EXPECT_TRUE(named.count(n)) << type << " " << n << " is declared but never set by the C++";
        }
    }
}

TEST(OceanShaders, EveryShaderFileIsEmbeddedByteForByte) {
    const std::filesystem::path dir =
        std::filesystem::path(PACIFICA_SOURCE_DIR_FOR_TESTS) / "ocean" / "shaders";
    int files = 0;
    size_t longest = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        const std::string disk = readFile(entry.path());
        EXPECT_EQ(std::string(shaderText(name)), disk) << name;
        longest = std::max(longest, disk.size());
        ++files;
    }
    EXPECT_GE(files, 25);
    EXPECT_GT(longest, 16380u) << "the test is meant to cover a file longer than one literal may be";
    EXPECT_THROW(shaderText("no-such.glsl"), std::out_of_range);
}

TEST(OceanShaders, NoEmbeddedLiteralExceedsMsvcsLimit) {
    const std::string generated = readFile(PACIFICA_OCEAN_EMBEDDED_CPP);
    ASSERT_FALSE(generated.empty()) << PACIFICA_OCEAN_EMBEDDED_CPP;
    const std::string open = "R\"PACIFICA_EMBED(", close = ")PACIFICA_EMBED\"";
    size_t pos = 0, literals = 0, longest = 0;
    while ((pos = generated.find(open, pos)) != std::string::npos) {
        const size_t begin = pos + open.size(), end = generated.find(close, begin);
        ASSERT_NE(end, std::string::npos);
        longest = std::max(longest, end - begin);
        ++literals;
        pos = end + close.size();
    }
    std::printf("%zu literals, the longest %zu bytes\n", literals, longest);
    EXPECT_LE(longest, 16380u);
    EXPECT_GT(literals, 25u); // more literals than files: the long ones are split
}

TEST(OceanShaders, ConstantDefinesHoldEachConstantOnce) {
    const std::string d = shaderConstantDefines();
    auto expectLine = [&](const std::string& line) {
        const size_t at = d.find(line + "\n");
        EXPECT_NE(at, std::string::npos) << line;
        EXPECT_EQ(d.find(line + "\n", at + 1), std::string::npos) << line << " twice";
    };
    expectLine("#define MAX_OCTAVES " + std::to_string(MAX_OCTAVES));
    expectLine("#define GRAVITY 9.81");
    expectLine("#define WATER_F0 0.02");
    expectLine("#define FOAM_PATTERN_SIZE " + std::to_string(FOAM_PATTERN_SIZE));
    expectLine("#define FOG_NOISE_TILE_2 7416.4");
    expectLine("#define FOAM_MEMORY_WINDOW " + std::to_string(FOAM_MEMORY_WINDOW));
    expectLine("#define FFT_MAX_CASCADES " + std::to_string(FFT_MAX_CASCADES));
    expectLine("#define FFT_MIX_AMPLITUDE 1.5");
    expectLine("#define MAX_SPOT_LIGHTS " + std::to_string(MAX_SPOT_LIGHTS));
    expectLine("#define SPOT_MIN_DISTANCE 0.1");
    expectLine("#define EFFECT_EXPLOSIONS_BINDING 4");
    expectLine("#define SHADE_OUTPUT_IMAGE_UNIT 1");
    expectLine("#define FFT_FOAM_MEMORY_IMAGE_UNIT 3");
    expectLine("#define ERF_AS_A float[5](0.254829592, -0.284496736, 1.42141374, -1.45315203, 1.06140543)");
    // The aperiodic mix's angle, written out for FFT_MIX_TERMS terms (4).
    expectLine("#define APERIODIC_MIX_THETA(m, first, rel) (FFT_MIX_AMPLITUDE * (sin(m[(first) + 0].z + "
               "dot(m[(first) + 0].xy, rel)) + sin(m[(first) + 1].z + dot(m[(first) + 1].xy, rel)) + "
               "sin(m[(first) + 2].z + dot(m[(first) + 2].xy, rel)) + sin(m[(first) + 3].z + "
               "dot(m[(first) + 3].xy, rel))))");
    // Every line is a define; 48 constants (3 of them arrays), the mix's macro, 13 binding slots and 10
    // image units.
    size_t lines = 0;
    for (size_t at = 0; (at = d.find('\n', at)) != std::string::npos; ++at)
        ++lines;
    EXPECT_EQ(lines, 72u);
    EXPECT_EQ(d.rfind("#define ", 0), 0u);
    EXPECT_EQ(d.back(), '\n');
}
