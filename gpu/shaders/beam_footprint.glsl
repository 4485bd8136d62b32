// GLSL twin of beamFootprint() in cpu/beam_rasterizer.cpp: a conservative film-space bound of the
// pixels whose primary ray can accept a beam (the derivation is there). The fragment shader
// decides exactly, so this only has to cover; both twins use the same bound so that the CPU and
// GL splatters visit the same pixels.

struct BeamFootprint {
    vec2 a;          // projected ends of the clipped axis, film pixels
    vec2 b;
    float radius;    // capsule radius, film pixels
    bool fullScreen;
    bool visible;
};

vec3 toCameraSpace(vec3 p) {
    vec3 v = p - frame.cameraPosition;
    return vec3(dot(v, frame.cameraRight), dot(v, frame.cameraUp), dot(v, frame.cameraForward));
}

// Clips the axis parameter range [lo, hi] to the half-space g >= 0 (g linear along the axis).
bool clipAxis(float ga, float gb, inout float lo, inout float hi) {
    if (ga < 0.0 && gb < 0.0) return false;
    if (ga < 0.0) lo = max(lo, ga / (ga - gb));
    else if (gb < 0.0) hi = min(hi, ga / (ga - gb));
    return lo <= hi;
}

BeamFootprint beamFootprint(PhotonBeam beam) {
    BeamFootprint fp;
    fp.a = vec2(0.0);
    fp.b = vec2(0.0);
    fp.radius = 0.0;
    fp.fullScreen = false;
    fp.visible = false;
    float tx = frame.tanHalfX, ty = frame.tanHalfY, f = frame.focalPixels;
    float r = beam.radius, lens = frame.lensRadius;
    vec3 a = toCameraSpace(beam.origin), b = toCameraSpace(beam.origin + beam.dir * beam.tMax);

    float spread = lens > 0.0 ? lens / frame.focusDistance : 0.0;
    float lx = tx + spread, ly = ty + spread;
    float sx = lens + r * sqrt(1.0 + lx * lx), sy = lens + r * sqrt(1.0 + ly * ly);
    float lo = 0.0, hi = 1.0;
    if (!clipAxis(a.z + r, b.z + r, lo, hi)) return fp;
    if (!clipAxis(a.z * lx - a.x + sx, b.z * lx - b.x + sx, lo, hi)) return fp;
    if (!clipAxis(a.z * lx + a.x + sx, b.z * lx + b.x + sx, lo, hi)) return fp;
    if (!clipAxis(a.z * ly - a.y + sy, b.z * ly - b.y + sy, lo, hi)) return fp;
    if (!clipAxis(a.z * ly + a.y + sy, b.z * ly + b.y + sy, lo, hi)) return fp;
    fp.visible = true;
    vec3 c0 = a + (b - a) * lo, c1 = a + (b - a) * hi;
    float zMin = min(c0.z, c1.z), zMax = max(c0.z, c1.z);
    if (zMin <= 2.0 * (r + lens)) {
        fp.fullScreen = true;
        return fp;
    }
    vec2 center = 0.5 * vec2(frame.filmSize);
    fp.a = vec2(center.x + f * c0.x / c0.z, center.y - f * c0.y / c0.z);
    fp.b = vec2(center.x + f * c1.x / c1.z, center.y - f * c1.y / c1.z);
    float tan2 = max(dot(c0.xy, c0.xy) / (c0.z * c0.z), dot(c1.xy, c1.xy) / (c1.z * c1.z));
    float coc = 0.0;
    if (lens > 0.0) {
        float invF = 1.0 / frame.focusDistance;
        coc = f * lens * max(abs(invF - 1.0 / (zMin - r)), abs(invF - 1.0 / (zMax + r)));
    }
    fp.radius = f * r * sqrt(1.0 + tan2) / (zMin - r) + coc + 1.5;
    return fp;
}
