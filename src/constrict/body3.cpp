// SPDX-License-Identifier: GPL-3.0-or-later
// Body3: the shared state of the 3D stages (detail/body3.hpp, docs/architecture.md).
#include "constrict/detail/body3.hpp"

#include <limits>

#include "constrict/predicates.hpp"
#include "core/detail/first_index.hpp"
#include "core/detail/ordered_pack.hpp"

namespace constrict::detail {

int Body3::surface_faces_of(int t) const {
  int k = 0;
  for (int i = 0; i < 4; ++i) k += boundary_face(t, i) ? 1 : 0;
  return k;
}

int Body3::local_index(int t, int vertex) const {
  const auto& v = tets[uz(t)];
  for (int l = 0; l < 4; ++l)
    if (v[uz(l)] == vertex) return l;
  return -1;
}

bool Body3::edge_on_boundary(int t, int i, int j) const {
  return edge_blocked_within(t, i, j, true, std::numeric_limits<int>::max()) == 1;
}

bool Body3::edge_touches_body(int t, int i, int j) const {
  return edge_blocked_within(t, i, j, false, std::numeric_limits<int>::max()) == 1;
}

int Body3::edge_blocked_within(int t, int i, int j, bool body, int limit) const {
  int steps = 0;
  bool hit = false, hull = false, too_long = false;
  // body: a tetrahedron not in the body (the convex hull too) puts the edge on the surface;
  // otherwise one in the body touches it.
  const auto step = [&](int nx) {
    if (++steps > limit) return too_long = true;
    if (nx < 0) {
      hull = true;
      hit = body;
      return true;
    }
    hit = body ? !alive(nx) : alive(nx);
    return hit;
  };
  walk_edge(t, i, j, 0, step);
  if (!body && !hit && !too_long && hull) walk_edge(t, i, j, 1, step);  // open at the hull: the other way too
  return too_long ? -1 : hit ? 1 : 0;
}

void Body3::edge_ring(int t, int i, int j, std::vector<int>& out) const {
  out.clear();
  out.push_back(t);
  bool closed = false;
  for (int dir = 0; dir < 2 && !closed; ++dir)
    walk_edge(t, i, j, dir, [&](int nx) {
      if (nx < 0) return true;  // open ring: walk the other way
      if (nx == t) {
        closed = true;
        return true;
      }
      out.push_back(nx);
      return false;
    });
}

// By face_components: a torus of 3·10^5 random points (5 M tetrahedra) in its auto mode, 398 perf
// samples with a depth-first search from one tetrahedron, 249 so.
bool Body3::side_connected(std::uint8_t side) const {
  const auto in = [&](int t) { return state[uz(t)] == side; };
  UnionFind uf = face_components(in);
  const std::size_t count = tets.size();
  if (side == kAlive) {  // one piece
    int root = -1;
    for (std::size_t t = 0; t < count; ++t) {
      if (state[t] != side) continue;
      const int r = uf.find(static_cast<int>(t));
      if (root < 0) root = r;
      else if (r != root) return false;
    }
    return root >= 0;
  }
  // Every piece touches the convex hull (a tetrahedron with a face on it: neighbour -1).
  std::vector<char> at_hull(count, 0);  // per root
  for (std::size_t t = 0; t < count; ++t) {
    if (state[t] != side) continue;
    for (int m : nbr[t])
      if (m < 0) at_hull[uz(uf.find(static_cast<int>(t)))] = 1;
  }
  for (std::size_t t = 0; t < count; ++t)
    if (state[t] == side && !at_hull[uz(uf.find(static_cast<int>(t)))]) return false;
  return true;
}

int Body3::new_tet(const std::array<int, 4>& v) {
  tets.push_back(v);
  nbr.push_back({{-1, -1, -1, -1}});
  state.push_back(kAlive);
  ver.push_back(0);
  mark.push_back(0);
  return static_cast<int>(tets.size() - 1);
}

void Body3::reset_to_hull(Tets& nbr_delaunay) {
  if (tets.size() > T0) {  // undo the cavities: the Delaunay tetrahedra again
    tets.resize(T0);
    nbr.swap(nbr_delaunay);
    nbr.resize(T0);
    ver.resize(T0);
    mark.resize(T0);
  }
  Tets().swap(nbr_delaunay);
  state.assign(T0, kAlive);
  for (auto& v : ver) ++v;
  onb.assign(n, 0);
  n_onb = 0;
  for (std::size_t t = 0; t < T0; ++t)
    for (int i = 0; i < 4; ++i)
      if (nbr[t][uz(i)] < 0)
        for (int k = 0; k < 3; ++k) {
          const int x = tets[t][uz(kFaceOut[i][k])];
          if (!onb[uz(x)]) {
            onb[uz(x)] = 1;
            ++n_onb;
          }
        }
}

TriMesh3 Body3::surface() const {
  // In tetrahedron order, in parallel (ordered_pack: the sequential order at any thread count).
  TriMesh3 m;
  m.triangles = ordered_pack<std::array<int, 3>>(tets.size(), [&](std::size_t t, const auto& push) {
    if (state[t] != kAlive) return;
    const auto& v = tets[t];
    for (int i = 0; i < 4; ++i)
      if (boundary_face(static_cast<int>(t), i))
        push({{v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][1])], v[uz(kFaceOut[i][2])]}});
  });
  return m;
}

std::vector<int> Body3::inside() const {
  std::vector<int> r;
  for (std::size_t v = 0; v < n; ++v)
    if (!onb[v]) r.push_back(static_cast<int>(v));
  return r;
}

void Body3::check_body() const {
  // The fault of tetrahedron t (0: none); the first faulty one in index order, found in parallel.
  enum Fault { kNone, kNotPositive, kNotSymmetric, kFaceNotShared };
  const auto fault = [&](std::size_t t) {
    if (state[t] != kAlive) return kNone;
    const auto& v = tets[t];
    if (orient3(P(v[0]), P(v[1]), P(v[2]), P(v[3])) <= 0) return kNotPositive;
    for (int i = 0; i < 4; ++i) {
      const int m = nbr[t][uz(i)];
      if (!alive(m)) continue;
      int j = -1;
      for (int l = 0; l < 4; ++l)
        if (nbr[uz(m)][uz(l)] == static_cast<int>(t)) j = l;
      if (j < 0) return kNotSymmetric;
      std::array<int, 3> f1{}, f2{};
      int k1 = 0, k2 = 0;
      for (int l = 0; l < 4; ++l) {
        if (l != i) f1[uz(k1++)] = v[uz(l)];
        if (l != j) f2[uz(k2++)] = tets[uz(m)][uz(l)];
      }
      std::sort(f1.begin(), f1.end());
      std::sort(f2.begin(), f2.end());
      if (f1 != f2) return kFaceNotShared;
    }
    return kNone;
  };
  const std::size_t first = first_index(tets.size(), [&](std::size_t t) { return fault(t) != kNone; });
  if (first == tets.size()) return;
  const Fault f = fault(first);
  CONSTRICT_CHECK(f != kNotPositive, "body tetrahedron not positive");
  CONSTRICT_CHECK(f != kNotSymmetric, "body adjacency not symmetric");
  CONSTRICT_CHECK(f != kFaceNotShared, "body neighbours do not share the face");
}

}  // namespace constrict::detail
