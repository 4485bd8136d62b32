// The viewer's transparent film (RenderSettings::transparentFilm in RenderLoop): each published
// frame carries the coverage beside the image, 0 and no radiance where the camera sees only the
// environment, 1 on a card; saveView writes it as the EXR's channel A and the PNG's alpha.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <thread>

#include "core/environment_light.h"
#include "loading/mesh_builders.h"
#include "tests/test_scenes.h"
#include "tests/test_util.h"
#include "viewer/render_loop.h"
#include "viewer/view_save.h"

namespace tyndall {
namespace {

TEST(RenderLoopAlpha, FramesCarryTheCoverageAndASavedViewWritesIt) {
    Scene s;
    s.name = "film";
    s.source = "<test>";
    test::addMaterial(s, "card", MaterialType::Diffuse, Rgb(0.5f));
    s.meshes.push_back(makeQuad("card", {-2, -2, -3}, {2, 0, 0}, {0, 4, 0}, 0));  // the left half
    s.environment = EnvironmentLight::constant(Rgb(1.5f));
    s.camera = Camera::lookAt({0, 0, 0}, {0, 0, -3}, {0, 1, 0}, 0.7f);
    s.finalize();
    s.validate();
    RenderSettings rs;
    rs.width = rs.height = 16;
    rs.photonsPerPass = 100;
    rs.transparentFilm = true;
    RenderLoop loop(s, rs, GpuMode::Off);
    loop.start(nlohmann::json::object());
    ViewFrame f;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!(f.mode == RenderMode::Refine && f.passes >= 2) && std::chrono::steady_clock::now() < end) {
        loop.latest(&f);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    loop.stop();
    ASSERT_EQ(loop.error(), "");
    ASSERT_GE(f.passes, 2u);
    ASSERT_EQ(f.alpha.width, f.mean.width);
    ASSERT_EQ(f.alpha.height, f.mean.height);
    EXPECT_EQ(f.alpha.at(2, 8).r, 1.0f) << "the card";
    EXPECT_GT(f.mean.at(2, 8).g, 0.0f);
    EXPECT_EQ(f.alpha.at(13, 8).r, 0.0f) << "only the environment";
    EXPECT_EQ(f.mean.at(13, 8).g, 0.0f) << "the background is left out";

    const SavedView v = saveView(f, test::outputDir() + "/render_loop_alpha", "builtin:default", "", "film", 1.0f);
    for (const std::string& path : {v.exr, v.png}) {
        auto in = OIIO::ImageInput::open(path);
        ASSERT_TRUE(in) << path;
        const OIIO::ImageSpec& spec = in->spec();
        ASSERT_EQ(spec.nchannels, 4) << path;
        ASSERT_EQ(spec.alpha_channel, 3) << path;
        std::vector<float> px(size_t(spec.width) * spec.height * 4);
        in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, px.data());
        EXPECT_EQ(px[size_t(8 * spec.width + 2) * 4 + 3], 1.0f) << path;
        EXPECT_EQ(px[size_t(8 * spec.width + 13) * 4 + 3], 0.0f) << path;
    }
}

}  // namespace
}  // namespace tyndall
