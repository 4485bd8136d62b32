// The exact estimator for this pixel's primary ray and the billboard's beam, added into the
// RGBA32F target (blending ONE, ONE). Film row 0 is the top row; GL's window origin is the bottom.

flat in int vBeam;
layout(location = 0) out vec4 radiance;

void main() {
    int x = int(gl_FragCoord.x);
    int y = frame.filmSize.y - 1 - int(gl_FragCoord.y);
    vec3 l = pixelRadiance(y * frame.filmSize.x + x, vBeam);
    if (l == vec3(0.0)) discard;
    radiance = vec4(l, 0.0);
}
