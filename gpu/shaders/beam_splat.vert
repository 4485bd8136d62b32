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
    vec2 lo = min(fp.a - fp.ra, fp.b - fp.rb), hi = max(fp.a + fp.ra, fp.b + fp.rb);
    // Covering far more than the film (or non-finite): the film itself is the same set of pixels.
    bool huge = !(all(greaterThan(lo, -4.0 * size)) && all(lessThan(hi, 5.0 * size)));
    vec2 film;
    if (fp.fullScreen || huge) {
        film = vec2((corner & 1) != 0 ? size.x : 0.0, (corner & 2) != 0 ? size.y : 0.0);
    } else {
        // The hull of the two discs lies between its two outer tangent lines and between the lines
        // across the axis at -ra and len + rb: the trapezoid they enclose is the billboard. With
        // sin(phi) = (ra - rb) / len the tangent on side s has outward normal s n cos(phi) + u sin(phi).
        vec2 axis = fp.b - fp.a;
        float len = length(axis);
        vec2 u = len > 0.0 ? axis / len : vec2(1.0, 0.0);
        vec2 n = vec2(-u.y, u.x);
        float sinPhi = len > 0.0 ? (fp.ra - fp.rb) / len : 1.0;
        float cosPhi = sqrt(max(0.0, 1.0 - sinPhi * sinPhi));
        float along = (corner & 1) != 0 ? len + fp.rb : -fp.ra;
        float across;
        if (cosPhi > 0.25) {  // the tangent at distance ra from a, met at `along`
            across = (fp.ra - along * sinPhi) / cosPhi;
        } else {  // one disc (nearly) holds the other: the rectangle around both
            along = (corner & 1) != 0 ? max(fp.ra, len + fp.rb) : min(-fp.ra, len - fp.rb);
            across = max(fp.ra, fp.rb);
        }
        film = fp.a + u * along + n * ((corner & 2) != 0 ? across : -across);
    }
    gl_Position = vec4(2.0 * film.x / size.x - 1.0, 1.0 - 2.0 * film.y / size.y, 0.0, 1.0);
}
