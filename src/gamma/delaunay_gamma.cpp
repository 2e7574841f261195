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

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "cgal/detail/delaunay_local.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/predicates.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/check_points.hpp"
#include "core/detail/union_find.hpp"
#include "gamma/detail/apex2.hpp"
#include "gamma/detail/apex3.hpp"
#include "gamma/detail/reconcile.hpp"

namespace constrict {
namespace {

constexpr std::size_t kMaxCompletionFaces = 20'000'000;

// The per-face loops run over fixed blocks of simplices (the block layout, hence every result,
// does not depend on the number of threads; each face is written to its own slot).
constexpr std::size_t kBlock = 1024;
// The apexes across the faces are scattered in memory: prefetch their coordinates.
constexpr std::size_t kAhead = 8;
template <int V, class Mesh>
[[gnu::always_inline]] inline void prefetch_far(const Mesh& loc, const double* X, std::size_t dim, std::size_t t, std::size_t end) {
  if (t >= end) return;
  for (int i = 0; i < V; ++i) {
    const int q = loc.opposite[t][static_cast<std::size_t>(i)];
    if (q >= 0) __builtin_prefetch(X + dim * static_cast<std::size_t>(q));
  }
}
// first[b + 1] = number of faces owned by the simplices of block b.
template <class Mesh>
void count_owned(const Mesh& loc, std::size_t T, std::vector<std::size_t>& first);
template <class F>
void for_blocks(std::size_t nblocks, const F& f) {
  if (nblocks <= 16) {  // small input: inline (task dispatch costs more than it saves)
    for (std::size_t b = 0; b < nblocks; ++b) f(b);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nblocks), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) f(b);
  });
}

using detail::UnionFind;

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

template <class Mesh>
void count_owned(const Mesh& loc, std::size_t T, std::vector<std::size_t>& first) {
  const std::size_t nblocks = first.size() - 1;
  for_blocks(nblocks, [&](std::size_t b) {
    std::size_t c = 0;
    for (std::size_t t = b * kBlock, e = std::min(T, t + kBlock); t < e; ++t)
      c += static_cast<std::size_t>(__builtin_popcount(loc.owned[t]));
    first[b + 1] = c;
  });
}

// Neighbour pairs of simplices found by a per-face loop, one list per block.
using PairBlocks = std::vector<std::vector<std::array<int, 2>>>;

bool any_pair(const PairBlocks& pairs) {
  bool any = false;
  for (const auto& v : pairs) any = any || !v.empty();
  return any;
}

// The stages of delaunay_gamma2, in order (defined after it).
template <class Mesh, class SimplexFace>
std::vector<std::size_t> number_faces(const Mesh& loc, std::size_t T, int dim, GammaFaces& faces,
                                      std::vector<SimplexFace>& simplex_face);
void delaunay_faces2(const detail::LocalMesh<2>& loc, DelaunayGamma2& out, const std::vector<std::size_t>& first,
                     PairBlocks& cocirc);
Status complete_cocircular2(const PointSet& points, const std::vector<std::array<int, 3>>& tri, const PairBlocks& cocirc,
                            GammaFaces& faces);

}  // namespace

Status delaunay_gamma2(const PointSet& points, DelaunayGamma2& out) {
  if (Status f = detail::check_finite(points, "delaunay_gamma2"); !f) return f;
  detail::LocalMesh<2> loc;
  if (Status s = detail::build_delaunay2_local(points, out.dt, &loc); !s) return s;
  const std::vector<std::size_t> first = number_faces(loc, out.dt.triangles.size(), 2, out.faces, out.simplex_face);
  PairBlocks cocirc(first.size() - 1);
  delaunay_faces2(loc, out, first, cocirc);
  if (!any_pair(cocirc)) return Status::ok();
  return complete_cocircular2(points, out.dt.triangles, cocirc, out.faces);
}

