#include "cpu/radius_defaults.h"

#include <algorithm>
#include <cmath>

#include "core/fresnel.h"
#include "core/material_eval.h"
#include "core/radius_schedule.h"
#include "cpu/pixel_footprint.h"

namespace tyndall {

bool hasAutomaticRadii(const RenderSettings& s) {
    return s.radius <= 0 || s.surfaceRadius <= 0 || s.radiusOffset == RenderSettings::kAutoRadiusOffset ||
           s.photonAngle == RenderSettings::kAutoPhotonAngle;
}

uint64_t plannedPhotonPaths(const RenderSettings& s) {
    if (s.plannedPaths > 0) return s.plannedPaths;
    // A pass count whose paths overflow (the viewer's "until stopped") is open-ended too.
    bool openEnded = s.timeBudget > 0 || s.passes > (uint64_t(1) << 50) / std::max<uint64_t>(1, s.photonsPerPass);
    if (!openEnded) return std::max<uint64_t>(1, s.passes * s.photonsPerPass);
    return RadiusDefaults::kOpenEndedPathsPerPixel * uint64_t(s.width) * uint64_t(s.height);
}

bool pointLightNearTheImage(const Scene& scene, int width, int height, double reach, double wider) {
    const Camera& c = scene.camera;
    const double pixelsPerUnitAtDepth1 = 1.0 / double(pixelSpread(c.yFov, height));
    for (const Light& l : scene.lights) {
        if (l.type == LightType::Directional) continue;
        if (length(l.position - c.position) <= reach) return true;
        float x, y, depth;
        if (!c.project(l.position, width, height, &x, &y, &depth)) continue;
        if (wider > 0 && !(wider * pixelsPerUnitAtDepth1 > double(depth))) continue;
        const double margin = reach * pixelsPerUnitAtDepth1 / std::max(double(depth), 1e-30);
        if (x >= -margin && x <= width + margin && y >= -margin && y <= height + margin) return true;
    }
    return false;
}

bool pointLightSeenInAMirror(const EmbreeScene& rt, int width, int height, double reach, double wider) {
    const Scene& scene = rt.scene();
    bool anyMirror = false, anyLight = false;
    for (const Material& m : scene.materials) anyMirror |= m.type == MaterialType::Mirror && !m.isRough();
    for (const Light& l : scene.lights) anyLight |= l.type != LightType::Directional;
    if (!anyMirror || !anyLight || width <= 0 || height <= 0) return false;
    Camera pinhole = scene.camera;
    pinhole.lensRadius = 0;
    const int nx = std::min(64, width), ny = std::min(64, height);
    // Radians between neighbouring grid rays, and half the cell's diagonal in them.
    const double spread = pixelSpread(pinhole.yFov, height);  // a pixel's footprint per unit of path length
    const double cell = spread * std::max(double(width) / nx, double(height) / ny);
    const double halfCell = 0.75 * cell;
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
            Ray ray = pinhole.generateRay((x + 0.5f) * width / nx, (y + 0.5f) * height / ny, width, height, {0.5f, 0.5f});
            double travelled = 0;
            int reflections = 0;
            for (int guard = 0; guard < 16; ++guard) {
                SurfaceHit hit;
                const bool found = rt.intersect(ray, &hit);
                const double tEnd = found ? double(length(hit.p - ray.o)) : 1e30;
                if (reflections > 0)
                    for (const Light& l : scene.lights) {
                        if (l.type == LightType::Directional) continue;
                        const Vec3 toLight = l.position - ray.o;
                        const double t = std::clamp(double(dot(toLight, ray.d)), 0.0, tEnd);
                        const double miss = length(toLight - ray.d * float(t));
                        const double footprint = (travelled + t) * spread;
                        if (miss <= reach + halfCell * (travelled + t) && !(wider > 0 && wider <= footprint))
                            return true;
                    }
                if (!found) break;
                const Material& m = scene.materials[size_t(scene.meshes[size_t(hit.mesh)].material)];
                const bool mirror = m.type == MaterialType::Mirror && !m.isRough();
                if (!mirror && m.type != MaterialType::Interface) break;
                travelled += tEnd;
                const Vec3 d = mirror ? reflect(-ray.d, dot(ray.d, hit.ns) < 0 ? hit.ns : -hit.ns) : ray.d;
                reflections += mirror;
                if (reflections > 4) break;
                ray = Ray{rt.offsetOrigin(hit.p, hit.ng, d), d, 0.0f, kInfinity};
            }
        }
    return false;
}

