// Shader compilation with error logs mapped back to source names and lines.
#include "engine/gl/Shader.h"

#include <epoxy/gl.h>

#include <cctype>
#include <regex>

namespace pacifica::gl {
namespace {

/// Lines per source in the concatenated shader (see mapShaderLog); no source may be this long.
constexpr long LINE_BLOCK = 100000;

GLenum glStage(ShaderStage s) {
    switch (s) {
    case ShaderStage::Vertex:
        return GL_VERTEX_SHADER;
    case ShaderStage::Fragment:
        return GL_FRAGMENT_SHADER;
    case ShaderStage::Compute:
        return GL_COMPUTE_SHADER;
    }
    return GL_VERTEX_SHADER;
}

const char* stageName(ShaderStage s) {
    switch (s) {
    case ShaderStage::Vertex:
        return "vertex";
    case ShaderStage::Fragment:
        return "fragment";
    case ShaderStage::Compute:
        return "compute";
    }
    return "?";
}

} // namespace

std::string mapShaderLog(const std::string& log, const std::vector<ShaderSource>& sources) {
    // Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error ...". Source index 0 is the #version line we add,
    // sources[i] is string i+1. buildProgram starts source k at line k * LINE_BLOCK + 1, because Mesa reports
    // source number 0 for semantic errors whatever #line said: a line above LINE_BLOCK identifies its source
    // by itself; smaller lines (other producers of logs) fall back to the reported source number.
    static const std::regex mesa(R"((^|\n)(\d+):(\d+)\((\d+)\))");
    static const std::regex nvidia(R"((^|\n)(\d+)\((\d+)\))");
    auto nameOf = [&](long index) -> std::string {
        if (index >= 1 && index <= static_cast<long>(sources.size()))
            return sources[static_cast<size_t>(index - 1)].name;
        std::string unnamed = "<source ";
        unnamed += std::to_string(index);
        unnamed += '>';
        return unnamed;
    };
    std::string out;
    std::smatch m;
    const std::regex* patterns[] = {&mesa, &nvidia};
    for (const std::regex* re : patterns) {
        out.clear();
        auto begin = log.cbegin();
        bool matched = false;
        while (std::regex_search(begin, log.cend(), m, *re)) {
            matched = true;
            long index = std::stol(m[2].str());
            long line = std::stol(m[3].str());
            if (line > LINE_BLOCK) {
                index = line / LINE_BLOCK;
                line %= LINE_BLOCK;
            }
            out.append(begin, m[0].first);
            out += m[1].str();
            out += nameOf(index);
            out += ':';
            out += std::to_string(line);
            if (re == &mesa) {
                out += ':';
                out += m[4].str();
            }
            begin = m[0].second;
        }
        out.append(begin, log.cend());
        if (matched)
            return out;
    }
    return log;
}

Program buildProgram(const std::vector<StageSources>& stages, const std::string& programName,
                     const std::vector<std::string>& feedbackVaryings) {
    std::vector<GLuint> shaders;
    auto cleanup = [&] {
        for (GLuint s : shaders)
            glDeleteShader(s);
    };
    for (const StageSources& st : stages) {
        std::vector<std::string> texts;
        texts.emplace_back("#version 450 core\n");
        for (size_t i = 0; i < st.sources.size(); ++i)
            texts.push_back("#line " + std::to_string((i + 1) * LINE_BLOCK + 1) + " " +
                            std::to_string(i + 1) + "\n" + st.sources[i].text + "\n");
        std::vector<const char*> ptrs;
        for (const std::string& t : texts)
            ptrs.push_back(t.c_str());
        GLuint sh = glCreateShader(glStage(st.stage));
        shaders.push_back(sh);
        glShaderSource(sh, static_cast<GLsizei>(ptrs.size()), ptrs.data(), nullptr);
        glCompileShader(sh);
        GLint ok = 0;
        glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint len = 0;
            glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
            std::string logText(static_cast<size_t>(std::max(len, 1)), '\0');
            glGetShaderInfoLog(sh, len, nullptr, logText.data());
            cleanup();
            throw ShaderError(programName + ": " + stageName(st.stage) + " shader failed to compile:\n" +
                              mapShaderLog(logText.c_str(), st.sources));
        }
    }
    GLuint prog = glCreateProgram();
    for (GLuint s : shaders)
        glAttachShader(prog, s);
    if (!feedbackVaryings.empty()) {
        std::vector<const char*> names;
        for (const std::string& v : feedbackVaryings)
            names.push_back(v.c_str());
        glTransformFeedbackVaryings(prog, static_cast<GLsizei>(names.size()), names.data(),
                                    GL_INTERLEAVED_ATTRIBS);
    }
    glLinkProgram(prog);
    cleanup();
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &len);
        std::string logText(static_cast<size_t>(std::max(len, 1)), '\0');
        glGetProgramInfoLog(prog, len, nullptr, logText.data());
        glDeleteProgram(prog);
        throw ShaderError(programName + ": link failed:\n" + std::string(logText.c_str()));
    }
    return Program::adopt(prog);
}

} // namespace pacifica::gl
