// Nested media (core/medium_nesting.h): winding numbers and containment of simple meshes, and the
// media finalize() gives each mesh of a jar of smoke in fog, a liquid in a glass in a room, a lamp
// in a lantern with an explicit cavity medium; meshes straddling a medium's boundary are refused
// with both names, opaque ones are not. Expected media are written out by hand for each scene.
#include "core/medium_nesting.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "loading/mesh_builders.h"

using namespace tyndall;

namespace {

enum : int { kFog = 0, kSmoke = 1, kWine = 2 };
constexpr int kDiffuse = 0, kGlass = 1, kHull = 2, kLamp = 3;

Scene baseScene() {
    Scene s;
    s.name = "nesting";
    s.source = "<test>";
    for (MaterialType type : {MaterialType::Diffuse, MaterialType::Dielectric, MaterialType::Interface,
                              MaterialType::Diffuse}) {
        Material m;
        m.type = type;
        s.materials.push_back(m);
    }
    s.materials[kLamp].emission = Rgb(1.0f);
    for (const char* name : {"fog", "smoke", "wine"}) {
        Medium m;
        m.name = name;
        s.media.push_back(m);
    }
    return s;
}
int add(Scene& s, TriangleMesh m, MediumId interior = kInheritMedium, MediumId exterior = kInheritMedium) {
    m.interiorMedium = interior;
    m.exteriorMedium = exterior;
    s.meshes.push_back(std::move(m));
    return int(s.meshes.size()) - 1;
}

std::string finalizeError(Scene s) {
    try {
        s.finalize();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(MediumNesting, WindingNumberOfBoxAndSphere) {
    TriangleMesh box = makeBox("box", {0, 0, 0}, {1, 2, 3}, 0);
    EXPECT_NEAR(windingNumber(box, {0.5f, 1.0f, 1.5f}), 1.0, 1e-9);
    EXPECT_NEAR(windingNumber(box, {0.99f, 1.99f, 0.01f}), 1.0, 1e-9);
    EXPECT_NEAR(windingNumber(box, {1.01f, 1.0f, 1.5f}), 0.0, 1e-9);
    EXPECT_NEAR(windingNumber(box, {-5.0f, 7.0f, 1.5f}), 0.0, 1e-9);
    EXPECT_NEAR(windingNumber(box, {0.5f, 1.0f, 3.0f}), 0.5, 1e-9);  // on a face
    EXPECT_NEAR(windingNumber(makeBox("in", {0, 0, 0}, {1, 2, 3}, 0, true), {0.5f, 1.0f, 1.5f}), -1.0, 1e-9);
    TriangleMesh sphere = makeSphere("s", {1, 2, 3}, 0.5f, 3, 0);
    EXPECT_NEAR(windingNumber(sphere, {1.1f, 2.2f, 2.9f}), 1.0, 1e-9);
    EXPECT_NEAR(windingNumber(sphere, {1.6f, 2.0f, 3.0f}), 0.0, 1e-9);
}

TEST(MediumNesting, ContainmentOfSimpleShapes) {
    TriangleMesh box = makeBox("box", {-1, -1, -1}, {1, 1, 1}, 0);
    EXPECT_EQ(containment(makeSphere("in", {0.2f, 0, 0}, 0.5f, 2, 0), box), Containment::Inside);
    EXPECT_EQ(containment(makeSphere("out", {3, 0, 0}, 0.5f, 2, 0), box), Containment::Outside);
    EXPECT_EQ(containment(makeSphere("half", {1, 0, 0}, 0.5f, 2, 0), box), Containment::Straddles);
    // Every vertex outside, the surfaces cross: a big quad through the box, and a box through a
    // small quad's middle (the quad's edges all outside).
    EXPECT_EQ(containment(makeQuad("sheet", {-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, 0), box), Containment::Straddles);
    EXPECT_EQ(containment(makeQuad("card", {-1, 0, 0}, {2, 0, 0}, {0, 1, 0}, 0),
                          makeBox("pin", {-0.05f, 0.05f, -0.5f}, {0.05f, 0.15f, 0.5f}, 0)),
              Containment::Straddles);
    // Touching is not crossing: a quad lying on the top face, a sphere touching a face from inside,
    // an inner box sharing a face with the outer one.
    EXPECT_EQ(containment(makeQuad("lid", {-0.5f, 1, 0.5f}, {1, 0, 0}, {0, 0, -1}, 0), box), Containment::Outside);
    EXPECT_EQ(containment(makeSphere("touch", {0.5f, 0, 0}, 0.5f, 2, 0), box), Containment::Inside);
    EXPECT_EQ(containment(makeBox("floor half", {-1, -1, -1}, {1, 0, 1}, 0), box), Containment::Inside);
    // The inward cavity of a hollow object holds what is inside it.
    EXPECT_EQ(containment(makeSphere("bulb", {0, 0, 0}, 0.1f, 2, 0), makeBox("cavity", {-0.9f, -0.9f, -0.9f}, {0.9f, 0.9f, 0.9f}, 0, true)),
              Containment::Inside);
}

// Smoke in a hollow glass jar in fog, a lamp in the smoke. The jar: outer surface facing out, inner
// surface facing in; the smoke fills an Interface hull inside the cavity.
TEST(MediumNesting, SmokeInGlassJarInFog) {
    Scene s = baseScene();
    s.globalMedium = kFog;
    int outer = add(s, makeBox("jar outside", {-1, 0, -1}, {1, 3, 1}, kGlass));
    int inner = add(s, makeBox("jar inside", {-0.9f, 0.1f, -0.9f}, {0.9f, 2.9f, 0.9f}, kGlass, true));
    int smoke = add(s, makeSphere("smoke hull", {0, 1.5f, 0}, 0.8f, 3, kHull), kSmoke);
    int lamp = add(s, makeSphere("lamp", {0, 1.5f, 0}, 0.1f, 2, kLamp));
    int floor = add(s, makeQuad("floor", {-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, kDiffuse));
    s.finalize();
    EXPECT_EQ(s.meshes[outer].exteriorMedium, kFog);
    EXPECT_EQ(s.meshes[outer].interiorMedium, kVacuum);  // the glass
    EXPECT_EQ(s.meshes[inner].interiorMedium, kVacuum);  // the glass again, seen from the cavity
    EXPECT_EQ(s.meshes[inner].exteriorMedium, kVacuum);  // the cavity: what holds it, the glass's
    EXPECT_EQ(s.meshes[smoke].exteriorMedium, kVacuum);
    EXPECT_EQ(s.meshes[smoke].interiorMedium, kSmoke);
    EXPECT_EQ(s.meshes[lamp].exteriorMedium, kSmoke);  // where its photons start
    EXPECT_EQ(s.meshes[floor].exteriorMedium, kFog);
    EXPECT_NO_THROW(s.validate());
}

// Wine in a solid glass (one closed dielectric) standing in a room full of haze; the room is an
// inward-facing opaque box, which bounds no medium.
TEST(MediumNesting, LiquidInGlassInRoom) {
    Scene s = baseScene();
    s.globalMedium = kFog;
    int room = add(s, makeBox("room", {-3, 0, -3}, {3, 3, 3}, kDiffuse, true));
    int glass = add(s, makeCylinder("glass", {0, 1, 0}, {0, 1.3f, 0}, 0.1f, 24, kGlass));
    int wine = add(s, makeCylinder("wine", {0, 1.02f, 0}, {0, 1.2f, 0}, 0.09f, 24, kGlass), kWine);
    int lamp = add(s, makeQuad("ceiling lamp", {-0.5f, 2.9f, -0.5f}, {1, 0, 0}, {0, 0, 1}, kLamp));
    s.finalize();
    EXPECT_EQ(s.meshes[room].exteriorMedium, kFog);
    EXPECT_EQ(s.meshes[room].interiorMedium, kFog);
    EXPECT_EQ(s.meshes[glass].exteriorMedium, kFog);
    EXPECT_EQ(s.meshes[glass].interiorMedium, kVacuum);
    EXPECT_EQ(s.meshes[wine].exteriorMedium, kVacuum);
    EXPECT_EQ(s.meshes[wine].interiorMedium, kWine);
    EXPECT_EQ(s.meshes[lamp].exteriorMedium, kFog);
}

// A lamp in a hollow glass lantern in fog: the cavity holds vacuum unless the inner surface says
// otherwise with an explicit exterior, which containment then passes on to what the cavity holds.
TEST(MediumNesting, ExplicitExteriorOverridesContainment) {
    for (bool explicitFog : {false, true}) {
        Scene s = baseScene();
        s.globalMedium = kFog;
        add(s, makeBox("glass outside", {-1, -1, -1}, {1, 1, 1}, kGlass));
        int inside = add(s, makeBox("glass inside", {-0.9f, -0.9f, -0.9f}, {0.9f, 0.9f, 0.9f}, kGlass, true),
                         kInheritMedium, explicitFog ? kFog : kInheritMedium);
        int bulb = add(s, makeSphere("bulb", {0, 0, 0}, 0.1f, 2, kLamp));
        s.finalize();
        MediumId cavity = explicitFog ? kFog : kVacuum;
        EXPECT_EQ(s.meshes[inside].exteriorMedium, cavity);
        EXPECT_EQ(s.meshes[inside].interiorMedium, kVacuum);
        EXPECT_EQ(s.meshes[bulb].exteriorMedium, cavity);
    }
}

TEST(MediumNesting, StraddlingMeshesAreRefusedWithBothNames) {
    auto fogBox = [](Scene& s) { add(s, makeBox("fog box", {-1, 0, -1}, {1, 2, 1}, kHull), kFog); };
    {
        Scene s = baseScene();
        fogBox(s);
        add(s, makeQuad("half lamp", {0.5f, 1, 0.5f}, {1, 0, 0}, {0, 0, -1}, kLamp));
        std::string e = finalizeError(s);
        EXPECT_NE(e.find("mesh 'half lamp' (index 1) lies partly inside and partly outside mesh 'fog box' (index 0)"),
                  std::string::npos)
            << e;
        EXPECT_NE(e.find("scene 'nesting' (<test>)"), std::string::npos) << e;
    }
    {
        Scene s = baseScene();
        fogBox(s);
        add(s, makeSphere("sunk glass ball", {0, 2, 0}, 0.3f, 2, kGlass));
        EXPECT_NE(finalizeError(s).find("'sunk glass ball'"), std::string::npos);
    }
    {
        // A light sheet through the fog box with every vertex outside it.
        Scene s = baseScene();
        fogBox(s);
        add(s, makeQuad("light sheet", {-3, 1, 3}, {6, 0, 0}, {0, 0, -6}, kLamp));
        EXPECT_NE(finalizeError(s).find("'light sheet'"), std::string::npos);
    }
    {
        // Two overlapping media.
        Scene s = baseScene();
        fogBox(s);
        add(s, makeSphere("smoke ball", {1, 1, 0}, 0.5f, 2, kHull), kSmoke);
        EXPECT_NE(finalizeError(s).find("'smoke ball'"), std::string::npos);
    }
    for (MediumId global : {kVacuum, MediumId(kFog)}) {
        // Intersecting glass balls: the same medium on both sides of each in vacuum (accepted),
        // fog outside and vacuum inside in fog (refused).
        Scene s = baseScene();
        s.globalMedium = global;
        add(s, makeSphere("ball 1", {0, 0, 0}, 0.5f, 2, kGlass));
        add(s, makeSphere("ball 2", {0.5f, 0, 0}, 0.5f, 2, kGlass));
        EXPECT_EQ(finalizeError(s).empty(), global == kVacuum) << finalizeError(s);
    }
    {
        // Opaque meshes take no medium from the boundary: a floor through the fog box and a ball
        // half in it are fine.
        Scene s = baseScene();
        fogBox(s);
        add(s, makeQuad("floor", {-5, 0.5f, 5}, {10, 0, 0}, {0, 0, -10}, kDiffuse));
        add(s, makeSphere("ball", {1, 1, 0}, 0.3f, 2, kDiffuse));
        s.lights.push_back(Light{});
        EXPECT_EQ(finalizeError(s), "");
    }
}

TEST(MediumNesting, CoincidentMediaAreRefused) {
    Scene s = baseScene();
    add(s, makeBox("fog box", {-1, -1, -1}, {1, 1, 1}, kHull), kFog);
    add(s, makeBox("smoke box", {-1, -1, -1}, {1, 1, 1}, kHull), kSmoke);
    add(s, makeSphere("lamp", {0, 0, 0}, 0.1f, 2, kLamp));
    std::string e = finalizeError(s);
    EXPECT_NE(e.find("mesh 'lamp' (index 2) lies inside both"), std::string::npos) << e;
}
