#pragma once
// A headless OpenGL 4.5 core context for the beam splatter.
//
// Backends, tried in this order by GlBackend::Auto:
//   1. EGL on a hardware device (EGL_EXT_platform_device; the NVIDIA/AMD/Intel GPU when present),
//   2. EGL on Mesa's surfaceless platform (llvmpipe on a machine without a GPU),
//   3. OSMesa (libOSMesa.so.8; software, no EGL needed).
// Both libEGL and libOSMesa are loaded with dlopen, so a machine without them still runs Tyndall
// on the CPU. The environment variables TYNDALL_EGL_LIBRARY and TYNDALL_OSMESA_LIBRARY name the
// library to load instead of the usual sonames (a vendor's libEGL, or a test hiding GL).
// Rendering goes to framebuffer objects only; there is no window. All GL calls go through gl()
// (gpu/gl_functions.h).
//
// Threading: a context is current on the thread that created it and must be used and destroyed
// there only (requireCurrentThread() checks); the hybrid scheduler gives it a thread of its own.
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "gpu/gl_functions.h"

namespace tyndall {

enum class GlBackend { Auto, Egl, OSMesa };

class GlContext {
public:
    /// Creates a context current on the calling thread. Throws Error with one line listing why
    /// every backend tried failed ("no OpenGL 4.5 context: EGL: ...; OSMesa: ...").
    static std::unique_ptr<GlContext> create(GlBackend backend = GlBackend::Auto);
    virtual ~GlContext() = default;

    const GlFunctions& gl() const { return m_gl; }
    /// e.g. "EGL surfaceless, llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
    const std::string& description() const { return m_description; }
    /// The GL_RENDERER string.
    const std::string& renderer() const { return m_renderer; }
    /// True for CPU rasterizers (llvmpipe, softpipe, swrast), which share the CPU cores.
    bool isSoftware() const;
    /// Throws Error when called from a thread other than the context's.
    void requireCurrentThread() const;

protected:
    GlContext() = default;
    /// Loads the function table and the description; call once the context is current.
    void finishSetup(const std::function<void*(const char*)>& getProc, const std::string& backendName);

private:
    GlFunctions m_gl;
    std::string m_description;
    std::string m_renderer;
    std::thread::id m_thread;
};

namespace detail {
/// Backend factories (gl_context_egl.cpp, gl_context_osmesa.cpp): a current context, or null
/// with the reason in `whyNot`.
std::unique_ptr<GlContext> createEglContext(std::string* whyNot);
std::unique_ptr<GlContext> createOSMesaContext(std::string* whyNot);
/// The library names to dlopen, in order: the environment variable `envVar`'s value alone when
/// it is set and not empty, else `defaults`.
std::vector<std::string> glLibraryNames(const char* envVar, std::vector<std::string> defaults);
}  // namespace detail

}  // namespace tyndall