namespace {

// Face f of simplex t, facet i, exists iff t owns the facet (hull facet, or t < neighbour); faces
// are numbered in (t, i) order, so block b of simplices starts at the returned first[b] (and
// first.back() is the number of Delaunay faces). Sizes faces (dim vertices each) and
// simplex_face for them.
template <class Mesh, class SimplexFace>
std::vector<std::size_t> number_faces(const Mesh& loc, std::size_t T, int dim, GammaFaces& faces,
                                      std::vector<SimplexFace>& simplex_face) {
  faces.clear();
  faces.dim = dim;
  const std::size_t nblocks = (T + kBlock - 1) / kBlock;
  std::vector<std::size_t> first(nblocks + 1, 0);
  count_owned(loc, T, first);
  for (std::size_t b = 0; b < nblocks; ++b) first[b + 1] += first[b];
  const std::size_t F0 = first[nblocks];
  detail::resize_big(faces.vertices, static_cast<std::size_t>(dim) * F0);
  detail::resize_big(faces.gamma_a, F0);
  detail::resize_big(faces.gamma_b, F0);
  detail::resize_big(faces.delta, F0);
  detail::resize_big(faces.flags, F0);
  detail::resize_big(simplex_face, T);
  return first;
}

// The Delaunay edges with their side values (spec §2.3), each in its numbered slot; co-circular
// neighbour pairs (in_circle == 0) go to cocirc[block].
void delaunay_faces2(const detail::LocalMesh<2>& loc, DelaunayGamma2& out, const std::vector<std::size_t>& first,
                     PairBlocks& cocirc) {
  const auto& tri = out.dt.triangles;
  const auto& nbr = out.dt.neighbors;
  const auto& ltri = loc.simplices;
  const double* X = loc.coords.data();
  auto LP = [X](int v) { return X + 2 * static_cast<std::size_t>(v); };
  const std::size_t T = tri.size();
  GammaFaces& faces = out.faces;
  for_blocks(first.size() - 1, [&](std::size_t b) {
    std::size_t f = first[b];
    for (std::size_t t = b * kBlock, e = std::min(T, t + kBlock); t < e; ++t) {
      prefetch_far<3>(loc, X, 2, t + kAhead, e);
      const auto& lt = ltri[t];
      for (int i = 0; i < 3; ++i) {
        if (!((loc.owned[t] >> i) & 1)) continue;
        const int nb = nbr[t][static_cast<std::size_t>(i)];
        const std::size_t i1 = static_cast<std::size_t>((i + 1) % 3), i2 = static_cast<std::size_t>((i + 2) % 3);
        const int v1 = tri[t][i1];
        const int v2 = tri[t][i2];
        const bool up = v1 < v2;
        const double* a = LP(up ? lt[i1] : lt[i2]);  // the smaller input id
        const double* b2 = LP(up ? lt[i2] : lt[i1]);
        int sp = 0, sq = 2;
        double gp, gq = 1.0;  // apex left of v1 -> v2 (the triangle is CCW), apex across
        int j = -1;
        if (nb != -1) {
          j = (loc.mirror[t] >> (2 * i)) & 3;
          detail::apex2_pair(a, b2, LP(lt[static_cast<std::size_t>(i)]), LP(loc.opposite[t][static_cast<std::size_t>(i)]),
                             gp, sp, gq, sq);
        } else {
          gp = detail::apex2(a, b2, LP(lt[static_cast<std::size_t>(i)]), sp);
        }
        double ga = up ? gp : gq;
        double gb = up ? gq : gp;
        // The two apexes can be co-circular with the edge, or the sum of the side values change
        // sign, only when their diametral signs are opposite (angles sum to 180° iff
        // co-circular); otherwise the exact in-circle test cannot change anything.
        if (nb != -1 && sp == -sq) {
          const int q = loc.opposite[t][static_cast<std::size_t>(i)];
          const int ic = in_circle_ccw(LP(lt[0]), LP(lt[1]), LP(lt[2]), LP(q));
          detail::reconcile_side_values(ga, gb, ic);
          if (ic == 0) cocirc[b].push_back({static_cast<int>(t), nb});
        }
        faces.vertices[2 * f] = up ? v1 : v2;
        faces.vertices[2 * f + 1] = up ? v2 : v1;
        faces.gamma_a[f] = ga;
        faces.gamma_b[f] = gb;
        faces.delta[f] = detail::filtration(ga, gb);
        faces.flags[f] = static_cast<std::uint8_t>(kFaceDelaunay | (nb == -1 ? kFaceHull : 0));
        out.simplex_face[t][static_cast<std::size_t>(i)] = static_cast<int>(f);
        if (nb != -1) out.simplex_face[static_cast<std::size_t>(nb)][static_cast<std::size_t>(j)] = static_cast<int>(f);
        ++f;
      }
    }
  });
}

// The chord (e[0], e[1]) of a co-circular polygon with vertices lex (in lexicographic order):
// side values ±g from the first polygon vertex on each side.
void push_chord2(const PointSet& points, const std::vector<int>& lex, const std::array<int, 2>& e, GammaFaces& faces) {
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

// One empty circle: the triangles tris triangulate the convex polygon of the points on it; every
// chord of that polygon that is not already a Delaunay edge is added. added counts the chords of
// all circles so far, against kMaxCompletionFaces.
Status complete_circle2(const PointSet& points, const std::vector<std::array<int, 3>>& tri, const std::vector<int>& tris,
                        std::size_t& added, GammaFaces& faces) {
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
      push_chord2(points, lex, e, faces);
    }
  return Status::ok();
}

// Co-circular completion: the triangles sharing one empty circle triangulate the convex polygon
// of the points on it; every chord of that polygon is a face of γ([-1,1],[0,1]) with side values
// ±g (the apex value of any polygon vertex on that side: all have the same t, spec §1.1).
// Circles are taken in the order of their smallest triangle.
Status complete_cocircular2(const PointSet& points, const std::vector<std::array<int, 3>>& tri, const PairBlocks& cocirc,
                            GammaFaces& faces) {
  const std::size_t T = tri.size();
  UnionFind clusters(T);
  std::vector<char> in_cluster(T, 0);
  for (const auto& v : cocirc)
    for (const auto& pr : v) {
      clusters.join(pr[0], pr[1]);
      in_cluster[static_cast<std::size_t>(pr[0])] = in_cluster[static_cast<std::size_t>(pr[1])] = 1;
    }
  std::unordered_map<int, std::vector<int>> members;
  for (std::size_t t = 0; t < T; ++t)
    if (in_cluster[t]) members[clusters.find(static_cast<int>(t))].push_back(static_cast<int>(t));
  std::vector<int> roots;
  for (const auto& kv : members) roots.push_back(kv.first);
  std::sort(roots.begin(), roots.end());
  std::size_t added = 0;
  for (int root : roots)
    if (Status s = complete_circle2(points, tri, members[root], added, faces); !s) return s;
  return Status::ok();
}

// The face of a positively oriented tet opposite its vertex i: vertex ids ascending, their
// positions in the tet, and the side of the apex (orient3(ids..., apex) = parity of the
// permutation (pos..., i)). Scalars only (no small arrays through memory).
struct FaceOrder {
  int ids[3];
  std::size_t pos[3];
  int side;
  FaceOrder(const std::array<int, 4>& tv, int i) {
    int p0 = i == 0 ? 1 : 0;
    int p1 = i <= 1 ? 2 : 1;
    int p2 = i <= 2 ? 3 : 2;
    int a = tv[static_cast<std::size_t>(p0)], b = tv[static_cast<std::size_t>(p1)], c = tv[static_cast<std::size_t>(p2)];
    auto cswap = [](int& x, int& y, int& px, int& py) {
      if (y < x) {
        std::swap(x, y);
        std::swap(px, py);
      }
    };
    cswap(a, b, p0, p1);
    cswap(b, c, p1, p2);
    cswap(a, b, p0, p1);
    ids[0] = a;
    ids[1] = b;
    ids[2] = c;
    pos[0] = static_cast<std::size_t>(p0);
    pos[1] = static_cast<std::size_t>(p1);
    pos[2] = static_cast<std::size_t>(p2);
    const int inv = (p0 > p1) + (p0 > p2) + (p0 > i) + (p1 > p2) + (p1 > i) + (p2 > i);
    side = (inv % 2 == 0) ? 1 : -1;
  }
};

// The stages of delaunay_gamma3, in order (defined after it).
void delaunay_faces3(const detail::LocalMesh<3>& loc, DelaunayGamma3& out, const std::vector<std::size_t>& first,
                     PairBlocks& cocirc);
std::vector<std::array<int, 2>> hull_disc_pairs(const detail::LocalMesh<3>& loc, const DelaunayGamma3& out);

// The degeneracy completion of delaunay_gamma3 on degenerate input (rare): the serial general
// code. Stages, in order: unite_clusters, find_side_tets, unite_discs, (with clusters)
// link_cluster_discs, then complete_discs and complete_clusters, which append the missing
// triples to the faces.
class Completion3 {
 public:
  Completion3(const PointSet& points, DelaunayGamma3& out, std::size_t F0)
      : points_(points), tet_(out.dt.tets), nbr_(out.dt.neighbors), simplex_face_(out.simplex_face), faces_(out.faces),
        F0_(F0), clusters_(tet_.size()), in_cluster_(tet_.size(), 0), side_tet_(F0), discs_(F0), in_disc_(F0, 0) {}

