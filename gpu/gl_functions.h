#pragma once
// The OpenGL entry points Tyndall calls, fetched at run time into one table through the context's
// getProcAddress (eglGetProcAddress, OSMesaGetProcAddress, or the viewer window's
// glfwGetProcAddress). Nothing in Tyndall calls a linked gl* symbol: the binary links libEGL only
// and loads OSMesa with dlopen, so libGL / libOpenGL and OSMesa never meet in one process (their
// dispatch tables would clash), and a machine without GL libraries still runs `--gpu off`. Call as
// `gl.DrawArrays(...)`; valid only on the thread whose context loaded the table.
#include <GL/glcorearb.h>

#include <functional>

namespace tyndall {

// One line per entry point: X(type of the pointer, name without the "gl" prefix).
// OpenGL 3.3 core: what the viewer's image display needs, and the splatter's plain calls.
#define TYNDALL_GL33_FUNCTIONS(X)                        \
    X(PFNGLGETERRORPROC, GetError)                       \
    X(PFNGLGETSTRINGPROC, GetString)                     \
    X(PFNGLGETSTRINGIPROC, GetStringi)                   \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                 \
    X(PFNGLGETINTEGER64VPROC, GetInteger64v)             \
    X(PFNGLENABLEPROC, Enable)                           \
    X(PFNGLDISABLEPROC, Disable)                         \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                     \
    X(PFNGLBLENDEQUATIONPROC, BlendEquation)             \
    X(PFNGLVIEWPORTPROC, Viewport)                       \
    X(PFNGLSCISSORPROC, Scissor)                         \
    X(PFNGLFINISHPROC, Finish)                           \
    X(PFNGLCLEARPROC, Clear)                             \
    X(PFNGLCLEARCOLORPROC, ClearColor)                   \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                 \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                   \
    X(PFNGLREADPIXELSPROC, ReadPixels)                   \
    X(PFNGLCREATESHADERPROC, CreateShader)               \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)               \
    X(PFNGLCOMPILESHADERPROC, CompileShader)             \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                 \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)       \
    X(PFNGLDELETESHADERPROC, DeleteShader)               \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)             \
    X(PFNGLATTACHSHADERPROC, AttachShader)               \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                 \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)               \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)     \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)             \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                   \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)   \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                     \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                     \
    X(PFNGLGENTEXTURESPROC, GenTextures)                 \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                 \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)             \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                   \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)             \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)           \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)         \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)   \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)         \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                   \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)             \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)           \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)         \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)   \
    X(PFNGLGENQUERIESPROC, GenQueries)                   \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)             \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                   \
    X(PFNGLENDQUERYPROC, EndQuery)                       \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

// OpenGL 4.5 core on top: direct state access, compute, program resources (the splatter).
#define TYNDALL_GL45_FUNCTIONS(X)                                        \
    X(PFNGLDEBUGMESSAGECALLBACKPROC, DebugMessageCallback)               \
    X(PFNGLGETPROGRAMRESOURCEINDEXPROC, GetProgramResourceIndex)         \
    X(PFNGLGETPROGRAMRESOURCEIVPROC, GetProgramResourceiv)               \
    X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                       \
    X(PFNGLPROGRAMUNIFORM1UIPROC, ProgramUniform1ui)                     \
    X(PFNGLPROGRAMUNIFORM1FPROC, ProgramUniform1f)                       \
    X(PFNGLPROGRAMUNIFORM2IPROC, ProgramUniform2i)                       \
    X(PFNGLPROGRAMUNIFORM3FPROC, ProgramUniform3f)                       \
    X(PFNGLPROGRAMUNIFORM4FPROC, ProgramUniform4f)                       \
    X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                             \
    X(PFNGLNAMEDBUFFERDATAPROC, NamedBufferData)                         \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                   \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)             \
    X(PFNGLCREATETEXTURESPROC, CreateTextures)                           \
    X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                       \
    X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                   \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)         \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)   \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus) \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)         \
    X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                   \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                         \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)

/// Which OpenGL core version a context must offer: every entry point of it must be found.
enum class GlVersion { Core33, Core45 };

struct GlFunctions {
#define TYNDALL_GL_DECLARE(type, name) type name = nullptr;
    TYNDALL_GL33_FUNCTIONS(TYNDALL_GL_DECLARE)
    TYNDALL_GL45_FUNCTIONS(TYNDALL_GL_DECLARE)
#undef TYNDALL_GL_DECLARE

    /// Fetches every entry point through `getProc` (called with the full "glName"); throws Error
    /// naming `who` and the first entry point of `need` it could not find. Entry points beyond
    /// `need` that are missing stay nullptr.
    void load(const std::function<void*(const char*)>& getProc, const char* who, GlVersion need = GlVersion::Core45);
};

}  // namespace tyndall
