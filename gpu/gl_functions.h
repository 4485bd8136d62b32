#pragma once
// The OpenGL 4.5 core entry points the splatter uses, fetched at run time into a table through the
// context's getProcAddress (eglGetProcAddress or OSMesaGetProcAddress). Nothing in Tyndall calls
// a linked gl* symbol: the binary links libEGL only and loads OSMesa with dlopen, so libGL /
// libOpenGL and OSMesa never meet in one process (DEPS.md), and a machine without GL libraries
// still runs `--gpu off`. Call as `gl.DrawArrays(...)`; valid only on the thread whose context
// loaded the table.
#include <GL/glcorearb.h>

#include <functional>

namespace tyndall {

// One line per entry point: X(type of the pointer, name without the "gl" prefix).
#define TYNDALL_GL_FUNCTIONS(X)                                          \
    X(PFNGLGETERRORPROC, GetError)                                       \
    X(PFNGLGETSTRINGPROC, GetString)                                     \
    X(PFNGLGETSTRINGIPROC, GetStringi)                                   \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                 \
    X(PFNGLGETINTEGER64VPROC, GetInteger64v)                             \
    X(PFNGLENABLEPROC, Enable)                                           \
    X(PFNGLDISABLEPROC, Disable)                                         \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                                     \
    X(PFNGLBLENDEQUATIONPROC, BlendEquation)                             \
    X(PFNGLVIEWPORTPROC, Viewport)                                       \
    X(PFNGLFINISHPROC, Finish)                                           \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                 \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                   \
    X(PFNGLDEBUGMESSAGECALLBACKPROC, DebugMessageCallback)               \
    X(PFNGLCREATESHADERPROC, CreateShader)                               \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                               \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                             \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                 \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                       \
    X(PFNGLDELETESHADERPROC, DeleteShader)                               \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                             \
    X(PFNGLATTACHSHADERPROC, AttachShader)                               \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                 \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                               \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                     \
    X(PFNGLGETPROGRAMRESOURCEINDEXPROC, GetProgramResourceIndex)         \
    X(PFNGLGETPROGRAMRESOURCEIVPROC, GetProgramResourceiv)               \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                             \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                   \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                   \
    X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                       \
    X(PFNGLPROGRAMUNIFORM1UIPROC, ProgramUniform1ui)                     \
    X(PFNGLPROGRAMUNIFORM1FPROC, ProgramUniform1f)                       \
    X(PFNGLPROGRAMUNIFORM2IPROC, ProgramUniform2i)                       \
    X(PFNGLPROGRAMUNIFORM3FPROC, ProgramUniform3f)                       \
    X(PFNGLPROGRAMUNIFORM4FPROC, ProgramUniform4f)                       \
    X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                             \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                             \
    X(PFNGLNAMEDBUFFERDATAPROC, NamedBufferData)                         \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                   \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)             \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                           \
    X(PFNGLCREATETEXTURESPROC, CreateTextures)                           \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                           \
    X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                       \
    X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                   \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                   \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)         \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)   \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus) \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)         \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                         \
    X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                   \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                   \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                         \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                   \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                         \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                             \
    X(PFNGLGENQUERIESPROC, GenQueries)                                   \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                             \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                                   \
    X(PFNGLENDQUERYPROC, EndQuery)                                       \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

struct GlFunctions {
#define TYNDALL_GL_DECLARE(type, name) type name = nullptr;
    TYNDALL_GL_FUNCTIONS(TYNDALL_GL_DECLARE)
#undef TYNDALL_GL_DECLARE

    /// Fetches every entry point through `getProc` (called with the full "glName"); throws Error
    /// naming `who` and the first entry point it could not find.
    void load(const std::function<void*(const char*)>& getProc, const char* who);
};

}  // namespace tyndall
