// The viewer's saved scene: edits as JSON, applied by the same code the view file loader uses.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/grid_emission.h"
#include "loading/default_scene.h"
#include "loading/homogeneous_twin.h"
#include "loading/scene_edits.h"
#include "loading/scene_file.h"
#include "loading/vdb_grid.h"
#include "viewer/camera_controller.h"

namespace tyndall {
namespace {

bool sameBits(const Camera& a, const Camera& b) { return std::memcmp(&a, &b, sizeof(Camera)) == 0; }

Scene editedDefaultScene() {
    Scene s = makeDefaultScene();
    CameraController ctl(s.camera, 3.0f);
    ctl.orbit(37.0f, -11.0f);
    ctl.pan(5.0f, 3.0f);
    ctl.dolly(2.0f);
    s.camera = ctl.camera();
    s.lights[0].position = s.lights[0].position + Vec3(0.1f, -0.2f, 0.3f);
    s.lights[0].direction = normalize(Vec3(0.3f, -1.0f, 0.2f));
    s.lights[0].intensity = Rgb(12.5f, 3.25f, 0.1f);
    s.media[0].sigmaS = Rgb(0.11f, 0.2f, 0.3f);
    s.media[0].sigmaA = Rgb(0.01f);
    s.media[0].g = 0.37f;
    return s;
}

TEST(SceneEdits, RoundTripThroughJsonTextIsExact) {
    Scene edited = editedDefaultScene();
    nlohmann::json edits = sceneEdits(edited);
    // Through text, as the view file goes.
    nlohmann::json reread = nlohmann::json::parse(edits.dump(2));
    Scene a = makeDefaultScene(), b = makeDefaultScene();
    applySceneEdits(a, edits, "test");
    applySceneEdits(b, reread, "test");
    EXPECT_TRUE(sameBits(a.camera, b.camera));
    EXPECT_EQ(sceneEdits(a).dump(), sceneEdits(b).dump());
    // The applied scene holds the edited values (light direction re-normalized, camera rebuilt by
    // lookAt from the same numbers).
    EXPECT_NEAR(length(a.camera.position - edited.camera.position), 0.0f, 0.0f);
    EXPECT_NEAR(dot(a.camera.forward, edited.camera.forward), 1.0f, 1e-6f);
    EXPECT_EQ(a.lights[0].intensity.r, 12.5f);
    EXPECT_EQ(a.media[0].sigmaS.g, 0.2f);
    EXPECT_EQ(a.media[0].g, 0.37f);
    // Applying the applied scene's own edits again changes nothing it renders with.
    Scene c = a;
    applySceneEdits(c, sceneEdits(a), "test");
    EXPECT_EQ(sceneEdits(c)["lights"].dump(), sceneEdits(a)["lights"].dump());
    EXPECT_EQ(sceneEdits(c)["media"].dump(), sceneEdits(a)["media"].dump());
}

// The viewer's emission slider: "emission_scale" multiplies the medium's Le wherever it is read
// (the source term, the constant that the homogeneous closed form uses), round-trips exactly,
// defaults to 1 when a view file leaves it out, and 0 turns the fire off.
TEST(SceneEdits, EmissionScaleMultipliesTheMediumsEmission) {
    Scene s = makeDefaultScene();
    s.media[0].sigmaA = Rgb(0.1f);
    s.media[0].emission = Rgb(2.0f, 1.0f, 0.5f);
    ASSERT_TRUE(s.media[0].emissive());
    const Rgb before = s.media[0].sourceAt(Vec3(0.0f));
    nlohmann::json edits = sceneEdits(s);
    ASSERT_EQ(edits["media"][0]["emission_scale"], 1.0);
    edits["media"][0]["emission_scale"] = 2.5;
    Scene a = s;
    applySceneEdits(a, nlohmann::json::parse(edits.dump()), "test");
    EXPECT_EQ(a.media[0].emissionScale, 2.5f);
    const Rgb after = a.media[0].sourceAt(Vec3(0.0f));
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(after[c], 2.5f * before[c]);
    EXPECT_FLOAT_EQ(a.media[0].constantEmission().r, 5.0f);
    EXPECT_EQ(sceneEdits(a)["media"][0]["emission_scale"], 2.5);
    // Applied again (the viewer applies every snapshot to the scene it renders): still 2.5x.
    applySceneEdits(a, sceneEdits(a), "test");
    EXPECT_FLOAT_EQ(a.media[0].sourceAt(Vec3(0.0f)).r, 2.5f * before.r);
    // Left out: 1.
    edits["media"][0].erase("emission_scale");
    applySceneEdits(a, edits, "test");
    EXPECT_EQ(a.media[0].emissionScale, 1.0f);
    // Off.
    edits["media"][0]["emission_scale"] = 0;
    applySceneEdits(a, edits, "test");
    EXPECT_FALSE(a.media[0].emissive());
    EXPECT_TRUE(a.media[0].sourceAt(Vec3(0.0f)).isBlack());
    // Negative: an error naming the place.
    edits["media"][0]["emission_scale"] = -1;
    try {
        applySceneEdits(a, edits, "test");
        FAIL() << "a negative emission scale was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/edits/media/0/emission_scale"), std::string::npos) << e.what();
    }
}