  void unite_clusters(const PairBlocks& cocirc);
  void find_side_tets();
  void unite_discs(const std::vector<std::array<int, 2>>& disc_pairs);
  void link_cluster_discs();
  bool any_disc() const;
  void mark_present();
  Status complete_discs();
  Status complete_clusters();

 private:
  const double* P(int v) const { return points_[static_cast<std::size_t>(v)]; }
  // link_cluster_discs
  std::vector<int> disc_candidates();
  int owner(int f, int side);
  void link_if_one_disc(const std::array<int, 2>& e, int f1, int f2);
  // complete_discs, complete_clusters
  Status budget(std::size_t m);
  Status complete_disc(int rep, const std::vector<int>& fl);
  Status complete_cluster(const std::vector<int>& tl);
  void push_cluster_triple(const std::vector<int>& lex, const std::array<int, 3>& tr);

  const PointSet& points_;
  const std::vector<std::array<int, 4>>& tet_;
  const std::vector<std::array<int, 4>>& nbr_;
  const std::vector<std::array<int, 4>>& simplex_face_;
  GammaFaces& faces_;
  const std::size_t F0_;  // number of Delaunay faces (the completion appends after them)
  UnionFind clusters_;    // over tets
  std::vector<char> in_cluster_;
  std::vector<std::array<int, 2>> side_tet_;  // per Delaunay face
  UnionFind discs_;                           // over Delaunay faces
  std::vector<char> in_disc_;
  std::unordered_set<std::array<int, 3>, ArrayHash> present_;
  std::size_t added_ = 0;  // triples counted by budget()
};

}  // namespace

