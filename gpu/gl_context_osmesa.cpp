// OSMesa backend of GlContext, loaded with dlopen so that libOSMesa's gl* exports never meet
// another GL library's at link time (gl_functions.h says why); every entry point comes from OSMesaGetProcAddress.
// Order matters: glcorearb.h (through gl_context.h) must come before osmesa.h's gl.h, which
// would hide the GL 1.x function-pointer typedefs the function table uses.
// clang-format off
#include "gpu/gl_context.h"

#include <GL/osmesa.h>
// clang-format on
#include <dlfcn.h>

#include "core/error.h"

namespace tyndall {

namespace {

struct OSMesaApi {
    void* library = nullptr;
    decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&OSMesaDestroyContext) destroyContext = nullptr;
    decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
};

/// Loaded once per process and never unloaded (Mesa keeps per-process state).
const OSMesaApi* osmesaApi(std::string* whyNot) {
    static const OSMesaApi api = [] {
        OSMesaApi a;
        for (const std::string& name :
             detail::glLibraryNames("TYNDALL_OSMESA_LIBRARY", {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}))
            if ((a.library = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL))) break;
        if (!a.library) return a;
        a.createContextAttribs =
            reinterpret_cast<decltype(a.createContextAttribs)>(dlsym(a.library, "OSMesaCreateContextAttribs"));
        a.makeCurrent = reinterpret_cast<decltype(a.makeCurrent)>(dlsym(a.library, "OSMesaMakeCurrent"));
        a.destroyContext = reinterpret_cast<decltype(a.destroyContext)>(dlsym(a.library, "OSMesaDestroyContext"));
        a.getProcAddress = reinterpret_cast<decltype(a.getProcAddress)>(dlsym(a.library, "OSMesaGetProcAddress"));
        return a;
    }();
    if (!api.library) {
        *whyNot =
            detail::glLibraryNames("TYNDALL_OSMESA_LIBRARY", {"libOSMesa.so.8"})[0] + " not found (install libosmesa6)";
        return nullptr;
    }
    if (!api.createContextAttribs || !api.makeCurrent || !api.destroyContext || !api.getProcAddress) {
        *whyNot = "libOSMesa lacks OSMesaCreateContextAttribs/OSMesaGetProcAddress";
        return nullptr;
    }
    return &api;
}

class OSMesaGlContext : public GlContext {
public:
    OSMesaGlContext(const OSMesaApi& api, OSMesaContext context) : m_api(api), m_context(context) {
        // OSMesa needs a colour buffer to make a context current; rendering goes to FBOs.
        if (!m_api.makeCurrent(m_context, m_dummy, GL_UNSIGNED_BYTE, 1, 1)) {
            m_api.destroyContext(m_context);
            throw Error("OSMesaMakeCurrent failed");
        }
        const OSMesaApi* a = &m_api;
        try {
            finishSetup([a](const char* f) { return reinterpret_cast<void*>(a->getProcAddress(f)); }, "OSMesa");
        } catch (...) {
            release();
            throw;
        }
    }
    ~OSMesaGlContext() override { release(); }

private:
    void release() {
        m_api.makeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
        m_api.destroyContext(m_context);
    }

    const OSMesaApi& m_api;
    OSMesaContext m_context;
    unsigned char m_dummy[4] = {};
};

}  // namespace

namespace detail {

std::unique_ptr<GlContext> createOSMesaContext(std::string* whyNot) {
    const OSMesaApi* api = osmesaApi(whyNot);
    if (!api) return nullptr;
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    OSMesaContext context = api->createContextAttribs(attribs, nullptr);
    if (!context) {
        *whyNot = "OSMesaCreateContextAttribs gave no 4.5 core context";
        return nullptr;
    }
    try {
        return std::make_unique<OSMesaGlContext>(*api, context);
    } catch (const Error& e) {
        *whyNot = e.what();
        return nullptr;
    }
}

}  // namespace detail

}  // namespace tyndall
