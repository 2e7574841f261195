// SPDX-License-Identifier: GPL-3.0-or-later
// The state every stage of the 3D engine works on (docs/architecture.md): the tetrahedra (the
// Delaunay ones first, then those the star cavities make), their adjacency, which of them form
// the body, and which points are on its surface. Plus the few operations every stage needs: the
// surface tests of the removal rules (seed paper §4.2; spec gamma-graph.md §3.3), edge walks, the
// surface, the body check. Plain index arrays and doubles; no CGAL.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"
#include "core/detail/edge_key.hpp"
#include "core/detail/tet_faces.hpp"
#include "core/detail/union_find.hpp"

namespace constrict::detail {


// Tetrahedron states: outside the body, in the body, replaced by a star cavity (gone for good).
enum : std::uint8_t { kOutside = 0, kAlive = 1, kReplaced = 2 };

inline std::size_t uz(int i) { return static_cast<std::size_t>(i); }

inline std::array<int, 4> sorted4(std::array<int, 4> t) {
  std::sort(t.begin(), t.end());
  return t;
}

using Tets = std::vector<std::array<int, 4>>;

struct HeapEntry {
  double key;
  int tet;
  std::uint32_t version;  // the tetrahedron's version when pushed: stale entries are skipped
};

// Max-heap of tetrahedra by key; equal keys -> the smallest sorted vertex-id tuple first (a
// geometric key, not the index; spec gamma-graph.md §3.5).
class TetHeap {
 public:
  void push(const HeapEntry& e, const Tets& tets) {
    heap_.push_back(e);
    std::push_heap(heap_.begin(), heap_.end(), Less{&tets});
  }
  HeapEntry pop(const Tets& tets) {
    std::pop_heap(heap_.begin(), heap_.end(), Less{&tets});
    const HeapEntry e = heap_.back();
    heap_.pop_back();
    return e;
  }
  const HeapEntry& top() const { return heap_.front(); }
  bool empty() const { return heap_.empty(); }
  void clear() { heap_.clear(); }
  void reserve(std::size_t n) { heap_.reserve(n); }

 private:
  struct Less {
    const Tets* tets;
    bool operator()(const HeapEntry& a, const HeapEntry& b) const {
      if (a.key != b.key) return a.key < b.key;
      return sorted4((*tets)[uz(a.tet)]) > sorted4((*tets)[uz(b.tet)]);
    }
  };
  std::vector<HeapEntry> heap_;
};

struct Body3 {
  const PointSet* pts = nullptr;
  std::size_t n = 0;   // points
  std::size_t T0 = 0;  // Delaunay tetrahedra (tets[0, T0)); cavity tetrahedra follow
  Tets tets;           // vertices, positively oriented
  Tets nbr;            // neighbour across the face opposite vertex i (-1: convex hull)
  std::vector<std::uint8_t> state;  // kOutside / kAlive / kReplaced
  std::vector<std::uint32_t> ver;   // versions (heap entries)
  std::vector<std::uint32_t> mark;  // per-tetrahedron epoch marks of the searches
  std::uint32_t epoch = 0;
  std::vector<char> onb;  // point on the surface
  std::size_t n_onb = 0;

  const double* P(int v) const { return (*pts)[uz(v)]; }
  bool alive(int t) const { return t >= 0 && state[uz(t)] == kAlive; }
  bool boundary_face(int t, int i) const { return !alive(nbr[uz(t)][uz(i)]); }
  int surface_faces_of(int t) const;
  int local_index(int t, int vertex) const;
  // Marks the vertices of t as on the surface.
  void mark_on_surface(int t) {
    for (int x : tets[uz(t)])
      if (!onb[uz(x)]) {
        onb[uz(x)] = 1;
        ++n_onb;
      }
  }

  // Walks around the edge (tets[t][i], tets[t][j]) from t through the tetrahedra sharing it, in
  // direction dir (0 or 1), calling f(next) for each neighbour met: next < 0 at the convex hull,
  // next == t when the ring closes. Stops when f returns true.
  template <class F>
  void walk_edge(int t, int i, int j, int dir, F&& f) const;
  // Is the edge (tets[t][i], tets[t][j]) on the surface? (The walk meets a tetrahedron not in
  // the body before the ring closes.)
  bool edge_on_boundary(int t, int i, int j) const;
  // Is that edge an edge of some body tetrahedron other than t? (Both ways round an open ring.)
  bool edge_touches_body(int t, int i, int j) const;
  // Either question (body: edge_on_boundary, else edge_touches_body), but the walks stop after
  // `limit` tetrahedra: -1 then (undecided), else 1 (yes) or 0 (no).
  int edge_blocked_within(int t, int i, int j, bool body, int limit) const;
  // The tetrahedra around that edge, any state but replaced, t first.
  void edge_ring(int t, int i, int j, std::vector<int>& out) const;
  // side kAlive: is the body one face-connected piece? kOutside: does every tetrahedron outside
  // the body reach the convex hull through outside tetrahedra (no enclosed void)?
  bool side_connected(std::uint8_t side) const;
  // The face-connected components of the tetrahedra t with in(t): a union-find over all
  // tetrahedra (the others stay alone), made by one pass in tetrahedron order, whose neighbours
  // are mostly near (a search from one start jumps about the arrays).
  template <class In>
  UnionFind face_components(const In& in) const {
    UnionFind uf(tets.size());
    for (std::size_t t = 0; t < tets.size(); ++t) {
      if (!in(static_cast<int>(t))) continue;
      for (int m : nbr[t])
        if (m > static_cast<int>(t) && in(m)) uf.join(static_cast<int>(t), m);
    }
    return uf;
  }

  // Appends a tetrahedron (in the body, no neighbours yet); returns its index.
  int new_tet(const std::array<int, 4>& v);
  // The state of the start: every Delaunay tetrahedron in the body, the hull points on the
  // surface; the cavity tetrahedra dropped (nbr_delaunay: the adjacency before the first cavity).
  void reset_to_hull(Tets& nbr_delaunay);
  TriMesh3 surface() const;       // outward triangles of the body
  std::vector<int> inside() const;  // points not on the surface, ascending
  // Throws (CONSTRICT_CHECK) unless every body tetrahedron is positive and the body adjacency
  // is symmetric and shares faces.
  void check_body() const;
};

template <class F>
void Body3::walk_edge(int t, int i, int j, int dir, F&& f) const {
  const int a = tets[uz(t)][uz(i)], b = tets[uz(t)][uz(j)];
  int k = 0;
  while (k == i || k == j) ++k;
  int l = 0;
  while (l == i || l == j || l == k) ++l;
  int cur = t, exit_v = tets[uz(t)][uz(dir ? l : k)], keep = tets[uz(t)][uz(dir ? k : l)];
  for (std::size_t guard = 0; guard < tets.size() + 1; ++guard) {
    const int li = local_index(cur, exit_v);
    CONSTRICT_CHECK(li >= 0, "edge walk lost its way");
    const int nx = nbr[uz(cur)][uz(li)];
    if (f(nx) || nx < 0 || nx == t) return;
    int w = -1;
    for (int x : tets[uz(nx)])
      if (x != a && x != b && x != keep) w = x;
    exit_v = keep;
    keep = w;
    cur = nx;
  }
  CONSTRICT_CHECK(false, "edge walk did not terminate");
}

}  // namespace constrict::detail
