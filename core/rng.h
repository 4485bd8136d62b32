#pragma once
// Deterministic random streams. Every random decision in a pass draws from a stream keyed by
// (seed, pass, index, purpose), never by thread id, so any thread count, CPU or GL, one process
// or many give the same samples. PCG32 (O'Neill 2014) seeded through SplitMix64 hashing.
#include <cstdint>

namespace tyndall {

/// What a stream is used for; part of the key so the photon and camera streams of a pass differ.
enum class StreamPurpose : uint32_t {
    PhotonPath = 1,
    CameraPath = 2,
    PixelJitter = 3,
    ReferencePath = 4,
    Transmittance = 5,
    DirectLight = 6,  ///< a camera path's shadow rays (--direct-light): drawn apart from its own stream
    PixelJitterRotation = 7,  ///< a pixel's offset of the film jitter's sequence (core/pixel_jitter.h)
    Equiangular = 8,  ///< a camera path's equiangular single scattering (cpu/equiangular.h)
    PhotonPlane = 9,  ///< a photon path's plane directions and lengths (core/photon_plane.h)
    MediumEmission = 10,  ///< a camera path's grid-medium emission, primary segment (cpu/segment_emission.h)
    LaterMediumEmission = 11,  ///< the same along its later segments
    LightChoiceRotation = 12,  ///< a pixel's offset of its shadow rays' light-choice sequence (core/pixel_jitter.h)
    FilmLight = 13,  ///< a pixel's light-directed camera ray near a light's image: its film position, lens point and path (cpu/camera_tracer.cpp)
    PrimaryTransmittance = 14,  ///< a camera path's transmittance through its primary grid segment (cpu/camera_tracer.cpp)
    Test = 99,
};

inline uint64_t splitMix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

class Rng {
public:
    Rng() : Rng(0, 0) {}
    Rng(uint64_t state, uint64_t sequence) { seed(state, sequence); }

    /// The stream for one unit of work: photon path `index` of pass `pass`, pixel `index` ...
    static Rng forKey(uint64_t seed, uint64_t pass, uint64_t index, StreamPurpose purpose) {
        uint64_t h = splitMix64(seed ^ splitMix64(pass ^ splitMix64(index ^ (uint64_t(purpose) << 56))));
        return Rng(h, splitMix64(h ^ 0x5851F42D4C957F2Dull));
    }

    void seed(uint64_t state, uint64_t sequence) {
        m_state = 0;
        m_inc = (sequence << 1u) | 1u;
        nextUInt();
        m_state += state;
        nextUInt();
    }

    uint32_t nextUInt() {
        uint64_t old = m_state;
        m_state = old * 6364136223846793005ull + m_inc;
        uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
    }

    /// Uniform float in [0, 1), never 1.
    float uniform() { return float(nextUInt() >> 8) * 0x1p-24f; }
    double uniformDouble() { return double((uint64_t(nextUInt()) << 21) ^ nextUInt()) * 0x1p-53; }

private:
    uint64_t m_state = 0;
    uint64_t m_inc = 1;
};

}  // namespace tyndall
