#include "loading/default_smoke_scene.h"

#include "loading/default_scene.h"
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

}  // namespace tyndall
