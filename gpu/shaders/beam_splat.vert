// One camera-facing billboard per beam: the film-space rectangle around the beam's footprint
// capsule (beam_footprint.glsl), six vertices (two triangles) per beam, no vertex attributes.
// Beams that cannot be seen get a zero-area quad; beams passing by the camera cover the film.

flat out int vBeam;
// The beam and its medium: a software rasterizer, which loads per fragment, need not load them.
flat out vec4 vBeamRows[3];
flat out vec4 vMediumRows[2];

const int kCorner[6] = int[6](0, 1, 2, 2, 1, 3);  // bit 0: b end, bit 1: +across

void main() {
    int b = gl_VertexID / 6;
    int corner = kCorner[gl_VertexID % 6];
    vBeam = b;
    PhotonBeam beam = beams[b];
    vBeamRows[0] = vec4(beam.origin, beam.tMax);
    vBeamRows[1] = vec4(beam.dir, beam.radius);
    vBeamRows[2] = vec4(beam.power, intBitsToFloat(beam.medium));
    if (beam.medium < 0) {
        gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
        return;
    }
    Medium med = media[beam.medium];
    vMediumRows[0] = vec4(med.sigmaS, med.g);
    vMediumRows[1] = vec4(med.sigmaT, intBitsToFloat(med.volume));
    BeamFootprint fp = beamFootprint(beam);
    if (!fp.visible) {
        gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
        return;
    }
    vec2 size = vec2(frame.filmSize);
    vec2 lo = min(fp.a, fp.b) - fp.radius, hi = max(fp.a, fp.b) + fp.radius;
    // Covering far more than the film (or non-finite): the film itself is the same set of pixels.
    bool huge = !(all(greaterThan(lo, -4.0 * size)) && all(lessThan(hi, 5.0 * size)));
    vec2 ndc;
    if (fp.fullScreen || huge) {
        ndc = vec2((corner & 1) != 0 ? 1.0 : -1.0, (corner & 2) != 0 ? 1.0 : -1.0);
    } else {
        vec2 axis = fp.b - fp.a;
        float len = length(axis);
        vec2 along = len > 0.0 ? axis / len : vec2(1.0, 0.0);
        vec2 across = vec2(-along.y, along.x);
        vec2 film = ((corner & 1) != 0 ? fp.b + along * fp.radius : fp.a - along * fp.radius) +
                    across * ((corner & 2) != 0 ? fp.radius : -fp.radius);
        ndc = vec2(2.0 * film.x / size.x - 1.0, 1.0 - 2.0 * film.y / size.y);
    }
    gl_Position = vec4(ndc, 0.0, 1.0);
}
