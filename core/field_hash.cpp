// The content hashes of the fields media read (DensityGrid::contentHash, EmissionField::contentHash
// and GridEmission's): what a checkpoint's scene hash mixes in so that a resume sees any change to
// a grid, however small. OpenVDB grids hash their own storage (loading/vdb_grid.cpp).
#include "core/checkpoint.h"
#include "core/density_grid.h"
#include "core/grid_emission.h"
#include "core/medium.h"

namespace tyndall {

namespace {
/// `h` mixed with f(p) at the centres of a 32^3 lattice over `b` (and `b` itself).
template <class F>
uint64_t hashLattice(const Bounds3& b, F f, uint64_t h) {
    h = fnv1a(&b.lo, sizeof b.lo, fnv1a(&b.hi, sizeof b.hi, h));
    if (b.empty()) return h;
    constexpr int kSide = 32;
    const Vec3 cell = b.diagonal() * (1.0f / kSide);
    for (int k = 0; k < kSide; ++k)
        for (int j = 0; j < kSide; ++j)
            for (int i = 0; i < kSide; ++i) {
                const auto v = f(b.lo + Vec3((i + 0.5f) * cell.x, (j + 0.5f) * cell.y, (k + 0.5f) * cell.z));
                h = fnv1a(&v, sizeof v, h);
            }
    return h;
}
}  // namespace

uint64_t DensityGrid::contentHash(uint64_t h) const {
    return hashLattice(bounds(), [this](const Vec3& p) { return density(p); }, h);
}

uint64_t EmissionField::contentHash(uint64_t h, const Bounds3& where) const {
    return hashLattice(where, [this](const Vec3& p) { return radiance(p); }, h);
}

uint64_t GridEmission::contentHash(uint64_t h, const Bounds3&) const {
    h = m_values->contentHash(h);
    const float params[8] = {m_color.r, m_color.g,        m_color.b,          m_blackbody ? 1.0f : 0.0f,
                             m_bb.scale, m_bb.temperatureScale, m_bb.temperatureOffset, m_ambient};
    return fnv1a(params, sizeof params, h);
}

}  // namespace tyndall
