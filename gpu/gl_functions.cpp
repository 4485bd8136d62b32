#include "gpu/gl_functions.h"

#include <string>

#include "core/error.h"

namespace tyndall {

void GlFunctions::load(const std::function<void*(const char*)>& getProc, const char* who) {
#define TYNDALL_GL_LOAD(type, name)                     \
    name = reinterpret_cast<type>(getProc("gl" #name)); \
    if (!name) throw Error(std::string(who) + ": OpenGL entry point gl" #name " is missing (need OpenGL 4.5 core)");
    TYNDALL_GL_FUNCTIONS(TYNDALL_GL_LOAD)
#undef TYNDALL_GL_LOAD
}

}  // namespace tyndall
