// SPDX-License-Identifier: GPL-3.0-or-later
// γ-values of the Delaunay faces in O(1) each (spec §2.3) and the degeneracy completion that
// turns the Delaunay triangulation into γ([-1,1],[0,1]) exactly (spec §1.4, §2.2, §3.8):
// every k-subset of points on a common empty circle/sphere is a face. docs/gamma-graph.md has the
// proofs of the rules used here.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "constrict/gamma_graph.hpp"
#include "constrict/predicates.hpp"
#include "gamma/detail/apex3.hpp"
#include "gamma/detail/reconcile.hpp"

namespace constrict {
namespace {

constexpr std::size_t kMaxCompletionFaces = 20'000'000;

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
};

struct ArrayHash {
  template <std::size_t K>
  std::size_t operator()(const std::array<int, K>& a) const noexcept {
    std::size_t h = 1469598103934665603ull;
    for (int v : a) h = (h ^ static_cast<std::size_t>(static_cast<unsigned>(v))) * 1099511628211ull;
    return h;
  }
};

// Lexicographic coordinate order (independent of input order, so the choice of representative
// apex does not depend on how the input was permuted).
std::vector<int> lex_sorted(const PointSet& pts, std::vector<int> ids) {
  const int d = pts.dim;
  std::sort(ids.begin(), ids.end(), [&](int a, int b) {
    const double* pa = pts[static_cast<std::size_t>(a)];
    const double* pb = pts[static_cast<std::size_t>(b)];
    return std::lexicographical_compare(pa, pa + d, pb, pb + d);
  });
  return ids;
}

}  // namespace

