#pragma once
// A linked GLSL program built from pieces: each stage is the version line ("#version 450 core"
// for the splatter, "#version 330 core" for the viewer's display) followed by the named embedded
// sources (gpu/shaders/) or literal texts, in order (GLSL has no #include).
#include <string>
#include <utility>
#include <vector>

#include "gpu/gl_functions.h"

namespace tyndall {

struct GlShaderStage {
    GLenum type;                       ///< GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER
    std::vector<std::string> sources;  ///< texts, concatenated after the #version line
};

class GlProgram {
public:
    /// Compiles and links; throws Error naming `name`, the stage and the driver's log.
    GlProgram(const GlFunctions& gl, const std::string& name, const std::vector<GlShaderStage>& stages,
              const char* version = "#version 450 core");
    ~GlProgram();
    GlProgram(const GlProgram&) = delete;
    GlProgram& operator=(const GlProgram&) = delete;

    GLuint id() const { return m_id; }

private:
    const GlFunctions& m_gl;
    GLuint m_id = 0;
};

/// The embedded source of gpu/shaders/<name>, for GlShaderStage::sources.
std::string glsl(const char* name);

}  // namespace tyndall