Status delaunay_gamma3(const PointSet& points, DelaunayGamma3& out, bool complete_degenerate) {
  if (Status f = detail::check_finite(points, "delaunay_gamma3"); !f) return f;
  detail::LocalMesh<3> loc;
  if (Status s = detail::build_delaunay3_local(points, out.dt, &loc); !s) return s;
  const std::vector<std::size_t> first = number_faces(loc, out.dt.tets.size(), 3, out.faces, out.simplex_face);
  PairBlocks cocirc(first.size() - 1);  // co-spherical neighbour tets
  delaunay_faces3(loc, out, first, cocirc);

  if (!complete_degenerate) return Status::ok();
  // ---- Degeneracy completion (docs/gamma-graph.md §"Co-spherical input") -------------------
  // (1) disc groups: connected sets of coplanar, co-circular Delaunay faces (on the hull, or on
  //     the boundary of a co-spherical cluster). All triangles on one circle share c, r and the
  //     plane, hence the same side values: every further triple of the group copies them.
  // (2) co-spherical clusters: every triple of cluster points with cluster points on both sides
  //     has side values ±g from any cluster point on each side.
  const bool any_cluster = any_pair(cocirc);
  std::vector<std::array<int, 2>> disc_pairs;
  if (!any_cluster) {
    disc_pairs = hull_disc_pairs(loc, out);
    if (disc_pairs.empty()) return Status::ok();
  }

  // Degenerate input from here on (rare): the serial general code.
  Completion3 completion(points, out, first.back());
  completion.unite_clusters(cocirc);
  completion.find_side_tets();
  completion.unite_discs(disc_pairs);
  if (any_cluster) completion.link_cluster_discs();
  if (!any_cluster && !completion.any_disc()) return Status::ok();
  completion.mark_present();
  if (Status s = completion.complete_discs(); !s) return s;
  return completion.complete_clusters();
}

