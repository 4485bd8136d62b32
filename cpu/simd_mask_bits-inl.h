// MaskBits: a Highway mask as an integer, bit j set where lane j is set, for kernels that walk the
// few accepted lanes of a vector with ctz instead of compressing them (which AVX2 emulates with
// table lookups). For per-target code only: include it after hwy/highway.h inside a file that
// hwy/foreach_target.h re-includes; the guard below lets each target's pass define it again.
#if defined(TYNDALL_CPU_SIMD_MASK_BITS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TYNDALL_CPU_SIMD_MASK_BITS_INL_H_
#undef TYNDALL_CPU_SIMD_MASK_BITS_INL_H_
#else
#define TYNDALL_CPU_SIMD_MASK_BITS_INL_H_
#endif

#include <cstdint>
#include <cstring>

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace tyndall {
namespace HWY_NAMESPACE {

// Lanes beyond the 64th are not reported (no target here has more than 16 float lanes).
template <class D, class M>
HWY_INLINE uint64_t MaskBits(D d, M mask) {
    uint8_t bytes[8] = {};
    hwy::HWY_NAMESPACE::StoreMaskBits(d, mask, bytes);
    uint64_t bits;
    std::memcpy(&bits, bytes, sizeof bits);
    return bits;
}

}  // namespace HWY_NAMESPACE
}  // namespace tyndall
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
