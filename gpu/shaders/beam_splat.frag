// The exact estimator for this pixel's primary ray and the billboard's beam, added into the
// RGBA32F target (blending ONE, ONE). Film row 0 is the top row; GL's window origin is the bottom.

flat in int vBeam;
flat in vec4 vBeamRows[3];
flat in vec4 vMediumRows[2];
layout(location = 0) out vec4 radiance;

void main() {
    int x = int(gl_FragCoord.x);
    int y = frame.filmSize.y - 1 - int(gl_FragCoord.y);
    PhotonBeam beam = PhotonBeam(vBeamRows[0].xyz, vBeamRows[0].w, vBeamRows[1].xyz, vBeamRows[1].w,
                                 vBeamRows[2].xyz, floatBitsToInt(vBeamRows[2].w));
    Medium med = Medium(vMediumRows[0].xyz, vMediumRows[0].w, vMediumRows[1].xyz, floatBitsToInt(vMediumRows[1].w));
    vec3 l = pixelRadiance(y * frame.filmSize.x + x, beam, med, vBeam);
    if (l == vec3(0.0)) discard;
    radiance = vec4(l, 0.0);
}