namespace {

// The Delaunay triangles with their side values (spec §2.3), each in its numbered slot;
// co-spherical neighbour pairs (in_sphere == 0) go to cocirc[block].
void delaunay_faces3(const detail::LocalMesh<3>& loc, DelaunayGamma3& out, const std::vector<std::size_t>& first,
                     PairBlocks& cocirc) {
  const auto& tet = out.dt.tets;
  const auto& nbr = out.dt.neighbors;
  const auto& ltet = loc.simplices;
  const double* X = loc.coords.data();
  auto LP = [X](int v) { return X + 3 * static_cast<std::size_t>(v); };
  const std::size_t T = tet.size();
  GammaFaces& faces = out.faces;
  for_blocks(first.size() - 1, [&](std::size_t b) {
    std::size_t f = first[b];
    for (std::size_t t = b * kBlock, e = std::min(T, t + kBlock); t < e; ++t) {
      prefetch_far<4>(loc, X, 3, t + kAhead, e);
      const auto& lt = ltet[t];
      for (int i = 0; i < 4; ++i) {
        if (!((loc.owned[t] >> i) & 1)) continue;
        const int nb = nbr[t][static_cast<std::size_t>(i)];
        // Face opposite local vertex i, ids ascending, with their local positions.
        const FaceOrder fo(tet[t], i);
        const detail::TriangleFrame3 frame(LP(lt[fo.pos[0]]), LP(lt[fo.pos[1]]), LP(lt[fo.pos[2]]));
        int sp = 0, sq = 2;
        const double gp = frame.apex(LP(lt[static_cast<std::size_t>(i)]), sp);
        double gq = 1.0;
        int j = -1, q = -1;
        if (nb != -1) {
          j = (loc.mirror[t] >> (2 * i)) & 3;
          q = loc.opposite[t][static_cast<std::size_t>(i)];
          gq = frame.apex(LP(q), sq);
        }
        double ga = fo.side > 0 ? gp : gq;
        double gb = fo.side > 0 ? gq : gp;
        // Co-sphericity of the two apexes with the face, or a sign change of the sum of the
        // side values, needs opposite diametral signs (a sphere through the face circle is
        // outside its diametral sphere on one side and inside on the other): only then can the
        // exact in-sphere test change anything.
        if (nb != -1 && sp == -sq) {
          const int is = in_sphere_positive(LP(lt[0]), LP(lt[1]), LP(lt[2]), LP(lt[3]), LP(q));
          detail::reconcile_side_values(ga, gb, is);
          if (is == 0) cocirc[b].push_back({static_cast<int>(t), nb});
        }
        for (int k = 0; k < 3; ++k) faces.vertices[3 * f + static_cast<std::size_t>(k)] = fo.ids[k];
        faces.gamma_a[f] = ga;
        faces.gamma_b[f] = gb;
        faces.delta[f] = detail::filtration(ga, gb);
        faces.flags[f] = static_cast<std::uint8_t>(kFaceDelaunay | (nb == -1 ? kFaceHull : 0));
        out.simplex_face[t][static_cast<std::size_t>(i)] = static_cast<int>(f);
        if (nb != -1) out.simplex_face[static_cast<std::size_t>(nb)][static_cast<std::size_t>(j)] = static_cast<int>(f);
        ++f;
      }
    }
  });
}

// Without clusters the disc-group candidates are the hull faces only, and two candidates are
// related iff they are the two hull faces of a hull edge (CGAL's adjacent infinite cells): the
// coplanar, co-circular such pairs (f1 < f2), in hull order.
std::vector<std::array<int, 2>> hull_disc_pairs(const detail::LocalMesh<3>& loc, const DelaunayGamma3& out) {
  const auto& tet = out.dt.tets;
  const auto& ltet = loc.simplices;
  const double* X = loc.coords.data();
  auto LP = [X](int v) { return X + 3 * static_cast<std::size_t>(v); };
  const std::size_t H = loc.hull.size();
  const std::size_t nhb = (H + kBlock - 1) / kBlock;
  PairBlocks pairs(nhb);
  for_blocks(nhb, [&](std::size_t b) {
    for (std::size_t h = b * kBlock, e = std::min(H, h + kBlock); h < e; ++h) {
      const detail::HullFace& hf = loc.hull[h];
      const std::size_t t = static_cast<std::size_t>(hf.t);
      const int f1 = out.simplex_face[t][static_cast<std::size_t>(hf.i)];
      const FaceOrder fo(tet[t], hf.i);
      const double* A = LP(ltet[t][fo.pos[0]]);
      const double* B = LP(ltet[t][fo.pos[1]]);
      const double* C = LP(ltet[t][fo.pos[2]]);
      for (int k = 0; k < 3; ++k) {
        const int f2 = out.simplex_face[static_cast<std::size_t>(hf.adj_t[k])][static_cast<std::size_t>(hf.adj_i[k])];
        if (f2 <= f1) continue;  // each pair once, from its smaller face
        // Coplanar and co-circular is a property of the four points: test f1 against the
        // vertex of f2 off the common edge.
        const double* D = LP(hf.far[k]);
        if (orient3(A, B, C, D) != 0 || in_circle_coplanar3(A, B, C, D) != 0) continue;
        pairs[b].push_back({f1, f2});
      }
    }
  });
  std::vector<std::array<int, 2>> disc_pairs;
  for (const auto& v : pairs) disc_pairs.insert(disc_pairs.end(), v.begin(), v.end());
  return disc_pairs;
}

// The sorted, distinct vertices of the given simplices (V vertices each, listed by get(s, l)).
template <class Get>
std::vector<int> distinct_vertices(const std::vector<int>& simplices, int V, const Get& get) {
  std::vector<int> verts;
  for (int s : simplices)
    for (int l = 0; l < V; ++l) verts.push_back(get(s, l));
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  return verts;
}

// Co-spherical clusters: connected sets of co-spherical neighbour tets.
void Completion3::unite_clusters(const PairBlocks& cocirc) {
  for (const auto& v : cocirc)
    for (const auto& pr : v) {
      clusters_.join(pr[0], pr[1]);
      in_cluster_[static_cast<std::size_t>(pr[0])] = in_cluster_[static_cast<std::size_t>(pr[1])] = 1;
    }
}

// For each face: the tet on its positive side ("a") and negative side ("b").
void Completion3::find_side_tets() {
  const std::size_t T = tet_.size();
  auto owns = [&](std::size_t t, int i) {
    const int nb = nbr_[t][static_cast<std::size_t>(i)];
    return nb == -1 || static_cast<std::size_t>(nb) > t;
  };
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i) {
      if (!owns(t, i)) continue;
      const int nb = nbr_[t][static_cast<std::size_t>(i)];
      const int tp = static_cast<int>(t);
      side_tet_[static_cast<std::size_t>(simplex_face_[t][static_cast<std::size_t>(i)])] =
          FaceOrder(tet_[t], i).side > 0 ? std::array<int, 2>{tp, nb} : std::array<int, 2>{nb, tp};
    }
}

