#pragma once
// The ground truth of the quality study (build/bench/tyndall_quality): a long render of the in-tree
// path tracer, cached as <dir>/<scene>-<W>x<H>-<spp>spp.exr with its own noise (the variance of
// its mean, per pixel beside it and averaged in its metadata), and the error of an image against it
// with that noise removed.
#include <string>

#include "core/image.h"
#include "core/scene.h"
#include "core/settings.h"

namespace tyndall::bench {

struct Reference {
    Image mean;
    double noiseVariance = 0;  ///< the reference's own variance of the mean, averaged over pixels and channels
    Image variance;            ///< per pixel (cached beside the mean); empty in caches written without it
};

/// The reference for `scene` at the size of `s`: read from `dir` when cached there, else rendered
/// with `spp` samples per pixel (seed 1000 + s.seed, independent of the renders it judges) and
/// cached. `name` names the cache file.
Reference loadOrRenderReference(const Scene& scene, const std::string& name, const RenderSettings& s,
                                const std::string& dir, uint32_t spp);

struct ImageError {
    double relRmse = 0, relBias = 0;
    double relRmse99 = 0;  ///< relative RMSE without the brightest 1% of the reference's pixels
};

/// Relative RMSE (the reference's own noise variance removed) and relative bias of the image mean;
/// also the RMSE over the pixels below the reference's 99th brightness percentile, which leaves out
/// singular glows (a point light seen in fog) that any kernel radius blurs.
ImageError measure(const Image& x, const Reference& ref);

}  // namespace tyndall::bench
