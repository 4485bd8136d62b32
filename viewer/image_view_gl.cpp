#include "viewer/image_view_gl.h"

#include <GL/glcorearb.h>

#include <vector>

#include "core/error.h"
#include "gpu/gl_functions.h"
#include "gpu/gl_program.h"

namespace tyndall {

namespace {
const char* kVertex = R"(
out vec2 uv;
void main() {
    // One triangle covering the viewport; uv (0,0) at the image's top-left.
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    uv = vec2(p.x, 1.0 - p.y);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";
// The same display transform as toneMapChannel (core/image_io.cpp): exposure, Narkowicz's ACES
// fit, sRGB encoding.
const char* kFragment = R"(
in vec2 uv;
out vec4 color;
uniform sampler2D image;
uniform float exposure;
float srgb(float c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055; }
float tone(float linear) {
    float x = max(0.0, linear * exposure);
    if (isnan(x) || isinf(x)) x = 0.0;
    float mapped = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    return srgb(clamp(mapped, 0.0, 1.0));
}
void main() {
    vec3 c = texture(image, uv).rgb;
    color = vec4(tone(c.r), tone(c.g), tone(c.b), 1.0);
}
)";

}  // namespace

ImageViewGl::ImageViewGl(GlProcLoader load) : m_gl(std::make_unique<GlFunctions>()) {
    m_gl->load([load](const char* name) { return load(name); }, "viewer: the window's OpenGL", GlVersion::Core33);
    const GlFunctions& gl = *m_gl;
    m_program = std::make_unique<GlProgram>(
        gl, "viewer display", std::vector<GlShaderStage>{{GL_VERTEX_SHADER, {kVertex}}, {GL_FRAGMENT_SHADER, {kFragment}}},
        "#version 330 core");
    m_exposureLocation = gl.GetUniformLocation(m_program->id(), "exposure");
    gl.GenVertexArrays(1, &m_vao);
    gl.GenTextures(2, m_texture);
    for (unsigned t : m_texture) {
        gl.BindTexture(GL_TEXTURE_2D, t);
        // Nearest: a preview's pixels show as blocks rather than a blur that looks converged.
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
}

ImageViewGl::~ImageViewGl() {
    m_gl->DeleteTextures(2, m_texture);
    m_gl->DeleteVertexArrays(1, &m_vao);
}

void ImageViewGl::upload(int slot, const Image& image) {
    const GlFunctions& gl = *m_gl;
    gl.BindTexture(GL_TEXTURE_2D, m_texture[slot]);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, image.width, image.height, 0, GL_RGB, GL_FLOAT, image.pixels.data());
    m_hasImage[slot] = true;
}

void ImageViewGl::clear(int w, int h) {
    const GlFunctions& gl = *m_gl;
    gl.Viewport(0, 0, w, h);
    gl.Disable(GL_SCISSOR_TEST);
    gl.ClearColor(0.12f, 0.12f, 0.13f, 1.0f);
    gl.Clear(GL_COLOR_BUFFER_BIT);
}

void ImageViewGl::draw(int slot, int x, int y, int w, int h, float exposure) {
    if (!m_hasImage[slot] || w <= 0 || h <= 0) return;
    const GlFunctions& gl = *m_gl;
    gl.Viewport(x, y, w, h);
    gl.Disable(GL_BLEND);
    gl.UseProgram(m_program->id());
    gl.Uniform1f(m_exposureLocation, exposure);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, m_texture[slot]);
    gl.BindVertexArray(m_vao);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.BindVertexArray(0);
    gl.UseProgram(0);
}

std::string ImageViewGl::readPixels(int w, int h) {
    const GlFunctions& gl = *m_gl;
    std::string rows(size_t(w) * h * 4, '\0'), out(rows.size(), '\0');
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadBuffer(GL_BACK);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    for (int y = 0; y < h; ++y)  // GL's first row is the bottom one
        std::copy_n(rows.data() + size_t(h - 1 - y) * w * 4, size_t(w) * 4, out.data() + size_t(y) * w * 4);
    return out;
}

}  // namespace tyndall