void Completion3::unite_discs(const std::vector<std::array<int, 2>>& disc_pairs) {
  for (const auto& pr : disc_pairs) {
    discs_.join(pr[0], pr[1]);
    in_disc_[static_cast<std::size_t>(pr[0])] = in_disc_[static_cast<std::size_t>(pr[1])] = 1;
  }
}

// With clusters: two candidate faces sharing an edge and an owner on a common side, coplanar
// and co-circular, are in one disc group.
void Completion3::link_cluster_discs() {
  std::unordered_map<std::array<int, 2>, std::vector<int>, ArrayHash> edge_faces;
  for (int f : disc_candidates())
    for (int a = 0; a < 3; ++a)
      for (int b = a + 1; b < 3; ++b)
        edge_faces[{faces_.vertex(static_cast<std::size_t>(f), a), faces_.vertex(static_cast<std::size_t>(f), b)}].push_back(f);
  std::vector<std::array<int, 2>> keys;
  keys.reserve(edge_faces.size());
  for (const auto& kv : edge_faces) keys.push_back(kv.first);
  std::sort(keys.begin(), keys.end());
  for (const auto& e : keys) {
    const auto& fl = edge_faces[e];
    for (std::size_t x = 0; x < fl.size(); ++x)
      for (std::size_t y = x + 1; y < fl.size(); ++y) link_if_one_disc(e, fl[x], fl[y]);
  }
}

