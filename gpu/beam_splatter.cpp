#include "gpu/beam_splatter.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/timing.h"
#include "gpu/gl_layout.h"
#include "gpu/gl_program.h"
#include "gpu/media_table.h"

namespace tyndall {

namespace {

constexpr int kVerticesPerBeam = 6;
constexpr uint64_t kBeamsPerDraw = 1u << 24;  // keeps the vertex count of one draw in GLsizei

bool hasExtension(const GlFunctions& gl, const char* name) {
    GLint n = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i)
        if (std::strcmp(reinterpret_cast<const char*>(gl.GetStringi(GL_EXTENSIONS, GLuint(i))), name) == 0) return true;
    return false;
}

GlSplatFrame splatFrame(const Camera& cam, const PrimarySegments& primary, const PhotonMap& photons) {
    GlSplatFrame f{};
    auto vec3 = [](const Vec3& v) { return shader::vec3{v.x, v.y, v.z}; };
    f.cameraPosition = vec3(cam.position);
    f.cameraRight = vec3(cam.right);
    f.cameraUp = vec3(cam.up);
    f.cameraForward = vec3(cam.forward);
    // The same float expressions as beamFootprint() in cpu/beam_rasterizer.cpp.
    const float tanHalf = std::tan(0.5f * cam.yFov);
    f.tanHalfX = tanHalf * float(primary.width) / float(primary.height);
    f.tanHalfY = tanHalf;
    f.focalPixels = 0.5f * float(primary.height) / tanHalf;
    f.lensRadius = cam.lensRadius;
    f.focusDistance = cam.focusDistance;
    f.filmSize = {primary.width, primary.height};
    f.freeFlightsPerRay = primary.freeFlightsPerRay;
    f.freeFlightsPerBeam = photons.freeFlightsPerBeam;
    f.beamCount = int32_t(photons.beams.size());
    return f;
}
}  // namespace

GlSplatStats& GlSplatStats::operator+=(const GlSplatStats& o) {
    uploadSeconds += o.uploadSeconds;
    drawSeconds += o.drawSeconds;
    readbackSeconds += o.readbackSeconds;
    fragments += o.fragments;
    beams += o.beams;
    return *this;
}

struct GlBeamSplatter::Buffers {
    const GlFunctions& gl;
    std::unique_ptr<GlProgram> program;
    bool programHasGridMedia = false;
    GLuint frame = 0, rays = 0, rayFreeFlights = 0, beams = 0, beamFreeFlights = 0, media = 0, volumes = 0, voxels = 0;
    GLuint vertexArray = 0, target = 0, framebuffer = 0, query = 0;
    int width = 0, height = 0;
    std::vector<float> readback;

    explicit Buffers(const GlFunctions& g) : gl(g) {
        GLuint ids[8];
        gl.CreateBuffers(8, ids);
        frame = ids[0];
        rays = ids[1];
        rayFreeFlights = ids[2];
        beams = ids[3];
        beamFreeFlights = ids[4];
        media = ids[5];
        volumes = ids[6];
        voxels = ids[7];
        gl.CreateVertexArrays(1, &vertexArray);
        gl.GenQueries(1, &query);
    }
    ~Buffers() {
        GLuint ids[8] = {frame, rays, rayFreeFlights, beams, beamFreeFlights, media, volumes, voxels};
        gl.DeleteBuffers(8, ids);
        gl.DeleteVertexArrays(1, &vertexArray);
        gl.DeleteQueries(1, &query);
        gl.DeleteFramebuffers(1, &framebuffer);
        gl.DeleteTextures(1, &target);
    }
    /// Uploads `bytes` (an empty array becomes 64 zero bytes: every declared buffer is bound).
    void upload(GLuint buffer, const void* data, size_t bytes) {
        static const float kZeros[16] = {};
        if (bytes == 0)
            gl.NamedBufferData(buffer, sizeof(kZeros), kZeros, GL_STREAM_DRAW);
        else
            gl.NamedBufferData(buffer, GLsizeiptr(bytes), data, GL_STREAM_DRAW);
    }
};

