// GLSL twin of BeamRasterizer::pixelRadiance (cpu/beam_rasterizer.cpp): the medium radiance that
// beam `b` adds to pixel `pixel`'s primary segment.

vec3 pixelRadiance(int pixel, int b) {
    PrimaryRay ray = rays[pixel];
    PhotonBeam beam = beams[b];
    if (beam.medium != ray.medium || ray.medium < 0) return vec3(0.0);
    BeamRayHit hit;
    if (!intersectBeamRay(ray.origin, ray.dir, ray.tMax, beam, hit)) return vec3(0.0);
    Medium med = media[ray.medium];
    if (med.volume < 0) {
        precise float l = hit.s + hit.t;
        precise vec3 opticalDepth = -med.sigmaT * l;
        return beamRadiance(hit, beam, med.sigmaS, med.g, exp(opticalDepth), vec3(1.0));
    }
    float trCam = rayTransmittance(pixel, hit.s);
    float trBeam = beamTransmittance(b, hit.t);
    if (trCam == 0.0 || trBeam == 0.0) return vec3(0.0);
    precise vec3 x = ray.origin + ray.dir * hit.s;
    return beamRadiance(hit, beam, sigmaSAt(med, x), med.g, vec3(trCam), vec3(trBeam));
}