Status delaunay_gamma2(const PointSet& points, DelaunayGamma2& out) {
  if (Status s = build_delaunay2(points, out.dt); !s) return s;
  const auto& tri = out.dt.triangles;
  const auto& nbr = out.dt.neighbors;
  const std::size_t T = tri.size();
  GammaFaces& faces = out.faces;
  faces.clear();
  faces.dim = 2;
  faces.reserve(T * 3 / 2 + 3);
  out.simplex_face.assign(T, {-1, -1, -1});
  UnionFind clusters(T);
  std::vector<char> in_cluster(T, 0);

  for (std::size_t t = 0; t < T; ++t) {
    for (int i = 0; i < 3; ++i) {
      const int nb = nbr[t][static_cast<std::size_t>(i)];
      if (nb != -1 && static_cast<std::size_t>(nb) < t) continue;
      const int v1 = tri[t][static_cast<std::size_t>((i + 1) % 3)];
      const int v2 = tri[t][static_cast<std::size_t>((i + 2) % 3)];
      const int p = tri[t][static_cast<std::size_t>(i)];  // left of v1 -> v2 (triangle is CCW)
      const int ids[2] = {std::min(v1, v2), std::max(v1, v2)};
      const double* a = points[static_cast<std::size_t>(ids[0])];
      const double* b = points[static_cast<std::size_t>(ids[1])];
      const double gp = apex_gamma2(a, b, points[static_cast<std::size_t>(p)]);
      double gq = 1.0;
      int j = -1;
      if (nb != -1) {
        const auto& tn = tri[static_cast<std::size_t>(nb)];
        for (int k = 0; k < 3; ++k)
          if (nbr[static_cast<std::size_t>(nb)][static_cast<std::size_t>(k)] == static_cast<int>(t)) j = k;
        const int q = tn[static_cast<std::size_t>(j)];
        gq = apex_gamma2(a, b, points[static_cast<std::size_t>(q)]);
      }
      double ga = v1 < v2 ? gp : gq;
      double gb = v1 < v2 ? gq : gp;
      if (nb != -1) {
        const int q = tri[static_cast<std::size_t>(nb)][static_cast<std::size_t>(j)];
        const int ic = in_circle_ccw(points[static_cast<std::size_t>(tri[t][0])], points[static_cast<std::size_t>(tri[t][1])],
                                 points[static_cast<std::size_t>(tri[t][2])], points[static_cast<std::size_t>(q)]);
        detail::reconcile_side_values(ga, gb, ic);
        if (ic == 0) {
          clusters.unite(static_cast<int>(t), nb);
          in_cluster[t] = in_cluster[static_cast<std::size_t>(nb)] = 1;
        }
      }
      const int f = static_cast<int>(faces.size());
      faces.push_back(ids, ga, gb, static_cast<std::uint8_t>(kFaceDelaunay | (nb == -1 ? kFaceHull : 0)));
      out.simplex_face[t][static_cast<std::size_t>(i)] = f;
      if (nb != -1) out.simplex_face[static_cast<std::size_t>(nb)][static_cast<std::size_t>(j)] = f;
    }
  }

  // Co-circular completion: the triangles sharing one empty circle triangulate the convex polygon
  // of the points on it; every chord of that polygon is a face of γ([-1,1],[0,1]) with side values
  // ±g (the apex value of any polygon vertex on that side: all have the same t, spec §1.1).
  std::unordered_map<int, std::vector<int>> members;
  for (std::size_t t = 0; t < T; ++t)
    if (in_cluster[t]) members[clusters.find(static_cast<int>(t))].push_back(static_cast<int>(t));
  std::vector<int> roots;
  for (const auto& kv : members) roots.push_back(kv.first);
  std::sort(roots.begin(), roots.end());
  std::size_t added = 0;
  for (int root : roots) {
    const auto& tris = members[root];
    std::vector<int> verts;
    std::unordered_set<std::array<int, 2>, ArrayHash> edges;
    for (int t : tris)
      for (int i = 0; i < 3; ++i) {
        const int u = tri[static_cast<std::size_t>(t)][static_cast<std::size_t>(i)];
        const int v = tri[static_cast<std::size_t>(t)][static_cast<std::size_t>((i + 1) % 3)];
        verts.push_back(u);
        edges.insert({std::min(u, v), std::max(u, v)});
      }
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    const std::size_t m = verts.size();
    added += m * (m - 1) / 2;
    if (added > kMaxCompletionFaces)
      return {StatusCode::Unsupported,
              "too many co-circular points: the complete γ([-1,1],[0,1]) graph would exceed " +
                  std::to_string(kMaxCompletionFaces) + " edges"};
    const std::vector<int> lex = lex_sorted(points, verts);
    for (std::size_t x = 0; x < m; ++x)
      for (std::size_t y = x + 1; y < m; ++y) {
        const std::array<int, 2> e{verts[x], verts[y]};
        if (edges.count(e)) continue;
        const double* a = points[static_cast<std::size_t>(e[0])];
        const double* b = points[static_cast<std::size_t>(e[1])];
        int wa = -1, wb = -1;
        for (int w : lex) {
          if (wa >= 0 && wb >= 0) break;
          if (w == e[0] || w == e[1]) continue;
          const int o = orient2(a, b, points[static_cast<std::size_t>(w)]);
          if (o > 0 && wa < 0) wa = w;
          if (o < 0 && wb < 0) wb = w;
        }
        CONSTRICT_CHECK(wa >= 0 && wb >= 0, "co-circular chord without apexes on both sides");
        double ga = apex_gamma2(a, b, points[static_cast<std::size_t>(wa)]);
        double gb = apex_gamma2(a, b, points[static_cast<std::size_t>(wb)]);
        detail::reconcile_side_values(ga, gb, 0);
        faces.push_back(e.data(), ga, gb, kFaceCospherical);
      }
  }
  return Status::ok();
}

namespace {

// Parity of the permutation taking (0,1,2,3) to (pa,pb,pc,pd): +1 even, -1 odd.
int parity4(std::array<int, 4> p) {
  int inv = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (p[static_cast<std::size_t>(i)] > p[static_cast<std::size_t>(j)]) ++inv;
  return (inv % 2 == 0) ? 1 : -1;
}

}  // namespace