GlBeamSplatter::GlBeamSplatter(GlContext& context, const Scene& scene)
    : m_context(context), m_gl(context.gl()), m_scene(scene) {
    m_context.requireCurrentThread();
    GLint vertexBlocks = 0, fragmentBlocks = 0;
    m_gl.GetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &vertexBlocks);
    m_gl.GetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &fragmentBlocks);
    if (vertexBlocks < 2 || fragmentBlocks < 7)
        throw Error("GL splatter: " + m_context.description() + " has " + std::to_string(vertexBlocks) + " vertex / " +
                    std::to_string(fragmentBlocks) + " fragment shader storage blocks, needs 2 / 7");
    GLint64 blockSize = 0;
    m_gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &blockSize);
    m_maxVoxels = size_t(blockSize) / sizeof(float);
    m_canCountFragments = hasExtension(m_gl, "GL_ARB_pipeline_statistics_query");

    m_buffers = std::make_unique<Buffers>(m_gl);
    reloadMedia();
}

GlBeamSplatter::~GlBeamSplatter() = default;

void GlBeamSplatter::reloadMedia() {
    m_context.requireCurrentThread();
    GlMediaTable table = buildMediaTable(m_scene, m_maxVoxels);
    Buffers& b = *m_buffers;
    const bool grid = !table.volumes.empty();
    if (!b.program || b.programHasGridMedia != grid) {
        std::string define = std::string("#define TYNDALL_GRID_MEDIA ") + (grid ? "1" : "0");
        b.program = std::make_unique<GlProgram>(
            m_gl, "beam splat",
            std::vector<GlShaderStage>{
                {GL_VERTEX_SHADER, {define, glsl("gl_layout.h"), glsl("beam_footprint.glsl"), glsl("beam_splat.vert")}},
                {GL_FRAGMENT_SHADER,
                 {define, glsl("gl_layout.h"), glsl("beam_estimator.glsl"), glsl("media.glsl"),
                  glsl("pixel_radiance.glsl"), glsl("beam_splat.frag")}}});
        b.programHasGridMedia = grid;
    }
    b.upload(b.media, table.media.data(), table.media.size() * sizeof(GlMedium));
    b.upload(b.volumes, table.volumes.data(), table.volumes.size() * sizeof(GlVolume));
    b.upload(b.voxels, table.voxels.data(), table.voxels.size() * sizeof(float));
}

bool GlBeamSplatter::countFragments(bool on) {
    m_countFragments = on && m_canCountFragments;
    return m_countFragments == on;
}

