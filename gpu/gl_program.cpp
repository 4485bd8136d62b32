#include "gpu/gl_program.h"

#include "core/error.h"
#include "gpu/shader_sources.h"

namespace tyndall {

std::string glsl(const char* name) {
    return shaderSource(name);
}

namespace {
const char* stageName(GLenum type) {
    switch (type) {
        case GL_VERTEX_SHADER:
            return "vertex";
        case GL_FRAGMENT_SHADER:
            return "fragment";
        case GL_COMPUTE_SHADER:
            return "compute";
        default:
            return "shader";
    }
}
/// Driver logs span lines; Error messages are one line.
std::string oneLine(const char* log) {
    std::string s(log);
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    for (char& c : s)
        if (c == '\n') c = '|';
    return s;
}
}  // namespace

GlProgram::GlProgram(const GlFunctions& gl, const std::string& name, const std::vector<GlShaderStage>& stages,
                     const char* version)
    : m_gl(gl) {
    m_id = gl.CreateProgram();
    std::vector<GLuint> shaders;
    auto cleanup = [&] {
        for (GLuint s : shaders) gl.DeleteShader(s);
    };
    for (const GlShaderStage& stage : stages) {
        std::string text = std::string(version) + "\n";
        for (const std::string& s : stage.sources) text += s + "\n";
        GLuint shader = gl.CreateShader(stage.type);
        shaders.push_back(shader);
        const char* src = text.c_str();
        gl.ShaderSource(shader, 1, &src, nullptr);
        gl.CompileShader(shader);
        GLint ok = 0;
        gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[4096] = {};
            gl.GetShaderInfoLog(shader, sizeof(log), nullptr, log);
            cleanup();
            gl.DeleteProgram(m_id);
            throw Error("GLSL program '" + name + "': " + stageName(stage.type) +
                        " shader does not compile: " + oneLine(log));
        }
        gl.AttachShader(m_id, shader);
    }
    gl.LinkProgram(m_id);
    cleanup();
    GLint ok = 0;
    gl.GetProgramiv(m_id, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        gl.GetProgramInfoLog(m_id, sizeof(log), nullptr, log);
        gl.DeleteProgram(m_id);
        throw Error("GLSL program '" + name + "' does not link: " + oneLine(log));
    }
}

GlProgram::~GlProgram() {
    m_gl.DeleteProgram(m_id);
}

}  // namespace tyndall
