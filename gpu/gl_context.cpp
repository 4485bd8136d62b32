#include "gpu/gl_context.h"

#include <cstdio>
#include <cstdlib>

#include "core/error.h"

namespace tyndall {

namespace {
#ifndef NDEBUG
void APIENTRY debugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                           const GLchar* message, const void* user) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    std::fprintf(stderr, "tyndall: GL debug: %s\n", message);
}
#endif
}  // namespace

std::unique_ptr<GlContext> GlContext::create(GlBackend backend) {
    std::string egl = "not tried", osmesa = "not tried";
    if (backend != GlBackend::OSMesa)
        if (auto ctx = detail::createEglContext(&egl)) return ctx;
    if (backend != GlBackend::Egl)
        if (auto ctx = detail::createOSMesaContext(&osmesa)) return ctx;
    throw Error("no OpenGL 4.5 core context: EGL: " + egl + "; OSMesa: " + osmesa);
}

void GlContext::finishSetup(const std::function<void*(const char*)>& getProc, const std::string& backendName) {
    m_thread = std::this_thread::get_id();
    m_gl.load(getProc, backendName.c_str());
    auto str = [&](GLenum e) {
        const GLubyte* s = m_gl.GetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    m_renderer = str(GL_RENDERER);
    m_description = backendName + ", " + m_renderer + ", " + str(GL_VERSION);
    GLint major = 0, minor = 0;
    m_gl.GetIntegerv(GL_MAJOR_VERSION, &major);
    m_gl.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45) throw Error(backendName + ": got OpenGL " + str(GL_VERSION) + ", need 4.5 core");
#ifndef NDEBUG
    m_gl.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    m_gl.DebugMessageCallback(debugMessage, nullptr);
#endif
}

std::vector<std::string> detail::glLibraryNames(const char* envVar, std::vector<std::string> defaults) {
    const char* chosen = std::getenv(envVar);
    if (chosen && *chosen) return {chosen};
    return defaults;
}

bool GlContext::isSoftware() const {
    for (const char* name : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
        if (m_renderer.find(name) != std::string::npos) return true;
    return false;
}

void GlContext::requireCurrentThread() const {
    if (std::this_thread::get_id() != m_thread)
        throw Error("OpenGL context used from a thread other than the one that created it (" + m_description + ")");
}

}  // namespace tyndall
