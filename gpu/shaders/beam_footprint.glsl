// GLSL twin of beamFootprint() in cpu/beam_rasterizer.cpp (the derivation is there): a
// conservative film-space bound of the pixels whose primary ray can accept a beam, the convex hull
// of two discs (a, ra) and (b, rb) around the projected ends of the beam's clipped axis, or the
// whole film. The fragment shader decides exactly, so this only has to cover.

struct BeamFootprint {
    vec2 a;          // projected ends of the clipped axis, film pixels
    float ra;        // radius around a, film pixels
    vec2 b;
    float rb;
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
    BeamFootprint fp = BeamFootprint(vec2(0.0), 0.0, vec2(0.0), 0.0, false, false);
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
    vec2 da = min(abs(fp.a - center), center), db = min(abs(fp.b - center), center);
    float stretch = max(sqrt(1.0 + dot(da, da) / (f * f)), sqrt(1.0 + dot(db, db) / (f * f)));
    float coc = 0.0;
    if (lens > 0.0) {
        float invF = 1.0 / frame.focusDistance;
        coc = f * lens * max(abs(invF - 1.0 / (zMin - r)), abs(invF - 1.0 / (zMax + r)));
    }
    float margin = coc + 0.75;
    fp.ra = f * r / (c0.z - r) * stretch + margin;
    fp.rb = f * r / (c1.z - r) * stretch + margin;
    return fp;
}
