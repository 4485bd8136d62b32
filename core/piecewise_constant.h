#pragma once
// Piecewise-constant distributions over cells, for sampling tabulated functions (an environment
// map's texels): a discrete choice of a cell with probability proportional to its weight, plus
// the uniform remainder within it, so a caller that maps cells to regions of its own measure
// (solid angle, area) gets an exact pdf of weight / (total x region measure).
#include <cstddef>
#include <vector>

#include "core/sampling.h"

namespace tyndall {

/// A cell chosen by PiecewiseConstant1D/2D::sample.
struct CellSample1D {
    int index = 0;
    float remainder = 0;  ///< where u fell inside the cell's share of [0, 1), in [0, 1)
    float probability = 0;
};

/// n cells with weights w_i >= 0 (finite); cell i is chosen with probability w_i / sum w. All
/// weights zero (or n = 0 weights given as one zero): every cell equally likely.
class PiecewiseConstant1D {
public:
    PiecewiseConstant1D() = default;
    explicit PiecewiseConstant1D(const std::vector<double>& weights);

    /// The cell whose share of [0, 1) holds u (u in [0, 1)); never a zero-weight cell unless all are.
    CellSample1D sample(float u) const;
    float probability(int i) const { return float(m_cdf[size_t(i) + 1] - m_cdf[size_t(i)]); }
    int size() const { return int(m_cdf.size()) - 1; }
    /// Sum of the weights given.
    double total() const { return m_total; }

private:
    std::vector<double> m_cdf;  // size n + 1, m_cdf[0] = 0, m_cdf[n] = 1
    double m_total = 0;
};

/// A width x height grid of cells, weights row-major from row 0 (the top row): a row by the
/// marginal (sum of its weights), then a column by the row's conditional.
struct CellSample2D {
    int x = 0, y = 0;
    Vec2 remainder;       ///< in [0, 1)^2
    float probability = 0;
};

class PiecewiseConstant2D {
public:
    PiecewiseConstant2D() = default;
    PiecewiseConstant2D(const std::vector<double>& weights, int width, int height);

    /// u1 picks the row, u2 the column (both in [0, 1)).
    CellSample2D sample(float u1, float u2) const;
    float probability(int x, int y) const { return m_rows.probability(y) * m_columns[size_t(y)].probability(x); }
    double total() const { return m_rows.total(); }
    int width() const { return m_width; }
    int height() const { return m_height; }

private:
    int m_width = 0, m_height = 0;
    PiecewiseConstant1D m_rows;
    std::vector<PiecewiseConstant1D> m_columns;
};

}  // namespace tyndall
