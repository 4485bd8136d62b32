// GLSL twin of BeamRasterizer::pixelRadiance (cpu/beam_rasterizer.cpp): the medium radiance that
// beam number `b` adds to pixel `pixel`'s primary segment. The beam and its medium `med`
// (= media[beam.medium]) are passed in so that the caller can take them from flat varyings.

vec3 pixelRadiance(int pixel, PhotonBeam beam, Medium med, int b) {
    PrimaryRay ray = rays[pixel];
    if (beam.medium != ray.medium || ray.medium < 0) return vec3(0.0);
    BeamRayHit hit;
    if (!intersectBeamRay(ray.origin, ray.dir, ray.tMax, beam, hit)) return vec3(0.0);
#if TYNDALL_GRID_MEDIA
    if (med.volume < 0) {
#endif
        precise float l = hit.s + hit.t;
        precise vec3 opticalDepth = -med.sigmaT * l;
        return beamRadiance(hit, beam, med.sigmaS, med.g, exp(opticalDepth), vec3(1.0));
#if TYNDALL_GRID_MEDIA
    }
    float trCam = rayTransmittance(pixel, hit.s);
    float trBeam = beamTransmittance(b, hit.t);
    if (trCam == 0.0 || trBeam == 0.0) return vec3(0.0);
    precise vec3 x = ray.origin + ray.dir * hit.s;
    return beamRadiance(hit, beam, sigmaSAt(med, x), med.g, vec3(trCam), vec3(trBeam));
#endif
}
