// `tyndall render --aov`: each layer on a scene where it alone holds the light. The layers adding up
// to the beauty image (tests/app/render_production_test.cpp) cannot tell two of them apart: a swap
// passes it. Here
//   - fog lit by a point light, seen directly, black walls: all in media_primary (equiangular
//     sampling off and on);
//   - fog in a closed volume the camera sees only in a mirror (vacuum elsewhere): all in media_secondary;
//   - no medium, a lit floor seen directly and in a mirror, and an emitter: all in surface.
// In each, the other two layers are zero (to float rounding) and the known one is the beauty image.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/image_io.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

using tyndall::test::runTyndall;

const char* kLayers[] = {"media_primary", "media_secondary", "surface"};

std::string writeScene(const std::string& name, const std::string& text) {
    std::string path = tyndall::test::outputDir() + "/aov_" + name + ".json";
    std::ofstream(path) << text;
    return path;
}

double layerSum(const std::string& exr, const std::string& layer) {
    tyndall::Image img = layer.empty() ? tyndall::readImage(exr) : tyndall::readImageLayer(exr, layer);
    double sum = 0;
    for (const tyndall::Rgb& p : img.pixels) sum += double(p.r) + p.g + p.b;
    return sum;
}

/// Renders `scene` with --aov (and `options`) and checks that layer `only` holds the beauty image and
/// the others nothing.
void expectOnlyLayer(const std::string& name, const std::string& scene, const std::string& only,
                     const std::string& options = "") {
    const std::string exr = tyndall::test::outputDir() + "/aov_" + name + ".exr";
    std::remove(exr.c_str());
    auto r = runTyndall("render " + writeScene(name, scene) +
                        " --size 32x24 --passes 3 --photons 3000 --seed 5 --gpu off -q --aov " + options + " -o " + exr);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const double beauty = layerSum(exr, "");
    ASSERT_GT(beauty, 1.0) << name << ": the scene should be lit";
    for (const char* layer : kLayers) {
        const double sum = layerSum(exr, layer);
        std::printf("%s: %s / beauty = %.6f\n", name.c_str(), layer, sum / beauty);
        if (layer == only)
            EXPECT_NEAR(sum / beauty, 1.0, 1e-4) << name << ": " << layer << " should hold the whole image";
        else
            EXPECT_LT(std::abs(sum) / beauty, 1e-5) << name << ": " << layer << " should be empty";
    }
}

TEST(AovLayers, FogSeenDirectlyIsMediaPrimaryAlone) {
    // With equiangular sampling the lamp's single scattering along the primary segments is the
    // CPU's, not the splat's: media_primary all the same.
    for (const std::string equiangular : {"off", "on"})
        expectOnlyLayer("direct_fog_equiangular_" + equiangular, R"({"name": "aov-direct-fog",
 "materials": [{"name": "black", "albedo": 0}],
 "media": [{"name": "fog", "sigma_s": 0.3, "sigma_a": 0.05}], "global_medium": "fog",
 "shapes": [{"type": "box", "name": "room", "material": "black", "min": [-2, -2, -2], "max": [2, 2, 2], "inward": true}],
 "lights": [{"type": "point", "name": "p", "position": [0, 0, 0], "intensity": 2}],
 "cameras": [{"name": "c", "position": [0, 0, 1.8], "target": [0, 0, 0], "fov": 60}]})",
                        "media_primary", "--equiangular " + equiangular);
}

TEST(AovLayers, FogSeenOnlyInAMirrorIsMediaSecondaryAlone) {
    // The mirror at 45 degrees sends the camera's rays to +x, into a fog box the camera cannot see
    // directly (it lies 37 degrees off axis, the half field of view is 15).
    expectOnlyLayer("mirror_fog", R"({"name": "aov-mirror-fog",
 "materials": [{"name": "mirror", "type": "mirror", "albedo": 0.9}, {"name": "hull", "type": "interface"}],
 "media": [{"name": "fog", "sigma_s": 0.5, "sigma_a": 0.05, "inside": "fog box"}],
 "shapes": [{"type": "quad", "name": "mirror", "material": "mirror", "corner": [-1.06, -1.5, 1.06], "edge1": [2.12, 0, -2.12], "edge2": [0, 3, 0]},
            {"type": "box", "name": "fog box", "material": "hull", "min": [1.5, -1, -1], "max": [3.5, 1, 1]}],
 "lights": [{"type": "point", "name": "p", "position": [2.5, 0, 0], "intensity": 3}],
 "cameras": [{"name": "c", "position": [0, 0, 3], "target": [0, 0, 0], "fov": 30}]})",
                    "media_secondary");
}

TEST(AovLayers, SurfacesDirectAndInAMirrorAndAnEmitterAreSurfaceAlone) {
    expectOnlyLayer("surfaces", R"({"name": "aov-surfaces",
 "materials": [{"name": "white", "albedo": 0.7}, {"name": "mirror", "type": "mirror", "albedo": 0.9},
               {"name": "lamp", "albedo": 0, "emission": 2}],
 "shapes": [{"type": "quad", "name": "floor", "material": "white", "corner": [-2, 0, 2], "edge1": [4, 0, 0], "edge2": [0, 0, -4]},
            {"type": "quad", "name": "mirror", "material": "mirror", "corner": [-2, 0, -1.5], "edge1": [4, 0, 0], "edge2": [0, 2, 0]},
            {"type": "quad", "name": "lamp", "material": "lamp", "corner": [-1.5, 0.8, -1.4], "edge1": [0.5, 0, 0], "edge2": [0, 0.5, 0]}],
 "lights": [{"type": "point", "name": "p", "position": [0.5, 1.5, 0.5], "intensity": 3}],
 "cameras": [{"name": "c", "position": [0, 1, 2.5], "target": [0, 0.6, 0], "fov": 60}]})",
                    "surface");
}

}  // namespace
