// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "cavity" of the 3D engine: the star-cavity re-tetrahedralization around a point that the
// removal (or, mirrored, the growth) rules cannot bring to the surface (seed paper §4.3;
// docs/reconstruction-3d.md §3, §4.7). Every test is an exact orient3.
#include <algorithm>
#include <unordered_map>

#include "constrict/criterion.hpp"
#include "constrict/detail/stages3.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/predicates.hpp"

namespace constrict::detail {
namespace {

// A star larger than this is not searched further (the point then stays where it is).
constexpr std::size_t kMaxStar = 100000;
// Target search rounds: face-hop depth around the star, and how many ranked targets each tries.
constexpr int kDepths[3] = {3, 8, 24};
constexpr std::size_t kTriesFirst = 6, kTriesLater = 24;
// Work bound of all placements of one pass (tetrahedra visited by the star, target and visibility
// searches): per tetrahedron of the triangulation, plus a floor. Points along a thin rod have
// stars of thousands of tetrahedra at every point and no cavity that works; unbounded, 2 000 of
// them took 10 s and 4 000 took 70 s (docs/reconstruction-3d.md §4.10). The largest use measured
// over the shared 3D and topology sets is far below (ibid.).
constexpr std::size_t kWorkPerTet = 64, kWorkFloor = std::size_t(1) << 20;

// A face of the cavity's boundary, outward from it, and the tetrahedron behind it (-1: hull).
struct BFace {
  int a, b, c, outside;
};

}  // namespace

bool Cavity3::in_side(int m) const {
  return side_ == CavitySide::Outside ? m >= 0 && b_.state[uz(m)] == kOutside : b_.alive(m);
}

void Cavity3::index_vertices() {
  s_.work = 0;
  s_.capped = false;
  s_.work_limit = kWorkPerTet * b_.tets.size() + kWorkFloor;
  s_.vert_tet.assign(b_.n, -1);
  const std::uint8_t want = side_ == CavitySide::Outside ? kOutside : kAlive;
  for (std::size_t t = 0; t < b_.tets.size(); ++t)
    if (b_.state[t] == want)
      for (int x : b_.tets[t]) s_.vert_tet[uz(x)] = static_cast<int>(t);
}

// The tetrahedra of the side around vertex p; false when p is on the surface.
bool Cavity3::star_of(int p, std::vector<int>& out) {
  const bool mirror = side_ == CavitySide::Outside;
  out.clear();
  const int t0 = s_.vert_tet[uz(p)];
  if (!in_side(t0) || b_.local_index(t0, p) < 0) return false;
  ++b_.epoch;
  b_.mark[uz(t0)] = b_.epoch;
  out.push_back(t0);
  for (std::size_t q = 0; q < out.size(); ++q) {
    const int t = out[q];
    for (int i = 0; i < 4; ++i) {
      if (b_.tets[uz(t)][uz(i)] == p) continue;
      const int m = b_.nbr[uz(t)][uz(i)];
      if (mirror && m < 0) continue;  // p on the convex hull: this hull face stays
      if (!in_side(m)) {              // p would be on the surface
        s_.work += out.size();
        return false;
      }
      if (b_.mark[uz(m)] != b_.epoch) {
        b_.mark[uz(m)] = b_.epoch;
        out.push_back(m);
      }
    }
    if (out.size() > kMaxStar) break;
  }
  s_.work += out.size();
  if (out.size() > kMaxStar) return false;
  return true;
}

// Rank of inserting p through surface face abc (the tet (a,b,c,p) removed by its one face).
double Cavity3::target_key(int a, int b, int c, int p) const {
  if (opt_.criterion != Criterion::MinAreaChange) return 1.0 - apex_gamma3(b_.P(a), b_.P(b), b_.P(c), b_.P(p));
  const double areas[4] = {triangle_area3(b_.P(a), b_.P(b), b_.P(c)), triangle_area3(b_.P(a), b_.P(b), b_.P(p)),
                           triangle_area3(b_.P(b), b_.P(c), b_.P(p)), triangle_area3(b_.P(c), b_.P(a), b_.P(p))};
  const bool bd[4] = {true, false, false, false};
  return -area_change_ratio3(areas, bd);
}

// Surface faces within `depth` face-hops of p's star that p sees from its side, best key first.
void Cavity3::targets_of(int p, const std::vector<int>& star, int depth, std::vector<Target>& out) {
  const bool mirror = side_ == CavitySide::Outside;
  out.clear();
  ++b_.epoch;
  std::vector<int> cur = star, next;
  for (int t : cur) b_.mark[uz(t)] = b_.epoch;
  for (int d = 0; d <= depth && !cur.empty(); ++d) {
    next.clear();
    s_.work += cur.size();
    for (int t : cur) {
      for (int i = 0; i < 4; ++i) {
        const int m = b_.nbr[uz(t)][uz(i)];
        if (mirror ? b_.alive(m) : !b_.alive(m)) {
          const auto& v = b_.tets[uz(t)];
          const int a = v[uz(kFaceOut[i][0])], b = v[uz(kFaceOut[i][1])], c = v[uz(kFaceOut[i][2])];
          if (orient3(b_.P(a), b_.P(b), b_.P(c), b_.P(p)) < 0) {
            std::array<int, 3> ids{{a, b, c}};
            std::sort(ids.begin(), ids.end());
            out.push_back({target_key(a, b, c, p), t, i, ids});
          }
        } else if (in_side(m) && b_.mark[uz(m)] != b_.epoch) {
          b_.mark[uz(m)] = b_.epoch;
          next.push_back(m);
        }
      }
    }
    std::swap(cur, next);
  }
  std::sort(out.begin(), out.end(),
            [](const Target& x, const Target& y) { return x.key != y.key ? x.key > y.key : x.ids < y.ids; });
}

// Visibility closure: grows U (marked in_u) until p sees every face of its boundary strictly from
// inside. False when U would cross the surface, exceed the size limit, or has p on its boundary.
bool Cavity3::grow_visible(int p, std::vector<int>& U, std::uint32_t in_u) {
  const bool mirror = side_ == CavitySide::Outside;
  std::vector<int> work = U;  // faces are re-scanned per added tet
  while (!work.empty()) {
    const int t = work.back();
    work.pop_back();
    if (b_.mark[uz(t)] != in_u) continue;
    for (int i = 0; i < 4; ++i) {
      const int m = b_.nbr[uz(t)][uz(i)];
      if (m >= 0 && b_.mark[uz(m)] == in_u) continue;
      const auto& v = b_.tets[uz(t)];
      const int a = v[uz(kFaceOut[i][0])], b = v[uz(kFaceOut[i][1])], c = v[uz(kFaceOut[i][2])];
      if (a == p || b == p || c == p) {
        if (mirror && m < 0) continue;  // a convex-hull face at p: it stays (cone side)
        return false;                   // p on U's boundary: cannot happen, be safe
      }
      if (orient3(b_.P(a), b_.P(b), b_.P(c), b_.P(p)) < 0) continue;  // visible
      if (!in_side(m)) return false;                                  // would cross the surface
      if (U.size() >= opt_.max_cavity_tets) return false;
      ++s_.work;
      b_.mark[uz(m)] = in_u;
      U.push_back(m);
      work.push_back(m);
    }
  }
  return true;
}

// Grows U = star(p) ∪ {tet behind the target face} until every face of its boundary is seen
// from p strictly from inside (orient3 < 0), then replaces U by the cone from p over its
// boundary. Returns false (and leaves everything unchanged) when U would have to grow across the
// surface, exceeds the size limit, swallows a vertex, or is not a sphere.
bool Cavity3::try_cavity(int p, const std::vector<int>& star, const Target& tg, CavityMade& made) {
  const bool mirror = side_ == CavitySide::Outside;
  ++s_.attempts;
  s_.work += star.size();
  ++b_.epoch;
  const std::uint32_t in_u = b_.epoch;
  std::vector<int> U;
  for (int t : star) {
    b_.mark[uz(t)] = in_u;
    U.push_back(t);
  }
  if (b_.mark[uz(tg.t)] != in_u) {
    b_.mark[uz(tg.t)] = in_u;
    U.push_back(tg.t);
  }
  if (!grow_visible(p, U, in_u)) return false;
  // U's boundary faces, outward from U; the edges opposite p of the hull faces at p (mirror).
  std::vector<BFace> bf;
  std::vector<std::uint64_t> hull_edges;
  for (int t : U)
    for (int i = 0; i < 4; ++i) {
      const int m = b_.nbr[uz(t)][uz(i)];
      if (m >= 0 && b_.mark[uz(m)] == in_u) continue;
      const auto& v = b_.tets[uz(t)];
      const int a = v[uz(kFaceOut[i][0])], b = v[uz(kFaceOut[i][1])], c = v[uz(kFaceOut[i][2])];
      if (a == p || b == p || c == p) {  // (only a hull face at p gets here, see grow_visible)
        hull_edges.push_back(a == p ? edge_key(b, c) : b == p ? edge_key(a, c) : edge_key(a, b));
        continue;
      }
      bf.push_back({a, b, c, m});
    }
  std::sort(hull_edges.begin(), hull_edges.end());
  // No vertex of U may disappear: every vertex of U other than p lies on its boundary.
  {
    std::vector<int> vb, vu;
    for (const auto& f : bf) {
      vb.push_back(f.a);
      vb.push_back(f.b);
      vb.push_back(f.c);
    }
    for (int t : U)
      for (int x : b_.tets[uz(t)])
        if (x != p) vu.push_back(x);
    std::sort(vb.begin(), vb.end());
    vb.erase(std::unique(vb.begin(), vb.end()), vb.end());
    std::sort(vu.begin(), vu.end());
    vu.erase(std::unique(vu.begin(), vu.end()), vu.end());
    if (vb != vu) return false;
  }
  // Edge pairing of the cone faces at p: the boundary must be a closed 2-manifold (every edge in
  // exactly 2 faces) but for the hull faces at p. Cone tets (f.a, f.c, f.b, p) are positively
  // oriented since orient3(a,b,c,p) < 0; their local faces containing p are those opposite w0
  // (edge w1w2), w1 (edge w0w2) and w2 (edge w0w1).
  std::unordered_map<std::uint64_t, std::array<int, 4>> edge_slots;  // -> (tet, local, tet, local)
  edge_slots.reserve(bf.size() * 2);
  const std::size_t first_new = b_.tets.size();
  for (std::size_t k = 0; k < bf.size(); ++k) {
    const auto& f = bf[k];
    const std::array<int, 4> v{{f.a, f.c, f.b, p}};
    const std::uint64_t keys[3] = {edge_key(v[1], v[2]), edge_key(v[0], v[2]), edge_key(v[0], v[1])};
    const int tid = static_cast<int>(first_new + k);
    for (int j = 0; j < 3; ++j) {
      auto it = edge_slots.find(keys[j]);
      if (it == edge_slots.end()) {
        edge_slots.emplace(keys[j], std::array<int, 4>{{tid, j, -1, -1}});
      } else {
        if (it->second[2] != -1) return false;  // edge in > 2 boundary faces
        it->second[2] = tid;
        it->second[3] = j;
      }
    }
  }
  std::size_t open = 0;
  for (const auto& kv : edge_slots) {
    const bool hull = std::binary_search(hull_edges.begin(), hull_edges.end(), kv.first);
    if ((kv.second[2] == -1) != hull) return false;
    open += hull ? 1 : 0;
  }
  if (open != hull_edges.size()) return false;
  // Commit.
  made.created.clear();
  made.created.reserve(bf.size());
  for (const auto& f : bf) {
    const int tid = b_.new_tet({{f.a, f.c, f.b, p}});
    if (mirror) b_.state[uz(tid)] = kOutside;  // the cone stays outside the body
    made.created.push_back(tid);
    b_.nbr[uz(tid)][3] = f.outside;
    if (f.outside < 0) continue;
    // Repoint the outside tet's neighbour (it pointed to the U tet behind this face).
    for (int j = 0; j < 4; ++j) {
      const int x = b_.nbr[uz(f.outside)][uz(j)];
      if (x >= 0 && x < static_cast<int>(first_new) && b_.mark[uz(x)] == in_u) {
        const int opp = b_.tets[uz(f.outside)][uz(j)];  // the face opposite j must be {a,b,c}
        if (opp != f.a && opp != f.b && opp != f.c) b_.nbr[uz(f.outside)][uz(j)] = tid;
      }
    }
  }
  for (const auto& kv : edge_slots) {
    const auto& sl = kv.second;
    b_.nbr[uz(sl[0])][uz(sl[1])] = sl[2];
    if (sl[2] >= 0) b_.nbr[uz(sl[2])][uz(sl[3])] = sl[0];
  }
  for (int t : U) {
    b_.state[uz(t)] = kReplaced;
    ++b_.ver[uz(t)];
  }
  for (int t : made.created)
    for (int x : b_.tets[uz(t)]) s_.vert_tet[uz(x)] = t;
  made.target = tg.ids;
  made.replaced = U.size();
  ++s_.made;
  if (visitor_) {
    Constrict3Event e;
    e.kind = Constrict3Event::Kind::Cavity;
    e.point = p;
    e.cavity_size = U.size();
    e.stage = Stage3::Cavity;
    visitor_->on_event(e);
  }
  return true;
}

bool Cavity3::over_budget() {
  if (s_.work > s_.work_limit) s_.capped = true;
  return s_.capped;
}

bool Cavity3::place(int p, CavityMade& made) {
  std::vector<int> star;
  if (over_budget() || !star_of(p, star)) return false;
  std::vector<Target> tg;
  for (int depth : kDepths) {
    if (over_budget()) return false;
    targets_of(p, star, depth, tg);
    const std::size_t tries = std::min<std::size_t>(tg.size(), depth == kDepths[0] ? kTriesFirst : kTriesLater);
    for (std::size_t k = 0; k < tries && !over_budget(); ++k)
      if (try_cavity(p, star, tg[k], made)) return true;
  }
  return false;
}

}  // namespace constrict::detail