// The compare view's emission slider: one scale drives both halves. The grid scene renders the
// edited scene's edits, its twin twinSceneEdits (the twin's own media, the edited scale): both
// emit 3x what they did, so their emitted powers stay equal; the grid's edits do not fit the twin.
TEST(SceneEdits, CompareEmissionSliderDrivesTheGridAndItsTwin) {
    Scene grid = makeDefaultScene();
    const int dims[3] = {6, 6, 6};
    std::vector<float> values(216, 0.0f);
    for (int k = 1; k <= 4; ++k)
        for (int j = 1; j <= 4; ++j)
            for (int i = 1; i <= 4; ++i) values[size_t(i + 6 * (j + 6 * k))] = float(i);
    const Affine3 xf = Affine3::scaleTranslate(Vec3(0.1f), Vec3(-0.3f));
    Medium& m = grid.media[0];
    m.sigmaS = Rgb(0.5f);
    m.sigmaA = Rgb(0.5f);
    m.density = VdbDensityGrid::fromDense(dims, values, xf, "block");
    m.emissionField = std::make_shared<GridEmission>(m.density, Rgb(1.0f, 0.5f, 0.25f), 2.0f);
    grid.finalize();
    const Scene twin = makeHomogeneousTwin(grid);
    const Vec3 inside(0.0f);
    const Rgb gridBefore = grid.media[0].sourceAt(inside), twinBefore = twin.media[0].sourceAt(inside);
    ASSERT_GT(gridBefore.r, 0.0f);
    ASSERT_GT(twinBefore.r, 0.0f);

    Scene edited = grid;
    edited.media[0].emissionScale = 3.0f;
    Scene left = grid, right = twin;
    applySceneEdits(left, sceneEdits(edited), "test");
    applySceneEdits(right, twinSceneEdits(edited, twin), "test");
    EXPECT_EQ(left.media[0].emissionScale, 3.0f);
    EXPECT_EQ(right.media[0].emissionScale, 3.0f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(left.media[0].sourceAt(inside)[c], 3.0f * gridBefore[c]);
        EXPECT_FLOAT_EQ(right.media[0].sourceAt(inside)[c], 3.0f * twinBefore[c]);
    }
    // The twin keeps its own medium: name, coefficients, no grid.
    EXPECT_EQ(right.media[0].name, twin.media[0].name);
    EXPECT_EQ(right.media[0].sigmaA.r, twin.media[0].sigmaA.r);
    EXPECT_TRUE(right.media[0].homogeneous());
    // The camera and lights are the edited scene's on both sides.
    EXPECT_EQ(twinSceneEdits(edited, twin)["camera"].dump(), sceneEdits(edited)["camera"].dump());
    EXPECT_EQ(twinSceneEdits(edited, twin)["lights"].dump(), sceneEdits(edited)["lights"].dump());
    Scene wrong = twin;
    EXPECT_THROW(applySceneEdits(wrong, sceneEdits(edited), "test"), Error);
}

TEST(SceneEdits, ViewFileLoadsTheBaseWithTheEditsAndItsRenderBlock) {
    namespace fs = std::filesystem;
    Scene edited = editedDefaultScene();
    nlohmann::json edits = sceneEdits(edited);
    Scene viewerScene = makeDefaultScene();
    applySceneEdits(viewerScene, edits, "viewer");
    nlohmann::json render = {{"passes", 7}, {"photons", 321}, {"radius", 0.0125}};
    fs::path dir = fs::path(TYNDALL_TEST_OUTPUT_DIR) / "viewer";
    fs::create_directories(dir);
    fs::path file = dir / "view.json";
    std::ofstream(file) << viewFileJson("edited", kBuiltinDefaultScene, "", edits, render).dump(2);
    SceneFile loaded = loadSceneFile(file.string());
    EXPECT_TRUE(sameBits(loaded.scene.camera, viewerScene.camera));
    EXPECT_EQ(sceneEdits(loaded.scene).dump(), sceneEdits(viewerScene).dump());
    EXPECT_EQ(loaded.scene.name, "edited");
    EXPECT_EQ(loaded.render["photons"], 321);
    EXPECT_EQ(loaded.scene.triangleCount(), makeDefaultScene().triangleCount());

    // A view of a scene file: the base is found relative to the view file.
    fs::path sceneFile = fs::path(TYNDALL_SOURCE_DIR) / "scenes" / "caustic-box.json";
    SceneFile base = loadSceneFile(sceneFile.string());
    nlohmann::json baseEdits = sceneEdits(base.scene);
    std::ofstream(dir / "view2.json") << viewFileJson("v2", fs::relative(sceneFile, dir).string(), "0", baseEdits,
                                                      nlohmann::json::object());
    SceneFile v2 = loadSceneFile((dir / "view2.json").string());
    EXPECT_EQ(sceneEdits(v2.scene)["lights"].dump(), baseEdits["lights"].dump());
}

TEST(SceneEdits, MismatchedEditsAreErrorsNamingThePlace) {
    Scene s = makeDefaultScene();
    nlohmann::json edits = sceneEdits(s);
    edits["lights"].erase(0);
    try {
        applySceneEdits(s, edits, "v.json");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("v.json: /edits/lights"), std::string::npos) << e.what();
    }
    nlohmann::json renamed = sceneEdits(s);
    renamed["media"][0]["name"] = "nope";
    EXPECT_THROW(applySceneEdits(s, renamed, "v.json"), Error);
    nlohmann::json unknown = sceneEdits(s);
    unknown["camera"]["zoom"] = 2;
    EXPECT_THROW(applySceneEdits(s, unknown, "v.json"), Error);
}

}  // namespace
}  // namespace tyndall
