// SPDX-License-Identifier: GPL-3.0-or-later
// Cell arithmetic for the uniform bucket grids over a bounding box (constrict2, refine2,
// validate2), scale free and overflow free for any finite coordinates. Lengths are kept in half
// units (x/2 - lo/2 instead of x - lo), which cannot overflow; for coordinates that are not
// subnormal, halving is exact and every value is exactly half the plain one, so the cells are the
// same as with the plain formulas. Cell indices are monotone in the coordinate: a box query over
// the cells of a box's corners finds everything inside the box, exactly.
#pragma once
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <limits>

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

}  // namespace constrict::detail
