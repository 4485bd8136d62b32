#include "gpu/gl_functions.h"

#include <string>

#include "core/error.h"

namespace tyndall {

void GlFunctions::load(const std::function<void*(const char*)>& getProc, const char* who, GlVersion need) {
    auto missing = [&](const char* name, const char* version) {
        return Error(std::string(who) + ": OpenGL entry point gl" + name + " is missing (need OpenGL " + version +
                     " core)");
    };
#define TYNDALL_GL_LOAD(type, name) name = reinterpret_cast<type>(getProc("gl" #name));
#define TYNDALL_GL_REQUIRE(type, name, version) \
    if (!name) throw missing(#name, version);
#define TYNDALL_GL_REQUIRE33(type, name) TYNDALL_GL_REQUIRE(type, name, need == GlVersion::Core45 ? "4.5" : "3.3")
#define TYNDALL_GL_REQUIRE45(type, name) TYNDALL_GL_REQUIRE(type, name, "4.5")
    TYNDALL_GL33_FUNCTIONS(TYNDALL_GL_LOAD)
    TYNDALL_GL45_FUNCTIONS(TYNDALL_GL_LOAD)
    TYNDALL_GL33_FUNCTIONS(TYNDALL_GL_REQUIRE33)
    if (need == GlVersion::Core45) TYNDALL_GL45_FUNCTIONS(TYNDALL_GL_REQUIRE45)
#undef TYNDALL_GL_REQUIRE45
#undef TYNDALL_GL_REQUIRE33
#undef TYNDALL_GL_REQUIRE
#undef TYNDALL_GL_LOAD
}

}  // namespace tyndall
