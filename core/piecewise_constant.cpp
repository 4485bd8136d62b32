#include "core/piecewise_constant.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace tyndall {

PiecewiseConstant1D::PiecewiseConstant1D(const std::vector<double>& weights) {
    const size_t n = std::max<size_t>(weights.size(), 1);
    m_cdf.assign(n + 1, 0.0);
    for (size_t i = 0; i < weights.size(); ++i) {
        TYNDALL_CHECK(weights[i] >= 0 && std::isfinite(weights[i]), "distribution weight negative or not finite");
        m_cdf[i + 1] = m_cdf[i] + weights[i];
    }
    m_total = m_cdf[n];
    for (size_t i = 1; i <= n; ++i) m_cdf[i] = m_total > 0 ? m_cdf[i] / m_total : double(i) / double(n);
    m_cdf[n] = 1.0;
}

CellSample1D PiecewiseConstant1D::sample(float u) const {
    const int n = size();
    // The first i with cdf[i + 1] > u: u lies in [cdf[i], cdf[i + 1]), a cell of non-zero width.
    auto it = std::upper_bound(m_cdf.begin() + 1, m_cdf.end(), double(u));
    int i = std::min(int(it - m_cdf.begin()) - 1, n - 1);
    while (i > 0 && !(m_cdf[size_t(i) + 1] > m_cdf[size_t(i)])) --i;  // u rounded onto the end
    CellSample1D s;
    s.index = i;
    const double lo = m_cdf[size_t(i)], width = m_cdf[size_t(i) + 1] - lo;
    s.probability = float(width);
    s.remainder = width > 0 ? float(std::clamp((double(u) - lo) / width, 0.0, 1.0)) : 0.0f;
    if (s.remainder >= 1.0f) s.remainder = std::nextafter(1.0f, 0.0f);
    return s;
}

PiecewiseConstant2D::PiecewiseConstant2D(const std::vector<double>& weights, int width, int height)
    : m_width(width), m_height(height) {
    TYNDALL_CHECK(width > 0 && height > 0 && weights.size() == size_t(width) * size_t(height),
                  "distribution size does not match its weights");
    std::vector<double> rowSums(size_t(height), 0.0);
    m_columns.reserve(size_t(height));
    for (int y = 0; y < height; ++y) {
        std::vector<double> row(weights.begin() + ptrdiff_t(y) * width, weights.begin() + ptrdiff_t(y + 1) * width);
        m_columns.emplace_back(row);
        rowSums[size_t(y)] = m_columns.back().total();
    }
    m_rows = PiecewiseConstant1D(rowSums);
}

CellSample2D PiecewiseConstant2D::sample(float u1, float u2) const {
    const CellSample1D row = m_rows.sample(u1);
    const CellSample1D column = m_columns[size_t(row.index)].sample(u2);
    CellSample2D s;
    s.x = column.index;
    s.y = row.index;
    s.remainder = {column.remainder, row.remainder};
    s.probability = row.probability * column.probability;
    return s;
}

}  // namespace tyndall
