#pragma once
// Shows a linear float image in the current OpenGL 3.3 core context: uploaded to a float texture,
// tone-mapped in a fragment shader with the same curve as the PNG writer (exposure, the ACES fit,
// sRGB: core/image_io.h toneMapChannel) and drawn into a viewport rectangle. The window's context
// only; entry points come from the window system's getProcAddress into gpu/'s table
// (gl_functions.h), so the binary links no libGL.
// Not thread-safe: the UI thread that owns the context.
#include <memory>
#include <string>

#include "core/image.h"

namespace tyndall {

struct GlFunctions;
class GlProgram;
using GlProcLoader = void* (*)(const char* name);

class ImageViewGl {
public:
    /// Loads the entry points and builds the shader; throws Error naming what is missing.
    explicit ImageViewGl(GlProcLoader load);
    ~ImageViewGl();
    ImageViewGl(const ImageViewGl&) = delete;
    ImageViewGl& operator=(const ImageViewGl&) = delete;

    /// Uploads `image` into texture slot `slot` (0 or 1: the compare view's halves).
    void upload(int slot, const Image& image);
    /// Draws slot `slot` tone-mapped with `exposure` into the framebuffer rectangle whose lower-left
    /// corner is (x, y) (GL window coordinates), size w x h; black when nothing was uploaded.
    void draw(int slot, int x, int y, int w, int h, float exposure);
    /// Clears the whole framebuffer of size w x h to dark grey.
    void clear(int w, int h);
    /// Reads the framebuffer (w x h, RGBA8, top row first) for screenshots.
    std::string readPixels(int w, int h);

private:
    std::unique_ptr<GlFunctions> m_gl;
    std::unique_ptr<GlProgram> m_program;  ///< after m_gl: destroyed before the table it calls through
    unsigned m_vao = 0;
    unsigned m_texture[2] = {0, 0};
    bool m_hasImage[2] = {false, false};
    int m_exposureLocation = -1;
};

}  // namespace tyndall