double photonConeAngle(uint64_t plannedPaths) {
    return RadiusDefaults::kConeAngleScale * std::pow(double(std::max<uint64_t>(plannedPaths, 1)), -0.2);
}

RenderSettings resolveRadiusDefaults(const RenderSettings& in, const EmbreeScene& rt) {
    RenderSettings s = in;
    // An explicit radius keeps its meaning: no photon cone unless the angle is given too.
    if (in.radius > 0 && s.photonAngle == RenderSettings::kAutoPhotonAngle) s.photonAngle = 0;
    if (!hasAutomaticRadii(s)) return s;
    const Scene& scene = rt.scene();
    s.plannedPaths = plannedPhotonPaths(s);
    // Without media or surfaces in view, footprints that start the radii at 0.5% and 2% of the
    // scene's diagonal (the scene-relative defaults of earlier versions) stand in.
    const double k = RadiusDefaults::kStartOverEnd;
    const double kb = RadiusDefaults::kBeamEndFootprints, ks = RadiusDefaults::kSurfaceEndFootprints;
    double diagonal = scene.bounds.empty() ? 1.0 : double(length(scene.bounds.diagonal()));
    PixelFootprint fp = measurePixelFootprint(rt, scene.camera, s.width, s.height);
    const double beamFallback = RadiusDefaults::kSceneRelativeBeam * diagonal / (k * kb);
    const double surfaceFallback = RadiusDefaults::kSceneRelativeSurface * diagonal / (std::sqrt(k) * ks);
    const double beamEnd = kb * fp.beam(beamFallback);
    const double surfaceEnd =
        std::min(ks * fp.surfaces(surfaceFallback), RadiusDefaults::kSurfaceEndMaxDiagonal * diagonal);

    double endFactor = 1.0 / k;  // beam factor at the end of the plan
    if (s.radiusOffset == RenderSettings::kAutoRadiusOffset) {
        double start = s.radius > 0 ? double(s.radius) : k * beamEnd;
        s.radiusOffset = RadiusSchedule::offsetForRatio(s.alpha, s.plannedPaths, std::min(1.0, beamEnd / start));
        endFactor = RadiusSchedule(s.alpha, s.radiusOffset).beamFactor(s.plannedPaths);
    }
    if (s.radius <= 0) s.radius = float(beamEnd / endFactor);
    if (s.surfaceRadius <= 0) s.surfaceRadius = float(surfaceEnd / std::sqrt(endFactor));
    if (s.photonAngle == RenderSettings::kAutoPhotonAngle) {
        // The cone reaches the full radius at path distance beamEnd / angle from the light (the
        // same for every path); it only pays where camera rays pass that close to a light.
        const double angle = photonConeAngle(s.plannedPaths);
        // ... and where the kernel at the start of the plan (k end radii) is wider than the light's
        // own pixel: the early passes' blur of the light's glow stays in the render's mean.
        const double wider = k * beamEnd / RadiusDefaults::kConeMinLightFootprints;
        const bool inView = pointLightNearTheImage(scene, s.width, s.height, beamEnd / angle, wider) ||
                            pointLightSeenInAMirror(rt, s.width, s.height, beamEnd / angle, wider);
        s.photonAngle = inView ? float(angle / endFactor) : 0.0f;
    }
    return s;
}

// The float products below are those of the literals they replaced (images unchanged).
static_assert(float(RadiusDefaults::kSceneRelativeBeam) == 0.005f &&
              float(RadiusDefaults::kSceneRelativeSurface) == 0.02f);

RenderSettings withSceneRelativeRadii(RenderSettings s, const Scene& scene) {
    const float diagonal = length(scene.bounds.diagonal());
    s.radius = float(RadiusDefaults::kSceneRelativeBeam) * diagonal;
    s.surfaceRadius = float(RadiusDefaults::kSceneRelativeSurface) * diagonal;
    s.radiusOffset = RadiusDefaults::kSceneRelativeOffset;
    return s;
}

}  // namespace tyndall
