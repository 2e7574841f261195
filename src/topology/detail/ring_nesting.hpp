// SPDX-License-Identifier: GPL-3.0-or-later
// Nesting of disjoint rings by exact point-in-polygon tests, shared by infer_rings2() and the
// validators. Only orient2 and coordinate comparisons decide.
#pragma once
#include <algorithm>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/predicates.hpp"

namespace constrict::detail {

inline bool lex_less2(const double* p, const double* q) { return p[0] < q[0] || (p[0] == q[0] && p[1] < q[1]); }

// Is p strictly inside the ring? Crossing number of the ray to +x, half-open in y, exact.
// @pre p is not on the ring.
inline bool inside_ring(const PointSet& pts, const std::vector<int>& ring, const double* p) {
  bool in = false;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const double* a = pts[static_cast<std::size_t>(ring[i])];
    const double* b = pts[static_cast<std::size_t>(ring[(i + 1) % ring.size()])];
    if ((a[1] > p[1]) == (b[1] > p[1])) continue;
    // The edge crosses y = p.y right of p iff p is left of the edge directed upwards.
    if ((a[1] < b[1] ? orient2(a, b, p) : orient2(b, a, p)) > 0) in = !in;
  }
  return in;
}

// For each ring, the other rings that contain its first vertex (= the ring, as rings are disjoint).
// use_boxes: skip rings whose bounding box misses the vertex (O(R^2 + R·E_box) instead of O(R·E)).
inline std::vector<std::vector<int>> ring_containers(const PointSet& pts, const std::vector<const std::vector<int>*>& rings,
                                                     bool use_boxes) {
  struct Box { double x0, x1, y0, y1; };
  std::vector<Box> box(rings.size());
  for (std::size_t k = 0; k < rings.size(); ++k) {
    const double* f = pts[static_cast<std::size_t>(rings[k]->front())];
    Box b{f[0], f[0], f[1], f[1]};
    for (int v : *rings[k]) {
      const double* q = pts[static_cast<std::size_t>(v)];
      b = {std::min(b.x0, q[0]), std::max(b.x1, q[0]), std::min(b.y0, q[1]), std::max(b.y1, q[1])};
    }
    box[k] = b;
  }
  std::vector<std::vector<int>> out(rings.size());
  for (std::size_t k = 0; k < rings.size(); ++k) {
    const double* p = pts[static_cast<std::size_t>(rings[k]->front())];
    for (std::size_t j = 0; j < rings.size(); ++j) {
      const Box& b = box[j];
      if (j == k || (use_boxes && (p[0] < b.x0 || p[0] > b.x1 || p[1] < b.y0 || p[1] > b.y1))) continue;
      if (inside_ring(pts, *rings[j], p)) out[k].push_back(static_cast<int>(j));
    }
  }
  return out;
}

// The innermost container of each ring (the container with the most containers), or -1.
inline std::vector<int> innermost_parents(const std::vector<std::vector<int>>& containers) {
  std::vector<int> parent(containers.size(), -1);
  for (std::size_t k = 0; k < containers.size(); ++k)
    for (int j : containers[k])
      if (parent[k] < 0 || containers[static_cast<std::size_t>(j)].size() > containers[static_cast<std::size_t>(parent[k])].size())
        parent[k] = j;
  return parent;
}

}  // namespace constrict::detail
