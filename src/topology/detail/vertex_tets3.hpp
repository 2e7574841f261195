// SPDX-License-Identifier: GPL-3.0-or-later
// The tetrahedra at each vertex of a Delaunay tetrahedralization (CSR), shared by the stages of
// reconstruct_surfaces3() that look up surface faces among its tetrahedra (detail/surfaces3.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "constrict/delaunay.hpp"

namespace constrict::detail::surfaces3 {

// The tetrahedra at each vertex (CSR), to find the tetrahedra of a face without a hash table of
// all faces (a few surface faces are looked up among millions of Delaunay faces).
class VertexTets {
 public:
  explicit VertexTets(const Delaunay3& dt) : dt_(dt) {
    std::size_t n = 0;
    for (const auto& t : dt.tets)
      for (int v : t) n = std::max(n, uz(v) + 1);
    off_.assign(n + 1, 0);
    for (const auto& t : dt.tets)
      for (int v : t) ++off_[uz(v) + 1];
    for (std::size_t v = 0; v < n; ++v) off_[v + 1] += off_[v];
    at_.resize(uz(off_[n]));
    std::vector<int> fill(off_.begin(), off_.end() - 1);
    for (std::size_t t = 0; t < dt.tets.size(); ++t)
      for (int v : dt.tets[t]) at_[uz(fill[uz(v)]++)] = static_cast<int>(t);
  }
  // f(t, i) for every tetrahedron t whose face opposite its vertex i is (a, b, c), any order.
  template <class F>
  void for_face(int a, int b, int c, F&& f) const {
    if (a < 0 || uz(a) + 1 >= off_.size()) return;
    for (int k = off_[uz(a)]; k < off_[uz(a) + 1]; ++k) {
      const int t = at_[uz(k)];
      const auto& v = dt_.tets[uz(t)];
      int i = -1, hits = 0;
      for (int l = 0; l < 4; ++l) {
        if (v[uz(l)] == a || v[uz(l)] == b || v[uz(l)] == c)
          ++hits;
        else
          i = l;
      }
      if (hits == 3) f(t, i);
    }
  }
  // The tetrahedra at v, ascending.
  struct Range {
    const int *b, *e;
    const int* begin() const { return b; }
    const int* end() const { return e; }
    std::size_t size() const { return static_cast<std::size_t>(e - b); }
  };
  Range of(int v) const {
    if (v < 0 || uz(v) + 1 >= off_.size()) return {nullptr, nullptr};
    return {at_.data() + off_[uz(v)], at_.data() + off_[uz(v) + 1]};
  }
  bool is_face(int a, int b, int c) const {
    bool any = false;
    for_face(a, b, c, [&](int, int) { any = true; });
    return any;
  }

 private:
  const Delaunay3& dt_;
  std::vector<int> off_, at_;
};

}  // namespace constrict::detail::surfaces3