void GlBeamSplatter::resizeTarget(int width, int height) {
    Buffers& b = *m_buffers;
    if (b.width == width && b.height == height) return;
    m_gl.DeleteFramebuffers(1, &b.framebuffer);
    m_gl.DeleteTextures(1, &b.target);
    m_gl.CreateTextures(GL_TEXTURE_2D, 1, &b.target);
    m_gl.TextureStorage2D(b.target, 1, GL_RGBA32F, width, height);
    m_gl.CreateFramebuffers(1, &b.framebuffer);
    m_gl.NamedFramebufferTexture(b.framebuffer, GL_COLOR_ATTACHMENT0, b.target, 0);
    if (m_gl.CheckNamedFramebufferStatus(b.framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("GL splatter: cannot render to a " + std::to_string(width) + "x" + std::to_string(height) +
                    " RGBA32F target on " + m_context.description());
    b.width = width;
    b.height = height;
    b.readback.resize(size_t(width) * height * 4);
}

Image GlBeamSplatter::splat(const PrimarySegments& primary, const PhotonMap& photons, GlSplatStats* stats) {
    m_context.requireCurrentThread();
    const int w = primary.width, h = primary.height;
    const size_t pixels = size_t(w) * size_t(h);
    TYNDALL_CHECK(w > 0 && h > 0 && primary.rays.size() == pixels,
                  "GL splatter: primary segments do not match their size");
    TYNDALL_CHECK(primary.freeFlights.size() == pixels * size_t(primary.freeFlightsPerRay),
                  "GL splatter: per-pixel free flights do not match the image");
    TYNDALL_CHECK(photons.freeFlights.size() == photons.beams.size() * size_t(photons.freeFlightsPerBeam),
                  "GL splatter: per-beam free flights do not match the beams");
    const GlFunctions& gl = m_gl;
    Buffers& b = *m_buffers;
    GlSplatStats local;
    local.beams = photons.beams.size();

    auto t0 = Clock::now();
    resizeTarget(w, h);
    GlSplatFrame frame = splatFrame(m_scene.camera, primary, photons);
    b.upload(b.frame, &frame, sizeof(frame));
    b.upload(b.rays, primary.rays.data(), pixels * sizeof(PrimaryRay));
    b.upload(b.rayFreeFlights, primary.freeFlights.data(), primary.freeFlights.size() * sizeof(float));
    b.upload(b.beams, photons.beams.data(), photons.beams.size() * sizeof(PhotonBeam));
    b.upload(b.beamFreeFlights, photons.freeFlights.data(), photons.freeFlights.size() * sizeof(float));
    gl.BindBufferBase(GL_UNIFORM_BUFFER, kBindFrame, b.frame);
    const std::pair<int, GLuint> storage[] = {{kBindPrimaryRays, b.rays}, {kBindRayFreeFlights, b.rayFreeFlights},
                                              {kBindBeams, b.beams},      {kBindBeamFreeFlights, b.beamFreeFlights},
                                              {kBindMedia, b.media},      {kBindVolumes, b.volumes},
                                              {kBindVoxels, b.voxels}};
    for (const auto& [binding, buffer] : storage) gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer);
    local.uploadSeconds = secondsSince(t0);

    auto t1 = Clock::now();
    const float zero[4] = {0, 0, 0, 0};
    gl.ClearNamedFramebufferfv(b.framebuffer, GL_COLOR, 0, zero);
    gl.BindFramebuffer(GL_FRAMEBUFFER, b.framebuffer);
    gl.Viewport(0, 0, w, h);
    // A render region: fragments there only (GL's rows run bottom-up); the rest stays cleared.
    const PixelRegion region = primary.region.whole() ? PixelRegion{0, 0, w, h} : primary.region;
    gl.Enable(GL_SCISSOR_TEST);
    gl.Scissor(region.x, h - region.y - region.height, region.width, region.height);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Enable(GL_BLEND);
    gl.BlendEquation(GL_FUNC_ADD);
    gl.BlendFunc(GL_ONE, GL_ONE);
    gl.UseProgram(b.program->id());
    gl.BindVertexArray(b.vertexArray);
    if (m_countFragments) gl.BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, b.query);
    for (uint64_t first = 0; first < photons.beams.size(); first += kBeamsPerDraw) {
        uint64_t count = std::min<uint64_t>(kBeamsPerDraw, photons.beams.size() - first);
        gl.DrawArrays(GL_TRIANGLES, GLint(first * kVerticesPerBeam), GLsizei(count * kVerticesPerBeam));
    }
    if (m_countFragments) gl.EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
    gl.Disable(GL_SCISSOR_TEST);
    gl.Finish();
    local.drawSeconds = secondsSince(t1);

    auto t2 = Clock::now();
    if (m_countFragments) gl.GetQueryObjectui64v(b.query, GL_QUERY_RESULT, &local.fragments);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, b.framebuffer);
    gl.NamedFramebufferReadBuffer(b.framebuffer, GL_COLOR_ATTACHMENT0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, b.readback.data());
    GLenum error = gl.GetError();
    if (error != GL_NO_ERROR)
        throw Error("GL splatter: OpenGL error 0x" +
                    [&] {
                        char hex[16];
                        std::snprintf(hex, sizeof(hex), "%04x", unsigned(error));
                        return std::string(hex);
                    }() +
                    " on " + m_context.description());
    Image out(w, h);
    for (int y = 0; y < h; ++y) {  // GL's rows run bottom-up
        const float* row = &b.readback[size_t(h - 1 - y) * w * 4];
        for (int x = 0; x < w; ++x) out.at(x, y) = Rgb(row[4 * x], row[4 * x + 1], row[4 * x + 2]);
    }
    local.readbackSeconds = secondsSince(t2);
    if (stats) *stats += local;
    return out;
}

}  // namespace tyndall