bool Completion3::any_disc() const {
  return std::any_of(in_disc_.begin(), in_disc_.end(), [](char c) { return c != 0; });
}

// The Delaunay faces, so that no triple is added twice.
void Completion3::mark_present() {
  for (std::size_t f = 0; f < F0_; ++f)
    present_.insert({faces_.vertex(f, 0), faces_.vertex(f, 1), faces_.vertex(f, 2)});
}

// (1) disc groups, in the order of their roots.
Status Completion3::complete_discs() {
  std::map<int, std::vector<int>> disc_members;
  for (std::size_t f = 0; f < F0_; ++f)
    if (in_disc_[f]) disc_members[discs_.find(static_cast<int>(f))].push_back(static_cast<int>(f));
  for (const auto& [root, fl] : disc_members)
    if (Status s = complete_disc(root, fl); !s) return s;
  return Status::ok();
}

// (2) co-spherical clusters, in the order of their roots.
Status Completion3::complete_clusters() {
  std::map<int, std::vector<int>> cluster_members;
  for (std::size_t t = 0; t < tet_.size(); ++t)
    if (in_cluster_[t]) cluster_members[clusters_.find(static_cast<int>(t))].push_back(static_cast<int>(t));
  for (const auto& [root, tl] : cluster_members)
    if (Status s = complete_cluster(tl); !s) return s;
  return Status::ok();
}

// Candidate faces for disc groups: hull faces and faces of clustered tets (other than those
// inside one cluster).
std::vector<int> Completion3::disc_candidates() {
  std::vector<int> cand;
  for (std::size_t f = 0; f < F0_; ++f) {
    const auto& st = side_tet_[f];
    const bool hull_face = st[0] == -1 || st[1] == -1;
    const bool clus = (st[0] >= 0 && in_cluster_[static_cast<std::size_t>(st[0])]) ||
                      (st[1] >= 0 && in_cluster_[static_cast<std::size_t>(st[1])]);
    if (hull_face || (clus && !(st[0] >= 0 && st[1] >= 0 && in_cluster_[static_cast<std::size_t>(st[0])] &&
                                in_cluster_[static_cast<std::size_t>(st[1])] &&
                                clusters_.find(st[0]) == clusters_.find(st[1]))))
      cand.push_back(static_cast<int>(f));
  }
  return cand;
}

// The "owner" of a candidate face on one side: -2 for the hull, else the cluster root it
// bounds (-3: an unclustered tet).
int Completion3::owner(int f, int side) {
  const int t = side_tet_[static_cast<std::size_t>(f)][static_cast<std::size_t>(side)];
  if (t < 0) return -2;
  return in_cluster_[static_cast<std::size_t>(t)] ? clusters_.find(t) : -3;
}

// Candidates f1, f2 on the common edge e.
void Completion3::link_if_one_disc(const std::array<int, 2>& e, int f1, int f2) {
  // Same owner on a common side: both hull faces, or both bounding the same cluster.
  bool same = false;
  for (int s1 = 0; s1 < 2 && !same; ++s1)
    for (int s2 = 0; s2 < 2 && !same; ++s2) {
      const int o1 = owner(f1, s1), o2 = owner(f2, s2);
      same = (o1 == -2 && o2 == -2) || (o1 >= 0 && o1 == o2);
    }
  if (!same) return;
  int d = -1;
  for (int a = 0; a < 3; ++a) {
    const int v = faces_.vertex(static_cast<std::size_t>(f2), a);
    if (v != e[0] && v != e[1]) d = v;
  }
  const double* A = P(faces_.vertex(static_cast<std::size_t>(f1), 0));
  const double* B = P(faces_.vertex(static_cast<std::size_t>(f1), 1));
  const double* C = P(faces_.vertex(static_cast<std::size_t>(f1), 2));
  if (orient3(A, B, C, P(d)) != 0 || in_circle_coplanar3(A, B, C, P(d)) != 0) return;
  discs_.join(f1, f2);
  in_disc_[static_cast<std::size_t>(f1)] = in_disc_[static_cast<std::size_t>(f2)] = 1;
}

