#include "loading/default_smoke_scene.h"

#include "loading/default_scene.h"
#include "core/error.h"
#include "loading/procedural_media.h"

namespace tyndall {

Scene makeDefaultSmokeScene() {
    Scene s = makeDefaultScene();
    s.name = "caustic-box-smoke";
    Medium& smoke = s.media[s.globalMedium];
    smoke.name = "smoke";
    smoke.sigmaS = Rgb(2.4f);
    smoke.sigmaA = Rgb(0.3f);
    smoke.g = 0.3f;
    smoke.density = makeProceduralSmoke();
    s.finalize();
    return s;
}

Scene makeHomogeneousTwin(const Scene& scene, float density, std::vector<float>* used) {
    Scene twin = scene;
    bool any = false;
    for (Medium& m : twin.media) {
        if (m.homogeneous()) continue;
        float d = density >= 0 ? density : m.density->meanDensity();
        m.sigmaS = m.sigmaS * d;
        m.sigmaA = m.sigmaA * d;
        m.density = nullptr;
        m.name += " (homogeneous twin)";
        if (used) used->push_back(d);
        any = true;
    }
    if (!any) throw Error("scene '" + scene.name + "' (" + scene.source + ") has no density-grid medium to compare");
    twin.name = scene.name + "-homogeneous";
    return twin;
}

}  // namespace tyndall
