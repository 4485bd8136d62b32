// GLSL twin of core/transmittance.h and core/density_volume.h: stored-distance transmittance and
// the dense density volumes of grid media (same trilinear rule as DensityVolume::sample).

#if TYNDALL_GRID_MEDIA
// Fraction of the pixel's (beam's) stored free-flight distances that lie beyond s (t).
float rayTransmittance(int pixel, float s) {
    int n = frame.freeFlightsPerRay;
    int beyond = 0;
    for (int k = 0; k < n; ++k) beyond += rayFreeFlights[pixel * n + k] > s ? 1 : 0;
    return float(beyond) / float(n);
}

float beamTransmittance(int beam, float t) {
    int n = frame.freeFlightsPerBeam;
    int beyond = 0;
    for (int k = 0; k < n; ++k) beyond += beamFreeFlights[beam * n + k] > t ? 1 : 0;
    return float(beyond) / float(n);
}

float volumeLattice(Volume v, int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= v.size.x || j >= v.size.y || k >= v.size.z) return 0.0;
    return voxels[v.offset + uint((k * v.size.y + j) * v.size.x + i)];
}

float lerpDensity(float a, float b, float t) {
    precise float r = a + (b - a) * t;  // not mix(): DensityVolume::sample's rounding
    return r;
}

float volumeDensity(int volume, vec3 p) {
    Volume v = volumes[volume];
    precise vec3 q;
    for (int r = 0; r < 3; ++r) {
        vec4 m = v.worldToIndex[r];
        q[r] = m.x * p.x + m.y * p.y + m.z * p.z + m.w;
    }
    precise vec3 f = floor(q);
    if (!(f.x > -2.0 && f.y > -2.0 && f.z > -2.0 && f.x < float(v.size.x) && f.y < float(v.size.y) &&
          f.z < float(v.size.z)))
        return 0.0;
    int i = int(f.x), j = int(f.y), k = int(f.z);
    precise vec3 w = q - f;
    float c00 = lerpDensity(volumeLattice(v, i, j, k), volumeLattice(v, i + 1, j, k), w.x);
    float c10 = lerpDensity(volumeLattice(v, i, j + 1, k), volumeLattice(v, i + 1, j + 1, k), w.x);
    float c01 = lerpDensity(volumeLattice(v, i, j, k + 1), volumeLattice(v, i + 1, j, k + 1), w.x);
    float c11 = lerpDensity(volumeLattice(v, i, j + 1, k + 1), volumeLattice(v, i + 1, j + 1, k + 1), w.x);
    return lerpDensity(lerpDensity(c00, c10, w.y), lerpDensity(c01, c11, w.y), w.z);
}

#endif  // TYNDALL_GRID_MEDIA

// Medium::sigmaSAt.
vec3 sigmaSAt(Medium m, vec3 p) {
#if TYNDALL_GRID_MEDIA
    return m.volume < 0 ? m.sigmaS : m.sigmaS * volumeDensity(m.volume, p);
#else
    return m.sigmaS;
#endif
}
