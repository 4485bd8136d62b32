#include "core/density_grid.h"

#include <algorithm>

namespace tyndall {

double DensityGrid::integratedDensity() const {
    return integrateDensity(*this, bounds());
}

double integrateDensity(const DensityGrid& grid, const Bounds3& box, int cellsPerAxis) {
    const Bounds3 g = grid.bounds();
    Bounds3 b;
    b.lo = vmax(box.lo, g.lo);
    b.hi = vmin(box.hi, g.hi);
    if (b.empty() || cellsPerAxis < 1) return 0.0;
    const Vec3 step = b.diagonal() / float(cellsPerAxis);
    double sum = 0;
    for (int k = 0; k < cellsPerAxis; ++k)
        for (int j = 0; j < cellsPerAxis; ++j) {
            double row = 0;
            for (int i = 0; i < cellsPerAxis; ++i)
                row += grid.density(b.lo + Vec3((float(i) + 0.5f) * step.x, (float(j) + 0.5f) * step.y,
                                                (float(k) + 0.5f) * step.z));
            sum += row;
        }
    return sum * double(step.x) * double(step.y) * double(step.z);
}

}  // namespace tyndall
