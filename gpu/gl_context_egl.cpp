// EGL backend of GlContext: a hardware EGL device first, then Mesa's surfaceless platform.
// libEGL is loaded with dlopen, like OSMesa, so the binary starts (and `--gpu off` renders) on a
// machine without any GL library.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "gpu/gl_context.h"

namespace tyndall {

namespace {

// The EGL 1.4 entry points used here; the extension ones come through getProcAddress.
#define TYNDALL_EGL_FUNCTIONS(X) \
    X(GetProcAddress)            \
    X(GetError)                  \
    X(QueryString)               \
    X(Initialize)                \
    X(BindAPI)                   \
    X(ChooseConfig)              \
    X(CreateContext)             \
    X(MakeCurrent)               \
    X(DestroyContext)            \
    X(ReleaseThread)

struct EglApi {
    void* library = nullptr;
#define TYNDALL_EGL_DECLARE(name) decltype(&egl##name) name = nullptr;
    TYNDALL_EGL_FUNCTIONS(TYNDALL_EGL_DECLARE)
#undef TYNDALL_EGL_DECLARE
};

/// Loaded once per process and never unloaded; null with the reason when there is no libEGL.
const EglApi* eglApi(std::string* whyNot) {
    static const EglApi api = [] {
        EglApi a;
        for (const std::string& name : detail::glLibraryNames("TYNDALL_EGL_LIBRARY", {"libEGL.so.1", "libEGL.so"}))
            if ((a.library = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL))) break;
        if (!a.library) return a;
#define TYNDALL_EGL_LOAD(name) a.name = reinterpret_cast<decltype(a.name)>(dlsym(a.library, "egl" #name));
        TYNDALL_EGL_FUNCTIONS(TYNDALL_EGL_LOAD)
#undef TYNDALL_EGL_LOAD
        return a;
    }();
    if (!api.library) {
        *whyNot = detail::glLibraryNames("TYNDALL_EGL_LIBRARY", {"libEGL.so.1"})[0] +
                  " not found (install libegl1 and libgl1-mesa-dri)";
        return nullptr;
    }
#define TYNDALL_EGL_CHECK(name)             \
    if (!api.name) {                        \
        *whyNot = "libEGL lacks egl" #name; \
        return nullptr;                     \
    }
    TYNDALL_EGL_FUNCTIONS(TYNDALL_EGL_CHECK)
#undef TYNDALL_EGL_CHECK
    return &api;
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

std::string eglErrorName(EGLint e) {
    switch (e) {
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        default:
            return "EGL error " + std::to_string(e);
    }
}

class EglContext : public GlContext {
public:
    EglContext(const EglApi& egl, EGLDisplay display, EGLContext context, const std::string& name)
        : m_egl(egl), m_display(display), m_context(context) {
        try {
            finishSetup([&egl](const char* f) { return reinterpret_cast<void*>(egl.GetProcAddress(f)); }, name);
        } catch (...) {
            release();
            throw;
        }
    }
    ~EglContext() override { release(); }

private:
    void release() {
        // The display is shared by every context on it in this process: release, never terminate.
        m_egl.MakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        m_egl.DestroyContext(m_display, m_context);
        m_egl.ReleaseThread();
    }

    const EglApi& m_egl;
    EGLDisplay m_display;
    EGLContext m_context;
};

/// A 4.5 core context on `display`, current on this thread, or null with the reason.
std::unique_ptr<GlContext> contextOn(const EglApi& egl, EGLDisplay display, const std::string& name,
                                     std::string* whyNot) {
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY) {
        *whyNot = name + ": no display";
        return nullptr;
    }
    if (!egl.Initialize(display, &major, &minor)) {
        *whyNot = name + ": eglInitialize failed (" + eglErrorName(egl.GetError()) + ")";
        return nullptr;
    }
    const char* ext = egl.QueryString(display, EGL_EXTENSIONS);
    if (!hasExtension(ext, "EGL_KHR_surfaceless_context")) {
        *whyNot = name + ": no EGL_KHR_surfaceless_context";
        return nullptr;
    }
    if (!egl.BindAPI(EGL_OPENGL_API)) {
        *whyNot = name + ": no desktop OpenGL API";
        return nullptr;
    }
    EGLConfig config = nullptr;
    EGLint count = 0;
    const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    if (!egl.ChooseConfig(display, configAttribs, &config, 1, &count) || count == 0) {
        if (!hasExtension(ext, "EGL_KHR_no_config_context")) {
            *whyNot = name + ": no OpenGL config";
            return nullptr;
        }
        config = EGL_NO_CONFIG_KHR;
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
#ifndef NDEBUG
                                     EGL_CONTEXT_OPENGL_DEBUG,
                                     EGL_TRUE,
#endif
                                     EGL_NONE};
    EGLContext context = egl.CreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (context == EGL_NO_CONTEXT) {
        *whyNot = name + ": no OpenGL 4.5 core context (" + eglErrorName(egl.GetError()) + ")";
        return nullptr;
    }
    if (!egl.MakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        *whyNot = name + ": eglMakeCurrent failed (" + eglErrorName(egl.GetError()) + ")";
        egl.DestroyContext(display, context);
        return nullptr;
    }
    try {
        return std::make_unique<EglContext>(egl, display, context, name);
    } catch (const Error& e) {  // the constructor released the context
        *whyNot = e.what();
        return nullptr;
    }
}

}  // namespace

namespace detail {

std::unique_ptr<GlContext> createEglContext(std::string* whyNot) {
    const EglApi* api = eglApi(whyNot);
    if (!api) return nullptr;
    const EglApi& egl = *api;
    const char* clientExt = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(egl.GetProcAddress("eglGetPlatformDisplayEXT"));
    std::vector<std::string> reasons;
    std::string why;

    // Hardware devices first: on a GPU machine this is the GPU even without a display server.
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(egl.GetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(egl.GetProcAddress("eglQueryDeviceStringEXT"));
    if (getPlatformDisplay && queryDevices && queryDeviceString && hasExtension(clientExt, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[16];
        EGLint n = 0;
        if (queryDevices(16, devices, &n)) {
            for (EGLint i = 0; i < n; ++i) {
                const char* devExt = queryDeviceString(devices[i], EGL_EXTENSIONS);
                if (hasExtension(devExt, "EGL_MESA_device_software")) continue;  // llvmpipe: surfaceless below
                EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (auto ctx = contextOn(egl, d, "EGL device " + std::to_string(i), &why)) return ctx;
                reasons.push_back(why);
            }
        }
    }
    if (getPlatformDisplay && hasExtension(clientExt, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (auto ctx = contextOn(egl, d, "EGL surfaceless", &why)) return ctx;
        reasons.push_back(why);
    } else {
        reasons.push_back("no EGL_MESA_platform_surfaceless");
    }
    *whyNot = reasons.empty() ? "no EGL display" : reasons.front();
    for (size_t i = 1; i < reasons.size(); ++i) *whyNot += ", " + reasons[i];
    return nullptr;
}

}  // namespace detail

}  // namespace tyndall
