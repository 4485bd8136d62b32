// gpu/gl_layout.h is compiled as C++ and as GLSL: the GL driver's own offsets, strides, sizes and
// binding points for every shared struct member (program interface queries on a program that
// uses every buffer) equal the C++ offsetof / sizeof of the same declarations.
#include "gpu/gl_layout.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "gpu/gl_context.h"
#include "gpu/gl_program.h"
#include "tests/gpu/gpu_test_util.h"

using namespace tyndall;

namespace {

// Statically uses every buffer and the uniform block, so all their members are active.
const char* kTouchEverything = R"(
layout(local_size_x = 1) in;
layout(std430, binding = 7) writeonly buffer Out { float outValue[]; };
void main() {
    float sum = rays[0].tMax + float(rays[0].medium) + rays[0].origin.x + rays[0].dir.x;
    sum += beams[0].tMax + beams[0].radius + float(beams[0].medium) + beams[0].origin.x + beams[0].dir.x +
           beams[0].power.x;
    sum += media[0].g + float(media[0].volume) + media[0].sigmaS.x + media[0].sigmaT.x;
    sum += volumes[0].worldToIndex[0].x + float(volumes[0].size.x) + float(volumes[0].offset);
    sum += rayFreeFlights[0] + beamFreeFlights[0] + voxels[0];
    sum += frame.cameraPosition.x + frame.tanHalfX + frame.cameraRight.x + frame.tanHalfY + frame.cameraUp.x +
           frame.focalPixels + frame.cameraForward.x + frame.lensRadius + float(frame.filmSize.x) +
           frame.focusDistance + float(frame.freeFlightsPerRay + frame.freeFlightsPerBeam + frame.beamCount);
    outValue[0] = sum;
}
)";

class GlLayout : public ::testing::Test {
protected:
    void SetUp() override {
        ctx = GlContext::create();
        program = std::make_unique<GlProgram>(
            ctx->gl(), "layout introspection",
            std::vector<GlShaderStage>{{GL_COMPUTE_SHADER, {glsl("gl_layout.h"), kTouchEverything}}});
    }
    /// One property of a named resource of `interface`; -1 when the driver does not list it.
    GLint property(GLenum interface, const std::string& name, GLenum prop) const {
        const GlFunctions& gl = ctx->gl();
        GLuint index = gl.GetProgramResourceIndex(program->id(), interface, name.c_str());
        if (index == GL_INVALID_INDEX) return -1;
        GLint value = -1;
        gl.GetProgramResourceiv(program->id(), interface, index, 1, &prop, 1, nullptr, &value);
        return value;
    }
    GLint offset(const std::string& member) const { return property(GL_BUFFER_VARIABLE, member, GL_OFFSET); }
    GLint stride(const std::string& member) const {
        return property(GL_BUFFER_VARIABLE, member, GL_TOP_LEVEL_ARRAY_STRIDE);
    }
    GLint binding(const std::string& block) const {
        return property(GL_SHADER_STORAGE_BLOCK, block, GL_BUFFER_BINDING);
    }

    std::unique_ptr<GlContext> ctx;
    std::unique_ptr<GlProgram> program;
};

}  // namespace

