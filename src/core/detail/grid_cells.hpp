// SPDX-License-Identifier: GPL-3.0-or-later
// Cell arithmetic for the uniform bucket grids over a bounding box (constrict2, refine2,
// validate2), scale free and overflow free for any finite coordinates. Lengths are kept in half
// units (x/2 - lo/2 instead of x - lo), which cannot overflow; for coordinates that are not
// subnormal, halving is exact and every value is exactly half the plain one, so the cells are the
// same as with the plain formulas. Cell indices are monotone in the coordinate: a box query over
// the cells of a box's corners finds everything inside the box, exactly.
#pragma once
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

namespace constrict::detail {

/// (hi - lo) / 2 without overflow, at least the smallest positive double (a cell edge divides it).
inline double half_span(double lo, double hi) noexcept {
  const double h = 0.5 * hi - 0.5 * lo;
  return h > 0 ? h : std::numeric_limits<double>::denorm_min();
}

/// sqrt(hw * hh / n): the edge of square cells holding about one of n points each in a box of
/// half spans hw, hh > 0, without underflow (tiny boxes) or overflow (huge ones).
inline double balanced_cell(double hw, double hh, std::size_t n) noexcept {
  const double dn = static_cast<double>(n);
  const double a = hw * hh / dn;
  if (a >= DBL_MIN && a <= DBL_MAX) return std::sqrt(a);
  return std::sqrt(hw) * std::sqrt(hh) / std::sqrt(dn);
}

/// Number of cells of edge half_cell covering a half span, in [1, max_cells].
inline int cell_count(double half, double half_cell, int max_cells) noexcept {
  const double c = std::ceil(half / half_cell);
  if (!(c > 1)) return 1;
  return c >= max_cells ? max_cells : static_cast<int>(c);
}

/// Cell of coordinate x in a grid starting at lo: floor((x/2 - lo/2) / half_cell), clamped to
/// [0, cells - 1] before the conversion (no out-of-range or NaN conversion to int).
inline int cell_of(double x, double lo, double half_cell, int cells) noexcept {
  const double f = std::floor((0.5 * x - 0.5 * lo) / half_cell);
  if (!(f > 0)) return 0;
  return f >= cells ? cells - 1 : static_cast<int>(f);
}

/// The largest coordinate magnitude of the box [lo_x, hi_x] x [lo_y, hi_y].
inline double box_magnitude(double lo_x, double lo_y, double hi_x, double hi_y) noexcept {
  return std::max({std::fabs(lo_x), std::fabs(hi_x), std::fabs(lo_y), std::fabs(hi_y)});
}

/// A uniform grid as cell_of() sees it: its corner, the largest coordinate magnitude of its box
/// (box_magnitude), half the cell edge and the cell counts.
struct GridFrame {
  double lo_x, lo_y, magnitude, half_cell;
  int nx, ny;
  int cx(double x) const noexcept { return cell_of(x, lo_x, half_cell, nx); }
  int cy(double y) const noexcept { return cell_of(y, lo_y, half_cell, ny); }
};

/// Most vertices of a shape for_rows_of_hull takes.
constexpr int kMaxHullVertices = 12;

/// Calls f(j, a, b) for rows j of cells with a <= b, such that the cells (i, j), a <= i <= b,
/// contain every cell (cell_of) of every point of the grid's box in the closed convex hull of
/// the m vertices v (m = 2: a segment, m = 3: a triangle, m > 3: a convex polygon, its vertices
/// in order around it). Row by row over the bounding box; in each row only the columns the shape crosses within the row and one row
/// above and below, widened by one column on each side. The widening is far larger than the
/// rounding of the interpolation (a few ulps of the coordinates) when a cell is wider than 2^-30
/// of the largest coordinate; otherwise, and for non-finite intermediates, the whole row of the
/// box is visited. So a box query with it finds the same points and segments as one over the
/// bounding box (exact), reading O(perimeter) cells instead of O(area): a long thin triangle
/// across the plane reads a strip, not a square (the 2D noisy-curve fallback,
/// docs/benchmarks.md). Precondition: 2 <= m <= kMaxHullVertices.
template <class F> void for_rows_of_hull(const GridFrame& g, const double* const* v, int m, F&& f) {
  double x0 = v[0][0], x1 = v[0][0], y0 = v[0][1], y1 = v[0][1];
  for (int k = 1; k < m; ++k) {
    x0 = std::min(x0, v[k][0]);
    x1 = std::max(x1, v[k][0]);
    y0 = std::min(y0, v[k][1]);
    y1 = std::max(y1, v[k][1]);
  }
  const int i0 = g.cx(x0), i1 = g.cx(x1), j0 = g.cy(y0), j1 = g.cy(y1);
  bool narrow = i1 - i0 > 2 && std::ldexp(g.half_cell, 30) > g.magnitude;
  // Half units from the grid's corner, as cell_of() computes them.
  double hx[kMaxHullVertices], hy[kMaxHullVertices];
  for (int k = 0; k < m; ++k) {
    hx[k] = 0.5 * v[k][0] - 0.5 * g.lo_x;
    hy[k] = 0.5 * v[k][1] - 0.5 * g.lo_y;
    narrow = narrow && std::isfinite(hx[k]) && std::isfinite(hy[k]);
  }
  const int edges = m == 2 ? 1 : m;
  for (int j = j0; j <= j1; ++j) {
    int a = i0, b = i1;
    if (narrow) {
      const double lo = (j - 1) * g.half_cell, hi = (j + 2) * g.half_cell;  // the row, one row either side
      double xl = HUGE_VAL, xh = -HUGE_VAL;
      for (int k = 0; k < edges; ++k) {
        const int l = (k + 1) % m;
        double t0 = 0, t1 = 1;  // the part of edge k->l inside the band
        const double dy = hy[l] - hy[k];
        if (dy != 0) {
          t0 = (lo - hy[k]) / dy;
          t1 = (hi - hy[k]) / dy;
          if (t0 > t1) std::swap(t0, t1);
          t0 = std::max(t0, 0.0);
          t1 = std::min(t1, 1.0);
          if (t0 > t1) continue;  // misses the widened band
        } else if (hy[k] < lo || hy[k] > hi) {
          continue;
        }
        for (const double t : {t0, t1}) {
          const double x = hx[k] + t * (hx[l] - hx[k]);
          xl = std::min(xl, x);
          xh = std::max(xh, x);
        }
      }
      if (xl > xh) continue;  // the shape does not reach this row
      if (std::isfinite(xl) && std::isfinite(xh)) {
        const auto column = [&](double x) {  // clamped before the conversion (no overflow)
          return static_cast<int>(std::min(static_cast<double>(g.nx), std::max(-1.0, std::floor(x / g.half_cell))));
        };
        a = std::max(i0, column(xl) - 1);
        b = std::min(i1, column(xh) + 1);
      }
    }
    if (a <= b) f(j, a, b);
  }
}

/// Calls f(i, j) for the cells of for_rows_of_hull, row by row.
template <class F> void for_cells_of_hull(const GridFrame& g, const double* const* v, int m, F&& f) {
  for_rows_of_hull(g, v, m, [&](int j, int a, int b) {
    for (int i = a; i <= b; ++i) f(i, j);
  });
}

}  // namespace constrict::detail
