// For valgrind only (callgrind profiles): libhwy's static initialiser calls
// hwy::platform::TimerResolution(), which executes RDTSCP; valgrind stops with SIGILL on CPUs whose
// CPUID does not advertise it (the VMs of this workplace). libhwy is loaded by every tyndall binary
// (OpenImageIO -> libjxl, and the SIMD splat). Preloading this answers the call instead:
//   g++ -O2 -shared -fPIC -o /tmp/libhwy-valgrind-shim.so scripts/valgrind-hwy-shim.cpp
//   LD_PRELOAD=/tmp/libhwy-valgrind-shim.so valgrind --tool=callgrind build/app/tyndall ...
// Highway's runtime dispatch then picks what valgrind's CPUID reports (AVX2).
#include <cstdint>

namespace hwy::platform {
uint64_t TimerResolution() { return 1; }
}  // namespace hwy::platform
