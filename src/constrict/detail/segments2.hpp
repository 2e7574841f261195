// SPDX-License-Identifier: GPL-3.0-or-later
// Exact 2D segment tests shared by the constrictor and the polygon validator.
#pragma once
#include <algorithm>

#include "constrict/predicates.hpp"
#include "core/detail/semi_static.hpp"

namespace constrict::detail {

// (orient2_fast: core/detail/semi_static.hpp.)

// q and r lie on the same side of v along their common line (all three collinear).
inline bool same_side_collinear(const double* v, const double* q, const double* r) {
  if (q[0] != v[0]) return (q[0] > v[0]) == (r[0] > v[0]);
  return (q[1] > v[1]) == (r[1] > v[1]);
}

// p collinear with segment ab: p in the closed segment?
inline bool on_closed_segment(const double* a, const double* b, const double* p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
         std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

// Do the closed segments pq and rs share a point? Exact.
inline bool closed_segments_meet(const double* p, const double* q, const double* r, const double* s) {
  const int o1 = orient2_fast(p, q, r), o2 = orient2_fast(p, q, s);
  if (o1 * o2 > 0) return false;  // both ends of rs strictly on one side of pq
  const int o3 = orient2_fast(r, s, p), o4 = orient2_fast(r, s, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && on_closed_segment(p, q, r)) return true;
  if (o2 == 0 && on_closed_segment(p, q, s)) return true;
  if (o3 == 0 && on_closed_segment(r, s, p)) return true;
  if (o4 == 0 && on_closed_segment(r, s, q)) return true;
  return false;
}

}  // namespace constrict::detail
