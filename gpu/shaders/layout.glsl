// GLSL twin of gpu/gl_layout.h: the structs and buffers shared with C++ (bindings listed there).

// Grid media compiled in or out: software rasterizers run both sides of every branch, so a
// scene without grid media gets a shader without their code (GlBeamSplatter defines it).
#ifndef TYNDALL_GRID_MEDIA
#define TYNDALL_GRID_MEDIA 1
#endif

struct PrimaryRay {
    vec3 origin;
    float tMax;
    vec3 dir;
    int medium;
};

struct PhotonBeam {
    vec3 origin;
    float tMax;
    vec3 dir;
    float radius;
    vec3 power;
    int medium;
};

struct Medium {
    vec3 sigmaS;
    float g;
    vec3 sigmaT;
    int volume;  // -1 = homogeneous
};

struct Volume {
    vec4 worldToIndex[3];
    ivec3 size;
    uint offset;
};

layout(std140, binding = 0) uniform SplatFrame {
    vec3 cameraPosition;
    float tanHalfX;
    vec3 cameraRight;
    float tanHalfY;
    vec3 cameraUp;
    float focalPixels;
    vec3 cameraForward;
    float lensRadius;
    ivec2 filmSize;
    float focusDistance;
    int freeFlightsPerRay;
    int freeFlightsPerBeam;
    int beamCount;
} frame;

layout(std430, binding = 0) readonly buffer PrimaryRays { PrimaryRay rays[]; };
layout(std430, binding = 1) readonly buffer RayFreeFlights { float rayFreeFlights[]; };
layout(std430, binding = 2) readonly buffer Beams { PhotonBeam beams[]; };
layout(std430, binding = 3) readonly buffer BeamFreeFlights { float beamFreeFlights[]; };
layout(std430, binding = 4) readonly buffer Media { Medium media[]; };
layout(std430, binding = 5) readonly buffer Volumes { Volume volumes[]; };
layout(std430, binding = 6) readonly buffer Voxels { float voxels[]; };