TEST_F(GlLayout, StorageBufferStructsMatchC) {
    namespace sh = tyndall::shader;
    EXPECT_EQ(stride("rays[0].origin"), GLint(sizeof(sh::PrimaryRay)));
    EXPECT_EQ(offset("rays[0].origin"), GLint(offsetof(sh::PrimaryRay, origin)));
    EXPECT_EQ(offset("rays[0].tMax"), GLint(offsetof(sh::PrimaryRay, tMax)));
    EXPECT_EQ(offset("rays[0].dir"), GLint(offsetof(sh::PrimaryRay, dir)));
    EXPECT_EQ(offset("rays[0].medium"), GLint(offsetof(sh::PrimaryRay, medium)));

    EXPECT_EQ(stride("beams[0].origin"), GLint(sizeof(sh::PhotonBeam)));
    EXPECT_EQ(offset("beams[0].tMax"), GLint(offsetof(sh::PhotonBeam, tMax)));
    EXPECT_EQ(offset("beams[0].dir"), GLint(offsetof(sh::PhotonBeam, dir)));
    EXPECT_EQ(offset("beams[0].radius"), GLint(offsetof(sh::PhotonBeam, radius)));
    EXPECT_EQ(offset("beams[0].power"), GLint(offsetof(sh::PhotonBeam, power)));
    EXPECT_EQ(offset("beams[0].medium"), GLint(offsetof(sh::PhotonBeam, medium)));

    EXPECT_EQ(stride("media[0].sigmaS"), GLint(sizeof(sh::Medium)));
    EXPECT_EQ(offset("media[0].g"), GLint(offsetof(sh::Medium, g)));
    EXPECT_EQ(offset("media[0].sigmaT"), GLint(offsetof(sh::Medium, sigmaT)));
    EXPECT_EQ(offset("media[0].volume"), GLint(offsetof(sh::Medium, volume)));

    EXPECT_EQ(stride("volumes[0].size"), GLint(sizeof(sh::Volume)));
    EXPECT_EQ(offset("volumes[0].worldToIndex[0]"), GLint(offsetof(sh::Volume, worldToIndex)));
    EXPECT_EQ(property(GL_BUFFER_VARIABLE, "volumes[0].worldToIndex[0]", GL_ARRAY_STRIDE), GLint(sizeof(sh::vec4)));
    EXPECT_EQ(offset("volumes[0].size"), GLint(offsetof(sh::Volume, size)));
    EXPECT_EQ(offset("volumes[0].offset"), GLint(offsetof(sh::Volume, offset)));

    EXPECT_EQ(property(GL_BUFFER_VARIABLE, "rayFreeFlights[0]", GL_ARRAY_STRIDE), GLint(sizeof(float)));
    EXPECT_EQ(property(GL_BUFFER_VARIABLE, "voxels[0]", GL_ARRAY_STRIDE), GLint(sizeof(float)));
}

TEST_F(GlLayout, BindingPointsMatchC) {
    EXPECT_EQ(binding("PrimaryRays"), kBindPrimaryRays);
    EXPECT_EQ(binding("RayFreeFlights"), kBindRayFreeFlights);
    EXPECT_EQ(binding("Beams"), kBindBeams);
    EXPECT_EQ(binding("BeamFreeFlights"), kBindBeamFreeFlights);
    EXPECT_EQ(binding("Media"), kBindMedia);
    EXPECT_EQ(binding("Volumes"), kBindVolumes);
    EXPECT_EQ(binding("Voxels"), kBindVoxels);
    EXPECT_EQ(property(GL_UNIFORM_BLOCK, "SplatFrame", GL_BUFFER_BINDING), kBindFrame);
}

TEST_F(GlLayout, UniformBlockMatchesC) {
    using tyndall::shader::SplatFrame;
    auto uniformOffset = [&](const char* member) {
        return property(GL_UNIFORM, std::string("SplatFrame.") + member, GL_OFFSET);
    };
    EXPECT_EQ(uniformOffset("cameraPosition"), GLint(offsetof(SplatFrame, cameraPosition)));
    EXPECT_EQ(uniformOffset("tanHalfX"), GLint(offsetof(SplatFrame, tanHalfX)));
    EXPECT_EQ(uniformOffset("cameraRight"), GLint(offsetof(SplatFrame, cameraRight)));
    EXPECT_EQ(uniformOffset("tanHalfY"), GLint(offsetof(SplatFrame, tanHalfY)));
    EXPECT_EQ(uniformOffset("cameraUp"), GLint(offsetof(SplatFrame, cameraUp)));
    EXPECT_EQ(uniformOffset("focalPixels"), GLint(offsetof(SplatFrame, focalPixels)));
    EXPECT_EQ(uniformOffset("cameraForward"), GLint(offsetof(SplatFrame, cameraForward)));
    EXPECT_EQ(uniformOffset("lensRadius"), GLint(offsetof(SplatFrame, lensRadius)));
    EXPECT_EQ(uniformOffset("filmSize"), GLint(offsetof(SplatFrame, filmSize)));
    EXPECT_EQ(uniformOffset("focusDistance"), GLint(offsetof(SplatFrame, focusDistance)));
    EXPECT_EQ(uniformOffset("freeFlightsPerRay"), GLint(offsetof(SplatFrame, freeFlightsPerRay)));
    EXPECT_EQ(uniformOffset("freeFlightsPerBeam"), GLint(offsetof(SplatFrame, freeFlightsPerBeam)));
    EXPECT_EQ(uniformOffset("beamCount"), GLint(offsetof(SplatFrame, beamCount)));
    EXPECT_LE(property(GL_UNIFORM_BLOCK, "SplatFrame", GL_BUFFER_DATA_SIZE), GLint(sizeof(SplatFrame)));
}