Status delaunay_gamma3(const PointSet& points, DelaunayGamma3& out) {
  if (Status s = build_delaunay3(points, out.dt); !s) return s;
  const auto& tet = out.dt.tets;
  const auto& nbr = out.dt.neighbors;
  const std::size_t T = tet.size();
  GammaFaces& faces = out.faces;
  faces.clear();
  faces.dim = 3;
  faces.reserve(T * 2 + 4);
  out.simplex_face.assign(T, {-1, -1, -1, -1});
  UnionFind clusters(T);
  std::vector<char> in_cluster(T, 0);
  // For each face: the tet and local index on its positive side ("a") and negative side ("b").
  std::vector<std::array<int, 2>> side_tet;
  side_tet.reserve(T * 2 + 4);
  auto P = [&](int v) { return points[static_cast<std::size_t>(v)]; };

  for (std::size_t t = 0; t < T; ++t) {
    for (int i = 0; i < 4; ++i) {
      const int nb = nbr[t][static_cast<std::size_t>(i)];
      if (nb != -1 && static_cast<std::size_t>(nb) < t) continue;
      // Face opposite local vertex i, ids ascending, with their local positions.
      std::array<std::pair<int, int>, 3> fv{};
      int k = 0;
      for (int l = 0; l < 4; ++l)
        if (l != i) fv[static_cast<std::size_t>(k++)] = {tet[t][static_cast<std::size_t>(l)], l};
      std::sort(fv.begin(), fv.end());
      const int ids[3] = {fv[0].first, fv[1].first, fv[2].first};
      // The tet is positively oriented, so orient3(ids..., apex) = parity of the permutation.
      const int side_p = parity4({fv[0].second, fv[1].second, fv[2].second, i});
      const int p = tet[t][static_cast<std::size_t>(i)];
      const detail::TriangleFrame3 frame(P(ids[0]), P(ids[1]), P(ids[2]));
      const double gp = frame.apex(P(p));
      double gq = 1.0;
      int j = -1;
      if (nb != -1) {
        for (int l = 0; l < 4; ++l)
          if (nbr[static_cast<std::size_t>(nb)][static_cast<std::size_t>(l)] == static_cast<int>(t)) j = l;
        const int q = tet[static_cast<std::size_t>(nb)][static_cast<std::size_t>(j)];
        gq = frame.apex(P(q));
      }
      double ga = side_p > 0 ? gp : gq;
      double gb = side_p > 0 ? gq : gp;
      if (nb != -1) {
        const int q = tet[static_cast<std::size_t>(nb)][static_cast<std::size_t>(j)];
        const auto& v = tet[t];
        const int is = in_sphere_positive(P(v[0]), P(v[1]), P(v[2]), P(v[3]), P(q));
        detail::reconcile_side_values(ga, gb, is);
        if (is == 0) {
          clusters.unite(static_cast<int>(t), nb);
          in_cluster[t] = in_cluster[static_cast<std::size_t>(nb)] = 1;
        }
      }
      const int f = static_cast<int>(faces.size());
      faces.push_back(ids, ga, gb, static_cast<std::uint8_t>(kFaceDelaunay | (nb == -1 ? kFaceHull : 0)));
      const int tp = static_cast<int>(t);
      side_tet.push_back(side_p > 0 ? std::array<int, 2>{tp, nb} : std::array<int, 2>{nb, tp});
      out.simplex_face[t][static_cast<std::size_t>(i)] = f;
      if (nb != -1) out.simplex_face[static_cast<std::size_t>(nb)][static_cast<std::size_t>(j)] = f;
    }
  }

  // ---- Degeneracy completion (docs/gamma-graph.md §"Co-spherical input") -------------------
  // (1) disc groups: connected sets of coplanar, co-circular Delaunay faces (on the hull, or on
  //     the boundary of a co-spherical cluster). All triangles on one circle share c, r and the
  //     plane, hence the same side values: every further triple of the group copies them.
  // (2) co-spherical clusters: every triple of cluster points with cluster points on both sides
  //     has side values ±g from any cluster point on each side.
  bool any_cluster = false;
  for (char c : in_cluster) any_cluster = any_cluster || c;
  const std::size_t F0 = faces.size();
  // Candidate faces for disc groups: hull faces and faces of clustered tets.
  std::vector<int> cand;
  for (std::size_t f = 0; f < F0; ++f) {
    const auto& st = side_tet[f];
    const bool hull = st[0] == -1 || st[1] == -1;
    const bool clus = (st[0] >= 0 && in_cluster[static_cast<std::size_t>(st[0])]) ||
                      (st[1] >= 0 && in_cluster[static_cast<std::size_t>(st[1])]);
    if (hull || (clus && !(st[0] >= 0 && st[1] >= 0 && in_cluster[static_cast<std::size_t>(st[0])] &&
                           in_cluster[static_cast<std::size_t>(st[1])] &&
                           clusters.find(st[0]) == clusters.find(st[1]))))
      cand.push_back(static_cast<int>(f));
  }
  // The "owner" of a candidate face: -1 for the hull, else the cluster root it bounds.
  auto owner = [&](int f, int side) {
    const int t = side_tet[static_cast<std::size_t>(f)][static_cast<std::size_t>(side)];
    if (t < 0) return -2;
    return in_cluster[static_cast<std::size_t>(t)] ? clusters.find(t) : -3;
  };
  std::unordered_map<std::array<int, 2>, std::vector<int>, ArrayHash> edge_faces;
  for (int f : cand)
    for (int a = 0; a < 3; ++a)
      for (int b = a + 1; b < 3; ++b)
        edge_faces[{faces.vertex(static_cast<std::size_t>(f), a), faces.vertex(static_cast<std::size_t>(f), b)}].push_back(f);
  UnionFind discs(F0);
  std::vector<char> in_disc(F0, 0);
  std::vector<std::array<int, 2>> keys;
  keys.reserve(edge_faces.size());
  for (const auto& kv : edge_faces) keys.push_back(kv.first);
  std::sort(keys.begin(), keys.end());
  for (const auto& e : keys) {
    const auto& fl = edge_faces[e];
    for (std::size_t x = 0; x < fl.size(); ++x)
      for (std::size_t y = x + 1; y < fl.size(); ++y) {
        const int f1 = fl[x], f2 = fl[y];
        // Same owner on a common side: both hull faces, or both bounding the same cluster.
        bool same = false;
        for (int s1 = 0; s1 < 2 && !same; ++s1)
          for (int s2 = 0; s2 < 2 && !same; ++s2) {
            const int o1 = owner(f1, s1), o2 = owner(f2, s2);
            same = (o1 == -2 && o2 == -2) || (o1 >= 0 && o1 == o2);
          }
        if (!same) continue;
        int d = -1;
        for (int a = 0; a < 3; ++a) {
          const int v = faces.vertex(static_cast<std::size_t>(f2), a);
          if (v != e[0] && v != e[1]) d = v;
        }
        const double* A = P(faces.vertex(static_cast<std::size_t>(f1), 0));
        const double* B = P(faces.vertex(static_cast<std::size_t>(f1), 1));
        const double* C = P(faces.vertex(static_cast<std::size_t>(f1), 2));
        if (orient3(A, B, C, P(d)) != 0 || in_circle_coplanar3(A, B, C, P(d)) != 0) continue;
        discs.unite(f1, f2);
        in_disc[static_cast<std::size_t>(f1)] = in_disc[static_cast<std::size_t>(f2)] = 1;
      }
  }
  if (!any_cluster && std::none_of(in_disc.begin(), in_disc.end(), [](char c) { return c != 0; }))
    return Status::ok();

  std::unordered_set<std::array<int, 3>, ArrayHash> present;
  for (std::size_t f = 0; f < F0; ++f)
    present.insert({faces.vertex(f, 0), faces.vertex(f, 1), faces.vertex(f, 2)});
  std::size_t added = 0;
  auto budget = [&](std::size_t m) -> Status {
    added += m * (m - 1) * (m - 2) / 6;
    if (added > kMaxCompletionFaces)
      return {StatusCode::Unsupported, "too many co-spherical points: the complete γ([-1,1],[0,1]) graph would exceed " +
                                           std::to_string(kMaxCompletionFaces) + " triangles"};
    return Status::ok();
  };

  // (1) disc groups
  std::map<int, std::vector<int>> disc_members;
  for (std::size_t f = 0; f < F0; ++f)
    if (in_disc[f]) disc_members[discs.find(static_cast<int>(f))].push_back(static_cast<int>(f));
  for (const auto& [root, fl] : disc_members) {
    std::vector<int> verts;
    for (int f : fl)
      for (int a = 0; a < 3; ++a) verts.push_back(faces.vertex(static_cast<std::size_t>(f), a));
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    if (Status s = budget(verts.size()); !s) return s;
    const int rep = root;
    const double ra = faces.gamma_a[static_cast<std::size_t>(rep)], rb = faces.gamma_b[static_cast<std::size_t>(rep)];
    // An off-plane witness point and its side w.r.t. the representative face.
    const auto& st = side_tet[static_cast<std::size_t>(rep)];
    const int wt = st[0] >= 0 ? st[0] : st[1];
    int witness = -1;
    for (int l = 0; l < 4 && witness < 0; ++l) {
      const int v = tet[static_cast<std::size_t>(wt)][static_cast<std::size_t>(l)];
      if (std::find(verts.begin(), verts.end(), v) == verts.end()) witness = v;
    }
    CONSTRICT_CHECK(witness >= 0, "disc group without an off-plane witness");
    const int rep_side = orient3(P(faces.vertex(static_cast<std::size_t>(rep), 0)), P(faces.vertex(static_cast<std::size_t>(rep), 1)),
                                 P(faces.vertex(static_cast<std::size_t>(rep), 2)), P(witness));
    const std::size_t m = verts.size();
    for (std::size_t x = 0; x < m; ++x)
      for (std::size_t y = x + 1; y < m; ++y)
        for (std::size_t z = y + 1; z < m; ++z) {
          const std::array<int, 3> tr{verts[x], verts[y], verts[z]};
          if (present.count(tr)) continue;
          if (collinear3(P(tr[0]), P(tr[1]), P(tr[2]))) continue;
          const int s = orient3(P(tr[0]), P(tr[1]), P(tr[2]), P(witness));
          present.insert(tr);
          const double ga = s == rep_side ? ra : rb, gb = s == rep_side ? rb : ra;
          faces.push_back(tr.data(), ga, gb,
                          static_cast<std::uint8_t>(kFaceCospherical | (ga == 1.0 || gb == 1.0 ? kFaceHull : 0)));
        }
  }

  // (2) co-spherical clusters
  std::map<int, std::vector<int>> cluster_members;
  for (std::size_t t = 0; t < T; ++t)
    if (in_cluster[t]) cluster_members[clusters.find(static_cast<int>(t))].push_back(static_cast<int>(t));
  for (const auto& [root, tl] : cluster_members) {
    std::vector<int> verts;
    for (int t : tl)
      for (int l = 0; l < 4; ++l) verts.push_back(tet[static_cast<std::size_t>(t)][static_cast<std::size_t>(l)]);
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    if (Status s = budget(verts.size()); !s) return s;
    const std::vector<int> lex = lex_sorted(points, verts);
    const std::size_t m = verts.size();
    for (std::size_t x = 0; x < m; ++x)
      for (std::size_t y = x + 1; y < m; ++y)
        for (std::size_t z = y + 1; z < m; ++z) {
          const std::array<int, 3> tr{verts[x], verts[y], verts[z]};
          if (present.count(tr)) continue;
          const double *A = P(tr[0]), *B = P(tr[1]), *C = P(tr[2]);
          if (collinear3(A, B, C)) continue;
          int wa = -1, wb = -1;
          for (int w : lex) {
            if (wa >= 0 && wb >= 0) break;
            if (w == tr[0] || w == tr[1] || w == tr[2]) continue;
            const int o = orient3(A, B, C, P(w));
            if (o > 0 && wa < 0) wa = w;
            if (o < 0 && wb < 0) wb = w;
          }
          // One side without cluster points: the triple lies on a boundary facet of the cluster
          // polytope, which (1) has already completed.
          if (wa < 0 || wb < 0) continue;
          double ga = apex_gamma3(A, B, C, P(wa));
          double gb = apex_gamma3(A, B, C, P(wb));
          detail::reconcile_side_values(ga, gb, 0);
          present.insert(tr);
          faces.push_back(tr.data(), ga, gb, kFaceCospherical);
        }
  }
  return Status::ok();
}

}  // namespace constrict
