// GLSL twin of core/beam_estimator.h (with core/phase.h's hgPhase): the beam x ray 1D estimator.
// Keep the arithmetic in the C++ order; `precise` stops the compiler fusing multiply-adds, so the
// closest-point parameters round as in C++ and the accept/reject decisions agree at the edges.
// tests/gpu/estimator_parity_test.cpp runs both on the same inputs.

const float kMinSinTheta = 1e-3;
const float kInv4Pi = 1.0 / (4.0 * 3.14159265358979323846);

struct BeamRayHit {
    float u;            // distance between the two lines
    float s;            // s_w: parameter along the camera segment
    float t;            // t_v: parameter along the beam
    float invSinTheta;  // 1/sin(theta), clamped
    float cosTheta;     // dot(w_c, w_b)
};

// Normalised 1D biweight kernel of radius r.
float beamKernel(float u, float r) {
    precise float x = u / r;
    precise float a = 1.0 - x * x;
    return a > 0.0 ? (15.0 / 16.0) * a * a / r : 0.0;
}

// Henyey-Greenstein; cosTheta between the travel directions before and after scattering.
float hgPhase(float cosTheta, float g) {
    precise float denom = 1.0 + g * g - 2.0 * g * cosTheta;
    precise float p = kInv4Pi * (1.0 - g * g) / (denom * sqrt(max(denom, 1e-12)));
    return p;
}

// Closest approach of camera segment (xc, wc, [0, sMax]) and `beam`; false when the beam does not
// contribute (u >= radius, closest points outside either segment, or lines parallel).
bool intersectBeamRay(vec3 xc, vec3 wc, float sMax, PhotonBeam beam, out BeamRayHit hit) {
    precise vec3 w0 = xc - beam.origin;
    precise float b = wc.x * beam.dir.x + wc.y * beam.dir.y + wc.z * beam.dir.z;
    precise float sin2 = 1.0 - b * b;
    if (sin2 < 1e-12) return false;
    precise float d = wc.x * w0.x + wc.y * w0.y + wc.z * w0.z;
    precise float e = beam.dir.x * w0.x + beam.dir.y * w0.y + beam.dir.z * w0.z;
    precise float s = (b * e - d) / sin2;
    precise float t = (e - b * d) / sin2;
    if (s < 0.0 || s > sMax || t < 0.0 || t > beam.tMax) return false;
    precise vec3 between = w0 + wc * s - beam.dir * t;
    precise float u2 = between.x * between.x + between.y * between.y + between.z * between.z;
    if (u2 >= beam.radius * beam.radius) return false;
    hit.u = sqrt(u2);
    hit.s = s;
    hit.t = t;
    hit.cosTheta = b;
    hit.invSinTheta = 1.0 / max(sqrt(sin2), kMinSinTheta);
    return true;
}

// The estimator's value for one beam, given the transmittances along the camera segment and the
// beam and sigma_s at the gather point.
vec3 beamRadiance(BeamRayHit hit, PhotonBeam beam, vec3 sigmaS, float g, vec3 trCam, vec3 trBeam) {
    precise float k = beamKernel(hit.u, beam.radius) * hgPhase(-hit.cosTheta, g) * hit.invSinTheta;
    precise vec3 l = sigmaS * beam.power * trCam * trBeam * k;
    return l;
}
