#pragma once
// The primary camera segments of one pass: for every pixel, the jittered camera ray's stretch
// from the camera (or where it enters the medium) to its first surface, and the medium it runs
// through. Produced by the CPU camera pass, consumed by the primary-beam splatters (CPU twin in
// cpu/beam_rasterizer, GL in gpu/): occlusion is this per-pixel distance, not a depth buffer.
// PrimaryRay is two vec4 rows so the GL side can upload the array as a texture/buffer as-is.
#include <vector>

#include "core/image.h"
#include "core/math.h"
#include "core/medium.h"
#include "core/pixel_region.h"

namespace tyndall {

struct PrimaryRay {
    Vec3 origin;
    float tMax = 0;  ///< length of the medium stretch; 0 when the camera ray meets no medium
    Vec3 dir;        ///< unit
    MediumId medium = kVacuum;
};
static_assert(sizeof(PrimaryRay) == 32, "PrimaryRay must stay two vec4 rows for the GL upload");

struct PrimarySegments {
    int width = 0;
    int height = 0;
    std::vector<PrimaryRay> rays;  ///< row-major, (0,0) top-left
    /// The pixels traced (RenderSettings::region resolved: the whole image when it has none). Rays
    /// outside it are stale; the splatters leave those pixels 0 and never read them.
    PixelRegion region;
    /// Heterogeneous media: `freeFlightsPerRay` collision distances per pixel along the stretch
    /// (from `origin`); empty when the scene has no density-grid medium.
    std::vector<float> freeFlights;
    int freeFlightsPerRay = 0;
};

}  // namespace tyndall
