#pragma once
// What photon tracing stores for one pass: photon beams (every path segment through a medium)
// and surface photons (every diffuse hit), plus the bookkeeping the radius schedule needs.
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/medium.h"
#include "core/photon_plane.h"

namespace tyndall {

/// One photon beam: the segment x_b + t w_b, t in [0, tMax], of a photon path inside one medium.
/// `power` is Phi_b: the path's throughput at x_b times the emitted power, divided by the number of
/// photon paths of the pass. Layout is three 16-byte rows so the GL side can upload the array
/// as-is (std430: vec4 originTMax, vec4 dirRadius, vec4 powerMedium); gpu/ static_asserts it.
struct PhotonBeam {
    Vec3 origin;
    float tMax = 0;
    Vec3 dir;
    float radius = 0;
    Rgb power;
    MediumId medium = kVacuum;
};
static_assert(sizeof(PhotonBeam) == 48, "PhotonBeam must stay three vec4 rows for the GL upload");

/// A photon point in a dense medium (RenderSettings::mediumPointMfp; docs/algorithm.md, "Photon
/// points in dense media"): a photon path's scattering at `position` inside the homogeneous medium
/// `medium`, standing for the beam it ended (which is then not stored). `dir` is the direction the
/// photon travelled to reach it; `power` its power just after the free flight's weight
/// (sigma_s Tr / pdf: the light this scattering sends out, before the phase function); `segment`
/// the index of that beam's segment on its photon path (PhotonMap::beamSegments).
struct MediumPoint {
    Vec3 position;
    float radius = 0;
    Vec3 dir;
    uint32_t segment = 0;
    Rgb power;
    MediumId medium = kVacuum;
};
static_assert(sizeof(MediumPoint) == 48, "MediumPoint: three 16-byte rows");

/// SurfacePhoton::flags bits.
inline constexpr uint8_t kPhotonDirect = 1;     ///< no scattering vertex (surface or medium) since the light
inline constexpr uint8_t kPhotonDeltaPath = 2;  ///< emitted by a delta light and every vertex since was a delta interaction

/// A photon stored on a surface (diffuse, coated, partly transmissive; glossy ones keep only
/// kPhotonDeltaPath photons). `wi` points from the surface toward where the photon came from;
/// `power` as for beams. `flags` (kPhoton*) say which gathers use it: glossy and coat-specular
/// gathers take only kPhotonDeltaPath photons (docs/algorithm.md "Glossy vertices").
struct SurfacePhoton {
    Vec3 position;
    float radius = 0;
    Vec3 wi;
    Vec3 normal;  ///< geometric normal on the side the photon arrived from
    Rgb power;
    /// kPhotonDirect | kPhotonDeltaPath, set by the photon tracer at every stored photon. Interface
    /// crossings (index-matched medium boundaries) are not scattering vertices.
    uint8_t flags = 0;
    /// Segments of its photon path from the light to here (an Interface crossing starts none),
    /// saturating at 65535; a camera path that gathers it at its own segment k makes a light path
    /// of k + segments (RenderSettings::maxPathLength).
    uint16_t segments = 0;
};

/// A surface photon counts at a gather point, and a mesh edge bounds the kernel there, only when
/// their normals agree with the point's to this cosine: the same surface (or, with |.|, either
/// side of it), not a neighbour meeting it at an angle.
inline constexpr float kSurfaceNormalAgreement = 0.7f;

/// Everything photon tracing produced for one pass.
struct PhotonMap {
    uint64_t pass = 0;
    uint64_t firstPath = 0;   ///< global index of the first photon path held (radius schedule)
    /// Photon paths held: the whole pass (the divisor in the beam power), or one batch of it
    /// (PhotonTracer::traceBatch: the divisor stays the pass's path count).
    uint32_t pathCount = 0;
    uint64_t raysTraced = 0;  ///< surface rays cast while tracing (for throughput figures)
    std::vector<PhotonBeam> beams;
    /// Heterogeneous media: `freeFlightsPerBeam` distances per beam (beam i uses
    /// freeFlights[i*n .. i*n+n)), distances along the beam from its origin; a distance >= tMax
    /// means the sample passed the whole beam. Empty when no beam is in a heterogeneous medium.
    std::vector<float> freeFlights;
    int freeFlightsPerBeam = 0;
    /// With RenderSettings::maxPathLength set: per beam, its segment's index on its photon path
    /// (1 = straight from the light; see SurfacePhoton::segments). Empty when uncapped.
    std::vector<uint16_t> beamSegments;
    std::vector<SurfacePhoton> surfacePhotons;
    /// RenderSettings::photonPlanes: one plane per beam in a homogeneous medium (core/photon_plane.h),
    /// in path order.
    std::vector<PhotonPlane> planes;
    /// RenderSettings::mediumPointMfp: the photon points in dense media, in path order.
    std::vector<MediumPoint> points;
};

}  // namespace tyndall