// Counts the triples of m points against kMaxCompletionFaces.
Status Completion3::budget(std::size_t m) {
  added_ += m * (m - 1) * (m - 2) / 6;
  if (added_ > kMaxCompletionFaces)
    return {StatusCode::Unsupported, "too many co-spherical points: the complete γ([-1,1],[0,1]) graph would exceed " +
                                         std::to_string(kMaxCompletionFaces) + " triangles"};
  return Status::ok();
}

// One disc group (faces fl, root rep): every further non-collinear triple of its points copies
// the side values of rep, oriented by an off-plane witness point.
Status Completion3::complete_disc(int rep, const std::vector<int>& fl) {
  const std::vector<int> verts =
      distinct_vertices(fl, 3, [&](int f, int a) { return faces_.vertex(static_cast<std::size_t>(f), a); });
  if (Status s = budget(verts.size()); !s) return s;
  const double ra = faces_.gamma_a[static_cast<std::size_t>(rep)], rb = faces_.gamma_b[static_cast<std::size_t>(rep)];
  // An off-plane witness point and its side w.r.t. the representative face.
  const auto& st = side_tet_[static_cast<std::size_t>(rep)];
  const int wt = st[0] >= 0 ? st[0] : st[1];
  int witness = -1;
  for (int l = 0; l < 4 && witness < 0; ++l) {
    const int v = tet_[static_cast<std::size_t>(wt)][static_cast<std::size_t>(l)];
    if (std::find(verts.begin(), verts.end(), v) == verts.end()) witness = v;
  }
  CONSTRICT_CHECK(witness >= 0, "disc group without an off-plane witness");
  const int rep_side = orient3(P(faces_.vertex(static_cast<std::size_t>(rep), 0)), P(faces_.vertex(static_cast<std::size_t>(rep), 1)),
                               P(faces_.vertex(static_cast<std::size_t>(rep), 2)), P(witness));
  const std::size_t m = verts.size();
  for (std::size_t x = 0; x < m; ++x)
    for (std::size_t y = x + 1; y < m; ++y)
      for (std::size_t z = y + 1; z < m; ++z) {
        const std::array<int, 3> tr{verts[x], verts[y], verts[z]};
        if (present_.count(tr)) continue;
        if (collinear3(P(tr[0]), P(tr[1]), P(tr[2]))) continue;
        const int s = orient3(P(tr[0]), P(tr[1]), P(tr[2]), P(witness));
        present_.insert(tr);
        const double ga = s == rep_side ? ra : rb, gb = s == rep_side ? rb : ra;
        faces_.push_back(tr.data(), ga, gb,
                         static_cast<std::uint8_t>(kFaceCospherical | (ga == 1.0 || gb == 1.0 ? kFaceHull : 0)));
      }
  return Status::ok();
}

// One co-spherical cluster (tets tl): every missing triple with cluster points on both sides.
Status Completion3::complete_cluster(const std::vector<int>& tl) {
  const std::vector<int> verts = distinct_vertices(
      tl, 4, [&](int t, int l) { return tet_[static_cast<std::size_t>(t)][static_cast<std::size_t>(l)]; });
  if (Status s = budget(verts.size()); !s) return s;
  const std::vector<int> lex = lex_sorted(points_, verts);
  const std::size_t m = verts.size();
  for (std::size_t x = 0; x < m; ++x)
    for (std::size_t y = x + 1; y < m; ++y)
      for (std::size_t z = y + 1; z < m; ++z) {
        const std::array<int, 3> tr{verts[x], verts[y], verts[z]};
        if (present_.count(tr)) continue;
        push_cluster_triple(lex, tr);
      }
  return Status::ok();
}

// The triple tr of a cluster with points lex (lexicographic order): side values ±g from the
// first cluster point on each side.
void Completion3::push_cluster_triple(const std::vector<int>& lex, const std::array<int, 3>& tr) {
  const double *A = P(tr[0]), *B = P(tr[1]), *C = P(tr[2]);
  if (collinear3(A, B, C)) return;
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
  if (wa < 0 || wb < 0) return;
  double ga = apex_gamma3(A, B, C, P(wa));
  double gb = apex_gamma3(A, B, C, P(wb));
  detail::reconcile_side_values(ga, gb, 0);
  present_.insert(tr);
  faces_.push_back(tr.data(), ga, gb, kFaceCospherical);
}

}  // namespace

}  // namespace constrict
