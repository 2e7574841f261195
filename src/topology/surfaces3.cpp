// SPDX-License-Identifier: GPL-3.0-or-later
// reconstruct_surfaces3(): the 3D ladder of topology.hpp (docs/topology.md §"3D") -- parts by the
// exact gap rule on the Delaunay edges (between 3/4 of its threshold and the threshold the engine's
// labels decide: parts that nearly touch; a small part that the labels show to be a patch of its
// neighbour's surface joins it); one part -> reconstruct3() (with handles in Auto); several
// -> one reconstruct3() per part, then the body of all of them from the Delaunay tetrahedralization
// of all points by the parity of the surfaces around each tetrahedron (inner shells become
// cavities), roles and parents from the nesting tree. Any step that does not hold exactly (a part
// too small, a surface face that is not a Delaunay face of all points, an inconsistent nesting)
// falls back to one part. Then the exact validation of what came out.
//
// Exactness contract: the nearest neighbours (compare_distance3) and the gap rule (compare_gap3)
// are exact predicates; the rest is combinatorics over the Delaunay tetrahedralization. Doubles
// are computed for the report (gap_spacings), and the split of parts that nearly touch reads the
// engine's circumball labels (doubles, as the engine's growth and handle stage read them; the same
// for the same points in any order). Parts and surfaces are ordered by their
// lexicographically smallest point, so the result does not depend on the file order.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "constrict/criterion.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/predicates.hpp"
#include "constrict/topology.hpp"
#include "constrict/detail/share3.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/bucket_sort.hpp"
#include "core/detail/canonical_order.hpp"
#include "core/detail/check_points.hpp"
#include "core/detail/edge_key.hpp"
#include "core/detail/link_cycle.hpp"
#include "core/detail/semi_static.hpp"
#include "core/detail/tet_faces.hpp"
#include "core/detail/tet_order.hpp"
#include "core/detail/union_find.hpp"

namespace constrict {
namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
inline std::size_t uz(int i) { return static_cast<std::size_t>(i); }

using detail::kFaceOut;

bool lex_less3(const double* p, const double* q) {
  return std::lexicographical_compare(p, p + 3, q, q + 3);
}

using detail::UnionFind;

// Calls f(p, q) for the 6 edges of every tetrahedron (an edge once per tetrahedron around it).
template <class F>
void for_tet_edges(const Delaunay3& dt, F&& f) {
  for (const auto& t : dt.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) f(t[uz(i)], t[uz(j)]);
}

// The local spacing at a point: the distance to its kSpacingRank-th nearest Delaunay neighbour. The
// nearest one alone is too small where a random sampling clumps (Poisson samples of a surface
// split into a hundred "parts" at T = 2 by the nearest-neighbour distance); the third is close to
// the sampling spacing for blue-noise and random samples alike (docs/topology.md §"3D").
constexpr int kSpacingRank = 3;

// |ab|² summed coordinate by coordinate, as compare_gap3 sums it (the same double).
double len2(const double* a, const double* b) {
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

// Each point's kSpacingRank-th nearest Delaunay neighbour (exact comparisons; ties -> the
// lexicographically smaller point; fewer neighbours -> the farthest).
std::vector<int> spacing_neighbours(const PointSet& pts, const Delaunay3& dt) {
  constexpr int k = kSpacingRank;
  // Each point's k nearest so far and their len2 from it, sorted; one such list per task.
  struct Nearest {
    std::vector<std::array<int, k>> id;
    std::vector<std::array<double, k>> d2;
  };
  // Is q (at squared distance dq from p) nearer to p than r (dr)? compare_distance3's own filter
  // (gap_filtered) on the cached squared lengths, its exact arithmetic when that cannot decide.
  const auto closer = [&](int p, int q, double dq, int r, double dr) {
    bool ok = false;
    int c = detail::gap_filtered(dq, dr, 1.0, 1, 3, ok);
    if (!ok) c = compare_distance3(pts[uz(p)], pts[uz(q)], pts[uz(r)]);
    return c < 0 || (c == 0 && lex_less3(pts[uz(q)], pts[uz(r)]));
  };
  const auto offer = [&](Nearest& nb, int p, int q) {
    auto& b = nb.id[uz(p)];
    auto& d = nb.d2[uz(p)];
    for (int x : b)
      if (x == q) return;
    const double dq = len2(pts[uz(p)], pts[uz(q)]);
    // Insert q into the sorted list of the k nearest so far.
    int i = k;
    while (i > 0 && (b[uz(i - 1)] < 0 || closer(p, q, dq, b[uz(i - 1)], d[uz(i - 1)]))) --i;
    if (i == k) return;
    for (int j = k - 1; j > i; --j) {
      b[uz(j)] = b[uz(j - 1)];
      d[uz(j)] = d[uz(j - 1)];
    }
    b[uz(i)] = q;
    d[uz(i)] = dq;
  };
  // The order "nearer" is a strict total order (ties to the lexicographically smaller point), so
  // the k nearest of a point are the k nearest of the union of any split of its offers. In
  // parallel over fixed blocks of tetrahedra (each task its own lists), then the lists merged per
  // point: the same lists for any number of threads. (Ranges of points whose tasks each read every
  // tetrahedron read them twice on two cores: 0.44-0.49 s on a torus of 3·10^5 random points, 5 M
  // tetrahedra; 0.33-0.34 s so, in 2 of 3 runs.)
  const std::size_t nt = dt.tets.size();
  constexpr std::size_t kBlocks = 2;
  const std::size_t blocks = nt < (std::size_t{1} << 16) ? 1 : kBlocks;
  std::vector<Nearest> lists(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t blk) {
    Nearest& nb = lists[blk];
    std::array<int, k> none;
    none.fill(-1);
    nb.id.assign(pts.size(), none);
    nb.d2.resize(pts.size());
    for (std::size_t t = nt * blk / blocks, e = nt * (blk + 1) / blocks; t < e; ++t) {
      const auto& v = dt.tets[t];
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          offer(nb, v[uz(i)], v[uz(j)]);
          offer(nb, v[uz(j)], v[uz(i)]);
        }
    }
  });
  std::vector<int> out(pts.size(), -1);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pts.size(), std::size_t{1} << 14),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v != r.end(); ++v) {
                        for (std::size_t blk = 1; blk < blocks; ++blk)
                          for (int x : lists[blk].id[v])
                            if (x >= 0) offer(lists[0], static_cast<int>(v), x);
                        for (int x : lists[0].id[v])
                          if (x >= 0) out[v] = x;
                      }
                    });
  return out;
}

struct Parts {
  std::vector<int> part_of;              // per point
  std::vector<std::vector<int>> points;  // per part, ascending ids
  double min_gap = std::numeric_limits<double>::infinity();
  std::vector<std::array<int, 2>> long_edges;  // the Delaunay edges the gap rule did not join (p < q)
};

// |pq| / rms(nn(p), nn(q)) in double (the report).
double gap_ratio(const PointSet& pts, const std::vector<int>& nn, int p, int q) {
  const double s = 0.5 * (len2(pts[uz(p)], pts[uz(nn[uz(p)])]) + len2(pts[uz(q)], pts[uz(nn[uz(q)])]));
  return std::sqrt(len2(pts[uz(p)], pts[uz(q)]) / s);
}

// Can the points have a closed surface of their own: at least min_points (and 4), not all
// coplanar (exact)?
bool solid_part(const PointSet& pts, const std::vector<int>& ids, std::size_t min_points) {
  if (ids.size() < std::max<std::size_t>(4, min_points)) return false;
  const double* a = pts[uz(ids[0])];
  std::size_t j = 1;
  while (j < ids.size() && std::equal(a, a + 3, pts[uz(ids[j])])) ++j;
  if (j == ids.size()) return false;
  const double* b = pts[uz(ids[j])];
  std::size_t k = j + 1;
  while (k < ids.size() && collinear3(a, b, pts[uz(ids[k])])) ++k;
  if (k == ids.size()) return false;
  const double* c = pts[uz(ids[k])];
  for (std::size_t l = k + 1; l < ids.size(); ++l)
    if (orient3(a, b, c, pts[uz(ids[l])]) != 0) return true;
  return false;
}

// Is Delaunay edge e shorter than f (exact; ties -> the smaller pair of lexicographic endpoints)?
bool shorter_edge(const PointSet& pts, const std::array<int, 2>& e, const std::array<int, 2>& f) {
  const double* a[1] = {pts[uz(f[0])]};
  const double* b[1] = {pts[uz(f[1])]};
  const int c = compare_gap3(pts[uz(e[0])], pts[uz(e[1])], a, b, 1, 1.0);
  if (c != 0) return c < 0;
  const auto lo = [&](const std::array<int, 2>& x) { return lex_less3(pts[uz(x[0])], pts[uz(x[1])]) ? x[0] : x[1]; };
  const auto hi = [&](const std::array<int, 2>& x) { return lo(x) == x[0] ? x[1] : x[0]; };
  if (lo(e) != lo(f)) return lex_less3(pts[uz(lo(e))], pts[uz(lo(f))]);
  return lex_less3(pts[uz(hi(e))], pts[uz(hi(f))]);
}

// The components of the union-find, ordered by their lexicographically smallest point.
Parts collect_parts(const PointSet& pts, UnionFind& uf) {
  std::vector<int> root_best(pts.size(), -1);
  for (std::size_t v = 0; v < pts.size(); ++v) {
    int& b = root_best[uz(uf.find(static_cast<int>(v)))];
    if (b < 0 || lex_less3(pts[v], pts[uz(b)])) b = static_cast<int>(v);
  }
  std::vector<int> roots;
  for (std::size_t v = 0; v < pts.size(); ++v)
    if (uf.find(static_cast<int>(v)) == static_cast<int>(v)) roots.push_back(static_cast<int>(v));
  std::sort(roots.begin(), roots.end(), [&](int a, int b) { return lex_less3(pts[uz(root_best[uz(a)])], pts[uz(root_best[uz(b)])]); });
  std::vector<int> index_of(pts.size(), -1);
  for (std::size_t k = 0; k < roots.size(); ++k) index_of[uz(roots[k])] = static_cast<int>(k);
  Parts out;
  out.part_of.resize(pts.size());
  out.points.resize(roots.size());
  for (std::size_t v = 0; v < pts.size(); ++v) {
    const int k = index_of[uz(uf.find(static_cast<int>(v)))];
    out.part_of[v] = k;
    out.points[uz(k)].push_back(static_cast<int>(v));
  }
  return out;
}

// Sorts the edges (p < q) ascending and drops repeats: a bucket sort on the pair as one 64-bit key
// (millions of edges at 10^6 points; tbb::parallel_sort took 0.4 s for 6 M on two cores, this
// 0.19 s).
void sort_unique_edges(std::vector<std::array<int, 2>>& edges) {
  detail::BigArray<std::array<int, 2>> a;
  a.allocate(edges.size());
  std::copy(edges.begin(), edges.end(), a.data());
  const auto key = [](const std::array<int, 2>& e) { return detail::edge_key(e[0], e[1]); };  // (p < q: ascending pairs)
  detail::bucket_sort(a, key, [&](const std::array<int, 2>& x, const std::array<int, 2>& y) { return key(x) < key(y); });
  edges.assign(a.data(), std::unique(a.data(), a.data() + a.size()));
}

// The small parts (fewer than min_points, or flat: a few outliers) each join the part across their
// shortest Delaunay edge, until none is left; then the parts, with the edges between them.
Parts settle_parts(const PointSet& pts, const std::vector<int>& nn, UnionFind& uf, std::vector<std::array<int, 2>> long_edges,
                   std::size_t min_points, std::size_t& merged) {
  // (Millions of edges at 10^6 points, most of them inside one part: a strict order, so the
  // parallel sort gives the sequential one's array. 10^6 ellipsoid: 2.3 M edges.)
  sort_unique_edges(long_edges);
  // (The list had each edge once per tetrahedron met before its ends were joined; it lives through
  // the engine's run: its room at 10^6 points was 67 MB per rule for 2 M edges and for 850.)
  long_edges.shrink_to_fit();
  merged = 0;
  for (;;) {
    Parts parts = collect_parts(pts, uf);
    std::vector<char> small(parts.points.size(), 0);
    bool any = false;
    if (parts.points.size() > 1)
      for (std::size_t k = 0; k < parts.points.size(); ++k) any = (small[k] = !solid_part(pts, parts.points[k], min_points)) || any;
    if (!any) {
      for (const auto& e : long_edges)
        if (parts.part_of[uz(e[0])] != parts.part_of[uz(e[1])])
          parts.min_gap = std::min(parts.min_gap, gap_ratio(pts, nn, e[0], e[1]));
      parts.long_edges = std::move(long_edges);
      return parts;
    }
    // The shortest edge out of each small part.
    std::vector<int> best(parts.points.size(), -1);
    for (std::size_t i = 0; i < long_edges.size(); ++i) {
      const int a = parts.part_of[uz(long_edges[i][0])], b = parts.part_of[uz(long_edges[i][1])];
      if (a == b) continue;
      for (int k : {a, b})
        if (small[uz(k)] && (best[uz(k)] < 0 || shorter_edge(pts, long_edges[i], long_edges[uz(best[uz(k)])]))) best[uz(k)] = static_cast<int>(i);
    }
    // (All at once: two small parts may join each other; the next round checks again.)
    for (std::size_t k = 0; k < parts.points.size(); ++k)
      if (small[k] && best[k] >= 0) {
        uf.join(long_edges[uz(best[k])][0], long_edges[uz(best[k])][1]);
        ++merged;
      }
  }
}

// Is the Delaunay edge pq shorter than g · rms(spacing at p, spacing at q) (compare_gap3, exact)?
bool edge_shorter(const PointSet& pts, const std::vector<int>& nn, int p, int q, double g) {
  const double* a[2] = {pts[uz(p)], pts[uz(q)]};
  const double* b[2] = {pts[uz(nn[uz(p)])], pts[uz(nn[uz(q)])]};
  return compare_gap3(pts[uz(p)], pts[uz(q)], a, b, 2, g) < 0;
}

// The narrower rule's pieces, robust to a random sample's sparse spots (docs/topology.md, "Inner
// shells of random samples"). A point in a hole of a uniformly random sample has a spacing about
// twice its neighbours', and then an edge to the next shell three spacings away passed the
// narrower rule: one or two such edges joined two shells into one piece (9 of 24 random nested
// sets at 3 area spacings, measured). So an edge joins pieces at once only below kStrictShare of
// the narrower rule's factor. An edge between that and the narrower rule (a loose edge) joins two
// strict pieces when one of them has fewer than kLoosePiece points, or when on each side at least
// kLooseEnds points, and at least kLooseShare of the points with a Delaunay edge to the other
// piece, have loose edges to it (two shells 3 spacings apart: 1-7 of 3 000-15 000 points).
constexpr double kStrictShare = 1.2 / 1.5;
constexpr std::size_t kLoosePiece = 64;
constexpr std::size_t kLooseEnds = 3;
constexpr double kLooseShare = 0.02;

// The strict pieces (uf_strict) joined by the loose edges (see kStrictShare). long_fine holds the
// Delaunay edges between two of the narrower rule's pieces as find_parts met them; where loose
// edges leave two strict pieces apart, the edges between the final pieces within one of those are
// added (a second pass over the tetrahedra, only when two large strict pieces have loose edges
// between them).
void join_loose(const Delaunay3& dt, UnionFind& uf_strict, std::vector<std::array<int, 2>> loose,
                std::vector<std::array<int, 2>>& long_fine) {
  const auto compact = [](auto& v) {  // sorted, without repeats
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  compact(loose);
  if (loose.empty()) return;
  // (Sizes and roots of the strict pieces, before any loose join: the decisions do not depend on
  // the order in which the joins are made.)
  const std::size_t n = uf_strict.up.size();
  std::vector<int> root(n);
  std::vector<std::size_t> size(n, 0);  // per root
  for (std::size_t v = 0; v < n; ++v) ++size[uz(root[v] = uf_strict.find(static_cast<int>(v)))];
  using End = std::array<int, 4>;  // the two pieces' roots (ascending), the side (0, 1), a point there
  std::vector<std::array<int, 2>> join;
  std::vector<End> ends;
  for (const auto& e : loose) {
    const int a = root[uz(e[0])], b = root[uz(e[1])];
    if (a == b) continue;
    if (size[uz(a)] < kLoosePiece || size[uz(b)] < kLoosePiece) {
      join.push_back(e);
    } else {  // (side 0: the piece with the smaller root)
      ends.push_back({std::min(a, b), std::max(a, b), a < b ? 0 : 1, e[0]});
      ends.push_back({std::min(a, b), std::max(a, b), a < b ? 1 : 0, e[1]});
    }
  }
  compact(ends);
  std::vector<std::array<int, 2>> pairs;  // the candidate pairs of large strict pieces, ascending
  for (const End& x : ends)
    if (pairs.empty() || pairs.back() != std::array<int, 2>{x[0], x[1]}) pairs.push_back({x[0], x[1]});
  // Each candidate pair's interface (the points with a Delaunay edge to the other piece, as
  // (pair, point) keys), and every edge between two strict pieces (for long_fine below). The pass
  // meets an edge once per tetrahedron, so both lists are compacted whenever they outgrow their
  // bound, 2 n entries or twice their distinct ones (a hollow ball of 914 381 random points: 10.2
  // million edge visits across its gap, 20.2 million interface entries, 0.9 million distinct).
  std::vector<std::uint64_t> face;
  std::vector<std::array<int, 2>> cross;
  std::size_t face_bound = std::max<std::size_t>(2 * n, std::size_t{1} << 16), cross_bound = face_bound;
  const auto compact_over = [&](auto& v, std::size_t& bound) {
    if (v.size() <= bound) return;
    compact(v);
    if (v.size() > bound / 2) bound *= 2;  // (mostly distinct: let it grow, amortised)
  };
  if (!pairs.empty())
    for_tet_edges(dt, [&](int p, int q) {
      const int a = root[uz(p)], b = root[uz(q)];
      if (a == b) return;
      cross.push_back({std::min(p, q), std::max(p, q)});
      compact_over(cross, cross_bound);
      const auto it = std::lower_bound(pairs.begin(), pairs.end(), std::array<int, 2>{std::min(a, b), std::max(a, b)});
      if (it == pairs.end() || *it != std::array<int, 2>{std::min(a, b), std::max(a, b)}) return;
      const auto k = static_cast<std::uint64_t>(it - pairs.begin()) << 32;
      face.push_back(k | static_cast<std::uint32_t>(p));
      face.push_back(k | static_cast<std::uint32_t>(q));
      compact_over(face, face_bound);
    });
  compact(face);
  compact(cross);
  std::size_t ie = 0, jf = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto& pr = pairs[k];
    std::size_t loose_n[2] = {0, 0}, face_n[2] = {0, 0};
    for (; ie < ends.size() && ends[ie][0] == pr[0] && ends[ie][1] == pr[1]; ++ie) ++loose_n[uz(ends[ie][2])];
    for (; jf < face.size() && (face[jf] >> 32) == k; ++jf) ++face_n[root[face[jf] & 0xffffffffu] == pr[0] ? 0 : 1];
    bool both = true;
    for (int s = 0; s < 2; ++s)
      both = both && loose_n[s] >= kLooseEnds && static_cast<double>(loose_n[s]) >= kLooseShare * static_cast<double>(face_n[s]);
    if (both) join.push_back(pr);
  }
  for (const auto& e : join) uf_strict.join(e[0], e[1]);
  for (const auto& e : loose)
    if (uf_strict.find(e[0]) != uf_strict.find(e[1])) long_fine.push_back(e);
  for (const auto& e : cross)
    if (uf_strict.find(e[0]) != uf_strict.find(e[1])) long_fine.push_back(e);
}

// The edges met lately, in a direct-mapped table of 2^16 slots (512 KB: the second-level cache).
// for_tet_edges meets an edge once per tetrahedron around it, about five times, and tetrahedra in
// their spatial order meet it again soon: seen() tells most of those repeats (a slot holds the
// last edge hashed to it, so some repeats pass, and nothing else is ever told seen).
struct RecentEdges {
  std::vector<std::uint64_t> slot = std::vector<std::uint64_t>(std::size_t{1} << 16, ~std::uint64_t{0});
  /// Was {p, q} the last edge of its slot? Makes it so.
  bool seen(int p, int q) {
    const std::uint64_t key = detail::edge_key(p, q);
    std::uint64_t& s = slot[(key * 0x9E3779B97F4A7C15ull) >> 40 & (slot.size() - 1)];
    if (s == key) return true;
    s = key;
    return false;
  }
};

// Parts: components of the Delaunay edges shorter than gap local spacings, then settle_parts().
// And in the same pass over the edges the parts of the narrower rule (narrow · gap; split_by_labels).
Parts find_parts(const PointSet& pts, const Delaunay3& dt, const std::vector<int>& nn, double gap, double narrow,
                 std::size_t min_points, std::size_t& merged, Parts& fine) {
  // uf: the gap rule; uf_narrow: the narrower rule's edges; uf_fine: its strict pieces, joined
  // by the loose edges at the end (join_loose).
  UnionFind uf(pts.size()), uf_narrow(pts.size()), uf_fine(pts.size());
  std::vector<std::array<int, 2>> long_edges, long_fine, loose;
  const double strict = kStrictShare * narrow;
  // (An edge whose ends are joined already decides nothing: every edge between two final parts
  // is tested, and recorded as long. The narrower rule's parts lie within the rule's.)
  // Each point's squared spacing, as compare_gap3 sums it: its filter (gap_filtered) decides most
  // edges from these, its exact arithmetic the rest.
  std::vector<double> s2(pts.size());
  for (std::size_t v = 0; v < pts.size(); ++v) s2[v] = len2(pts[v], pts[uz(nn[v])]);
  const auto shorter = [&](int p, int q, double g) {
    bool ok = false;
    const int c = detail::gap_filtered(2.0 * len2(pts[uz(p)], pts[uz(q)]), s2[uz(p)] + s2[uz(q)], g, 2, 3, ok);
    return ok ? c < 0 : edge_shorter(pts, nn, p, q, g);
  };
  RecentEdges recent;
  // (uf, uf_narrow and long_fine evolve as they did with the narrower rule alone: an edge within
  // one of its pieces is recorded only if join_loose leaves strict pieces apart, and found then.)
  for_tet_edges(dt, [&](int p, int q) {
    if (uf_fine.find(p) == uf_fine.find(q)) return;
    // (A repeat changes no union-find and adds only entries already in the lists, which are sorted
    // and made unique later: skipped. A torus of 3·10^5 random points: 30 M edge visits, 17 M
    // long edges and 19 M of the narrower rule's before, 6 M and 6 M now.)
    if (recent.seen(p, q)) return;
    const bool same_narrow = uf_narrow.find(p) == uf_narrow.find(q);
    if (shorter(p, q, narrow)) {
      if (!same_narrow) {
        uf_narrow.join(p, q);
        uf.join(p, q);
      }
      if (shorter(p, q, strict)) uf_fine.join(p, q);
      else loose.push_back({std::min(p, q), std::max(p, q)});
      return;
    }
    if (same_narrow) return;
    long_fine.push_back({std::min(p, q), std::max(p, q)});
    if (uf.find(p) == uf.find(q)) return;
    if (shorter(p, q, gap)) uf.join(p, q);
    else long_edges.push_back({std::min(p, q), std::max(p, q)});
  });
  join_loose(dt, uf_fine, std::move(loose), long_fine);
  // (Most of the narrower rule's long edges end up inside one of its parts: only those between
  // parts are kept. On 10^6 random points of a star-shaped surface the list held millions.)
  long_fine.erase(std::remove_if(long_fine.begin(), long_fine.end(),
                                 [&](const std::array<int, 2>& e) { return uf_fine.find(e[0]) == uf_fine.find(e[1]); }),
                  long_fine.end());
  std::size_t merged_fine = 0;
  fine = settle_parts(pts, nn, uf_fine, std::move(long_fine), min_points, merged_fine);
  return settle_parts(pts, nn, uf, std::move(long_edges), min_points, merged);
}

// The parts whose points share a group (group(v) < groups), ordered as collect_parts() orders
// them, with the edges of @p edge_lists that run between two of them and their smallest gap.
template <class Group>
Parts regroup(const PointSet& pts, const std::vector<int>& nn, std::size_t groups, const Group& group,
              std::initializer_list<const std::vector<std::array<int, 2>>*> edge_lists) {
  UnionFind uf(pts.size());
  std::vector<int> first(groups, -1);
  for (std::size_t v = 0; v < pts.size(); ++v) {
    int& f = first[uz(group(v))];
    if (f < 0) f = static_cast<int>(v);
    uf.join(f, static_cast<int>(v));
  }
  Parts out = collect_parts(pts, uf);
  for (const std::vector<std::array<int, 2>>* edges : edge_lists)
    for (const auto& e : *edges)
      if (out.part_of[uz(e[0])] != out.part_of[uz(e[1])]) out.long_edges.push_back(e);
  std::sort(out.long_edges.begin(), out.long_edges.end());
  out.long_edges.erase(std::unique(out.long_edges.begin(), out.long_edges.end()), out.long_edges.end());
  for (const auto& e : out.long_edges) out.min_gap = std::min(out.min_gap, gap_ratio(pts, nn, e[0], e[1]));
  return out;
}

// ---- parts that nearly touch ------------------------------------------------------------------

// Between kNarrowGap · T and T local spacings the gap rule joins two parts and the engine's
// circumball labels decide (docs/topology.md, "Parts that nearly touch"): the pieces that the
// narrower rule keeps apart stay apart unless tetrahedra labelled inside join them, i.e. unless at
// least kInsideShare of the points of one of the two pieces lie on such a tetrahedron. Measured:
// two boxes or plates 2.5-3 spacings apart (their gap labelled outside but for label noise) have
// 0.05-1 % of their points there; a piece of one object that a sampling gap of a sparse quarter
// left apart 30 %, the cluster of a noisy figure eight 100 %, the two shells of a hollow ball 100 %.
constexpr double kNarrowGap = 0.75;
constexpr double kInsideShare = 0.05;

// An inner shell surrounds a void: tetrahedra labelled outside, face-connected, that meet no
// convex-hull face, with the object's wall around them (every face across which the void ends has
// a tetrahedron labelled inside beyond it). The shell's points are the void's boundary; so are a
// shell's around a cavity that holds another part (its points are then on the void as well). A
// piece lies around a void when at least half its points are vertices of the void's tetrahedra,
// and the void is large: at least kVoidTets tetrahedra and kVoidTets points, one tetrahedron at
// least kVoidWidth local spacings across (its longest edge over the largest spacing of its
// vertices), as the handle stage asks of a cavity it seals inside one part (handles3.cpp; there
// the voids of real inner shells measured 263+ tetrahedra, 99+ points and 5.66+ spacings, the
// pockets of noise and of closed cuts at most 32, 48 and 4.55). Measured here: the cavities of
// randomly sampled hollow balls, 15 000 tetrahedra with every point of the inner shell on them;
// the exterior beside the fillets of a decimated bracket reaches the hull. A void 16 times that
// size (kLargeVoidTets tetrahedra, kLargeVoidPoints points) needs no such width: the cavity of a
// shell 3 spacings inside its outer one (random samples) is only 4.8-5.7 spacings across at its
// widest, with 1 588-2 991 points on it (docs/topology.md, "Inner shells of random samples").
constexpr std::size_t kVoidTets = 64;
constexpr double kVoidWidth = 5.0;
constexpr std::size_t kLargeVoidTets = 16 * kVoidTets, kLargeVoidPoints = 16 * kVoidTets;

std::vector<char> pieces_around_voids(const PointSet& pts, const Delaunay3& dt, const std::vector<int>& nn,
                                      const std::vector<int>& piece, const std::vector<std::size_t>& piece_size,
                                      const std::vector<float>& label) {
  std::vector<char> around(piece_size.size(), 0), seen(dt.tets.size(), 0), on(pts.size(), 0);
  std::vector<double> spacing(pts.size());  // the local spacing: to the third Delaunay neighbour
  for (std::size_t v = 0; v < pts.size(); ++v) spacing[v] = std::sqrt(len2(pts[v], pts[uz(nn[v])]));
  std::vector<std::size_t> count(piece_size.size(), 0);
  std::vector<int> comp, stack, points;
  const auto outside = [&](int t) { return label[uz(t)] >= 0; };
  for (std::size_t t0 = 0; t0 < dt.tets.size(); ++t0) {
    if (seen[t0] || !outside(static_cast<int>(t0))) continue;
    seen[t0] = 1;
    comp.assign(1, static_cast<int>(t0));
    stack.assign(1, static_cast<int>(t0));
    bool hull = false;
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int u : dt.neighbors[uz(t)]) {
        if (u < 0) hull = true;
        if (u < 0 || seen[uz(u)] || !outside(u)) continue;
        seen[uz(u)] = 1;
        comp.push_back(u);
        stack.push_back(u);
      }
    }
    if (hull || comp.size() < kVoidTets) continue;
    double widest = 0;
    points.clear();
    for (int t : comp) {
      for (int x : dt.tets[uz(t)])
        if (!on[uz(x)]) {
          on[uz(x)] = 1;
          points.push_back(x);
        }
      widest = std::max(widest, detail::bridge_ratio3(pts, spacing, dt.tets[uz(t)]));
    }
    for (int v : points) on[uz(v)] = 0;
    const bool large = comp.size() >= kLargeVoidTets && points.size() >= kLargeVoidPoints;
    if (points.size() < kVoidTets || (widest < kVoidWidth && !large)) continue;
    for (int v : points) ++count[uz(piece[uz(v)])];
    for (int v : points) {  // each piece on the void once: its count is then cleared
      const std::size_t p = uz(piece[uz(v)]);
      if (count[p] == 0) continue;
      if (2 * count[p] >= piece_size[p]) around[p] = 1;
      count[p] = 0;
    }
  }
  return around;
}

Parts split_by_labels(const PointSet& pts, Delaunay3& dt, const std::vector<int>& nn, Parts parts, const Parts& fine,
                      std::size_t min_points, std::size_t& split) {
  split = 0;
  if (fine.points.size() <= parts.points.size()) return parts;
  // Pieces: the points in one part of each rule (the small parts that each rule joins may differ);
  // numbered in point order.
  std::map<std::pair<int, int>, int> piece_id;
  std::vector<int> piece(pts.size());
  std::vector<std::size_t> piece_size;
  for (std::size_t v = 0; v < pts.size(); ++v) {
    const auto key = std::make_pair(parts.part_of[v], fine.part_of[v]);
    auto it = piece_id.find(key);
    if (it == piece_id.end()) {
      it = piece_id.emplace(key, static_cast<int>(piece_size.size())).first;
      piece_size.push_back(0);
    }
    piece[v] = it->second;
    ++piece_size[uz(it->second)];
  }
  // Per pair of pieces of one part: the points on a tetrahedron labelled inside that spans them.
  const std::vector<float> label = detail::circumball_labels3(pts, dt);
  std::map<std::pair<int, int>, std::vector<int>> touching;
  for (std::size_t t = 0; t < dt.tets.size(); ++t) {
    const auto& v = dt.tets[t];
    const int k = parts.part_of[uz(v[0])];
    bool one_part = true;
    for (int x : v) one_part = one_part && parts.part_of[uz(x)] == k;
    if (!one_part) continue;
    std::array<int, 4> pc{};  // the tetrahedron's pieces, ascending, each once
    for (int i = 0; i < 4; ++i) pc[uz(i)] = piece[uz(v[uz(i)])];
    std::sort(pc.begin(), pc.end());
    const auto end = std::unique(pc.begin(), pc.end());
    for (auto i = pc.begin(); i != end; ++i)
      for (auto j = i + 1; j != end; ++j) {
        std::vector<int>& on = touching[{*i, *j}];
        if (label[t] < 0) on.insert(on.end(), v.begin(), v.end());
      }
  }
  UnionFind joined(static_cast<int>(piece_size.size()));
  std::vector<char> around_void;  // per piece (pieces_around_voids), computed when first asked
  const bool debug = std::getenv("CONSTRICT_DEBUG_HANDLES") != nullptr;  // (docs/cli.md)
  for (auto& [pair, on] : touching) {
    std::sort(on.begin(), on.end());
    on.erase(std::unique(on.begin(), on.end()), on.end());
    std::size_t na = 0, nb = 0;
    for (int x : on) {
      na += piece[uz(x)] == pair.first;
      nb += piece[uz(x)] == pair.second;
    }
    const bool inside = static_cast<double>(na) >= kInsideShare * static_cast<double>(piece_size[uz(pair.first)]) ||
                        static_cast<double>(nb) >= kInsideShare * static_cast<double>(piece_size[uz(pair.second)]);
    // The object's inside between an inner shell and the shell around it is its wall, not a sign
    // of one piece: a piece around a void stays a part of its own, and the nesting of the parts'
    // surfaces (step 3 of the method) makes it the wall's inner surface.
    if (inside && around_void.empty()) around_void = pieces_around_voids(pts, dt, nn, piece, piece_size, label);
    const bool shell = inside && (around_void[uz(pair.first)] || around_void[uz(pair.second)]);
    const bool join = inside && !shell;
    if (debug)
      std::fprintf(stderr, "near parts: pieces of %zu and %zu points, %zu and %zu on inside tetrahedra between them: %s\n",
                   piece_size[uz(pair.first)], piece_size[uz(pair.second)], na, nb,
                   join ? "joined" : shell ? "apart (one lies around a void)" : "apart");
    if (join) joined.join(pair.first, pair.second);
  }
  // The Delaunay edges between the new parts: the gap rule's long edges and the narrower rule's.
  Parts out = regroup(pts, nn, piece_size.size(), [&](std::size_t v) { return joined.find(piece[v]); },
                      {&std::as_const(parts).long_edges, &fine.long_edges});
  if (out.points.size() <= parts.points.size()) return parts;
  for (const auto& p : out.points)
    if (!solid_part(pts, p, min_points)) return parts;
  split = out.points.size() - parts.points.size();
  return out;
}

// ---- patches of one surface ----------------------------------------------------------------------

// A dense patch of a surface (a fillet or a rounded corner of a decimated machined part, whose flat
// faces around it are sparse: long triangles) can lie more than T local spacings from the rest of
// its own surface; it is not an object of its own. Such a part joins its neighbour when, at a gap
// below kPatchGap · T, (1) it is much smaller (kPatchShare), (2) tetrahedra labelled inside span
// it and the neighbour (at least kPatchSideShare of its points on them: the object's inside joins
// them, as between the pieces of split_by_labels), and (3) tetrahedra labelled outside span them
// too (as large a share of its points on them): a patch lies on the surface, with the object on one side
// and the exterior on the other, while an inner shell is surrounded by the object (every
// tetrahedron between it and the outer shell inside) and a separate part by the exterior.
// Measured: docs/topology.md, "Decimated meshes".
constexpr double kPatchGap = 1.6;
constexpr std::size_t kPatchShare = 4;
constexpr double kPatchSideShare = 0.1;

Parts join_patches(const PointSet& pts, Delaunay3& dt, const std::vector<int>& nn, Parts parts, double gap,
                   std::size_t& joined_count) {
  joined_count = 0;
  const std::size_t k = parts.points.size();
  if (k < 2) return parts;
  // Candidate pairs (small, large) with a Delaunay edge below kPatchGap · gap between them.
  std::set<std::pair<int, int>> cand;
  for (const auto& e : parts.long_edges) {
    int a = parts.part_of[uz(e[0])], b = parts.part_of[uz(e[1])];
    if (a == b) continue;
    if (parts.points[uz(a)].size() > parts.points[uz(b)].size()) std::swap(a, b);
    if (parts.points[uz(a)].size() * kPatchShare > parts.points[uz(b)].size()) continue;
    if (cand.count({a, b})) continue;
    if (edge_shorter(pts, nn, e[0], e[1], kPatchGap * gap)) cand.insert({a, b});
  }
  if (cand.empty()) return parts;
  const std::vector<float> label = detail::circumball_labels3(pts, dt);
  // Per candidate pair: its small part's points on tetrahedra spanning the two, labelled inside
  // (first) and outside (second).
  std::map<std::pair<int, int>, std::array<std::vector<int>, 2>> spanning;
  for (std::size_t t = 0; t < dt.tets.size(); ++t) {
    const auto& v = dt.tets[t];
    int pa = parts.part_of[uz(v[0])], pb = pa;
    bool two = true;
    for (int x : v) {
      const int q = parts.part_of[uz(x)];
      if (q == pa || q == pb) continue;
      if (pb == pa) pb = q;
      else two = false;
    }
    if (!two || pa == pb || label[t] == 0) continue;
    for (const auto& pr : {std::make_pair(pa, pb), std::make_pair(pb, pa)}) {
      auto it = cand.find(pr);
      if (it == cand.end()) continue;
      std::vector<int>& on = spanning[pr][label[t] < 0 ? 0 : 1];
      for (int x : v)
        if (parts.part_of[uz(x)] == pr.first) on.push_back(x);
    }
  }
  UnionFind uf(static_cast<int>(k));
  const bool debug = std::getenv("CONSTRICT_DEBUG_HANDLES") != nullptr;  // (docs/cli.md)
  for (const auto& pr : cand) {
    std::array<std::size_t, 2> on{};
    for (int side = 0; side < 2; ++side) {
      std::vector<int>& v = spanning[pr][uz(side)];
      std::sort(v.begin(), v.end());
      on[uz(side)] = static_cast<std::size_t>(std::unique(v.begin(), v.end()) - v.begin());
    }
    const std::size_t n = parts.points[uz(pr.first)].size();
    const bool both = static_cast<double>(on[0]) >= kPatchSideShare * static_cast<double>(n) &&
                      static_cast<double>(on[1]) >= kPatchSideShare * static_cast<double>(n);
    if (debug)
      std::fprintf(stderr, "patch: part of %zu points beside one of %zu: %zu on inside and %zu on outside tetrahedra between them: %s\n",
                   n, parts.points[uz(pr.second)].size(), on[0], on[1], both ? "joined" : "apart");
    if (both && uf.find(pr.first) != uf.find(pr.second)) {
      uf.join(pr.first, pr.second);
      ++joined_count;
    }
  }
  if (joined_count == 0) return parts;
  return regroup(pts, nn, k, [&](std::size_t v) { return uf.find(parts.part_of[v]); }, {&std::as_const(parts).long_edges});
}

// ---- assembling the body of several parts --------------------------------------------------------

struct FaceKey {
  std::array<int, 3> v;
  bool operator==(const FaceKey& o) const { return v == o.v; }
};
struct FaceHash {
  std::size_t operator()(const FaceKey& k) const {
    std::uint64_t h = 1469598103934665603ULL;
    for (int x : k.v) h = (h ^ static_cast<std::uint32_t>(x)) * 1099511628211ULL;
    return static_cast<std::size_t>(h);
  }
};
FaceKey key_of(int a, int b, int c) {
  std::array<int, 3> v{{a, b, c}};
  std::sort(v.begin(), v.end());
  return {v};
}

// The regions of the tetrahedralization between the surface faces (is_surface(t, i): the face
// opposite vertex i of t): face-connected components not crossing one; region 0 is the exterior
// (the tetrahedra that reach the convex hull through a non-surface face). Returns the count.
template <class IsSurface>
int surface_regions(const Delaunay3& dt, IsSurface&& is_surface, std::vector<int>& region) {
  const std::size_t T = dt.tets.size();
  region.assign(T, -1);
  std::vector<int> queue;
  const auto flood = [&](int r) {
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int t = queue[q];
      for (int i = 0; i < 4; ++i) {
        const int m = dt.neighbors[uz(t)][uz(i)];
        if (m < 0 || is_surface(uz(t), i) || region[uz(m)] >= 0) continue;
        region[uz(m)] = r;
        queue.push_back(m);
      }
    }
    queue.clear();
  };
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i)
      if (dt.neighbors[t][uz(i)] < 0 && !is_surface(t, i) && region[t] < 0) {
        region[t] = 0;
        queue.push_back(static_cast<int>(t));
      }
  flood(0);
  int regions = 1;
  for (std::size_t t = 0; t < T; ++t)
    if (region[t] < 0) {
      region[t] = regions;
      queue.push_back(static_cast<int>(t));
      flood(regions++);
    }
  return regions;
}

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

// The body of the part surfaces inside the tetrahedralization of all points: the regions of
// tetrahedra between the surfaces, a tree rooted at the exterior; the body is the regions at odd
// depth. False when a surface face is not a Delaunay face or the regions do not form that tree.
bool assemble_body(const Delaunay3& dt, const std::vector<std::array<int, 3>>& faces, std::vector<std::array<int, 4>>& body) {
  std::vector<std::array<int, 3>> keys;
  keys.reserve(faces.size());
  for (const auto& f : faces) keys.push_back(key_of(f[0], f[1], f[2]).v);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  const std::size_t T = dt.tets.size();
  // Which face of which tetrahedron is a surface face.
  std::vector<std::uint8_t> on_surface(T, 0);  // bit i: face opposite vertex i
  std::size_t found = 0;
  const VertexTets at(dt);
  for (const auto& k : keys)
    at.for_face(k[0], k[1], k[2], [&](int t, int i) {
      on_surface[uz(t)] |= static_cast<std::uint8_t>(1u << i);
      ++found;
    });
  // Every surface face is shared by two tetrahedra, or one on the convex hull.
  std::size_t expect = 0;
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i)
      if (on_surface[t] >> i & 1u) expect += dt.neighbors[t][uz(i)] < 0 ? 2 : 1;
  if (expect != 2 * faces.size() || found > 2 * faces.size()) return false;
  std::vector<int> region;
  const int regions = surface_regions(dt, [&](std::size_t t, int i) { return (on_surface[t] >> i & 1u) != 0; }, region);
  // Region adjacency through surface faces; the depth by breadth-first search from the exterior.
  std::vector<std::vector<int>> adj(uz(regions));
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i) {
      if (!(on_surface[t] >> i & 1u)) continue;
      const int m = dt.neighbors[t][uz(i)];
      const int other = m < 0 ? 0 : region[uz(m)];
      if (other == region[t]) return false;  // a surface with the same region on both sides
      adj[uz(region[t])].push_back(other);
      // (A face on the convex hull is met from its one tetrahedron only: the exterior's side too.
      // Without it a part whose surface is its whole convex hull left the exterior with no way in.)
      if (m < 0) adj[0].push_back(region[t]);
    }
  std::vector<int> depth(uz(regions), -1);
  depth[0] = 0;
  std::vector<int> bfs{0};
  for (std::size_t q = 0; q < bfs.size(); ++q)
    for (int o : adj[uz(bfs[q])]) {
      if (depth[uz(o)] < 0) {
        depth[uz(o)] = depth[uz(bfs[q])] + 1;
        bfs.push_back(o);
      } else if (std::abs(depth[uz(o)] - depth[uz(bfs[q])]) != 1) {
        return false;  // not a tree of nested regions
      }
    }
  for (int d : depth)
    if (d < 0) return false;
  body.clear();
  for (std::size_t t = 0; t < T; ++t)
    if (depth[uz(region[t])] % 2 == 1) body.push_back(dt.tets[t]);
  return true;
}

// The parts' surfaces made of Delaunay faces of all points where edge flips can: a surface face
// that is not one (the other points of the data are inside all of its empty spheres; seen on
// random samples of nested spheres, where a part's own surface keeps nearly coplanar triangles on
// the diagonals that the other part's points exclude) and the surface face across one of its
// edges are replaced by the two triangles on the quad's other diagonal, when fewer of those are
// not Delaunay faces (so every flip lowers their number) and that diagonal is no surface edge
// yet. Each flip keeps every surface a closed, oriented 2-manifold of the same genus through the
// same points (a tetrahedron added to or taken from one part's body); assemble_body() then checks
// the rest.
// Returns the number of flips (0: faces unchanged); at most `max_flips`, in at most 4 passes.
std::size_t flip_to_delaunay_faces(const Delaunay3& dt, std::vector<std::array<int, 3>>& faces, std::size_t max_flips) {
  const VertexTets at(dt);
  const auto is_delaunay = [&](int a, int b, int c) { return at.is_face(a, b, c); };
  // Directed surface edge (a, b) -> its face (an edge is a surface edge in either direction).
  const auto ekey = [](int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); };
  std::unordered_map<std::uint64_t, int> face_of_edge;
  face_of_edge.reserve(3 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) face_of_edge[ekey(faces[f][uz(k)], faces[f][uz((k + 1) % 3)])] = static_cast<int>(f);
  std::size_t flips = 0;
  for (int pass = 0, changed = 1; changed && pass < 4 && flips < max_flips; ++pass) {
    changed = 0;
    for (std::size_t f = 0; f < faces.size() && flips < max_flips; ++f) {
      if (is_delaunay(faces[f][0], faces[f][1], faces[f][2])) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = faces[f][uz(k)], b = faces[f][uz((k + 1) % 3)], c = faces[f][uz((k + 2) % 3)];
        const auto across = face_of_edge.find(ekey(b, a));
        if (across == face_of_edge.end()) continue;
        const std::size_t g = uz(across->second);
        const auto& tg = faces[g];
        int d = -1;
        for (int v : tg)
          if (v != a && v != b) d = v;
        // (a, b, c) and (b, a, d) -> (a, d, c) and (d, b, c): the quad a d b c, diagonal c d.
        if (d < 0 || d == c || face_of_edge.count(ekey(c, d)) || face_of_edge.count(ekey(d, c))) continue;
        // (Fewer faces that are not Delaunay after the flip: a strip of them goes a flip at a time.)
        const int before = 1 + !is_delaunay(tg[0], tg[1], tg[2]), after = !is_delaunay(a, d, c) + !is_delaunay(d, b, c);
        if (after >= before) continue;
        for (const std::size_t h : {f, g})
          for (int j = 0; j < 3; ++j) face_of_edge.erase(ekey(faces[h][uz(j)], faces[h][uz((j + 1) % 3)]));
        faces[f] = {a, d, c};
        faces[g] = {d, b, c};
        for (const std::size_t h : {f, g})
          for (int j = 0; j < 3; ++j) face_of_edge[ekey(faces[h][uz(j)], faces[h][uz((j + 1) % 3)])] = static_cast<int>(h);
        ++flips;
        changed = 1;
        break;
      }
    }
  }
  return flips;
}

// The free faces of a body of positively oriented tetrahedra, oriented out of it.
// (Sorted, not hashed: every face with its sorted ids, then the ones met once.)
TriMesh3 body_surface(const std::vector<std::array<int, 4>>& body) {
  struct Occurrence {
    std::array<int, 3> key, face;
  };
  std::vector<Occurrence> all;
  all.reserve(4 * body.size());
  for (const auto& t : body)
    for (const auto& f : kFaceOut) {
      const std::array<int, 3> face{{t[uz(f[0])], t[uz(f[1])], t[uz(f[2])]}};
      all.push_back({key_of(face[0], face[1], face[2]).v, face});
    }
  std::sort(all.begin(), all.end(), [](const Occurrence& a, const Occurrence& b) { return a.key < b.key; });
  TriMesh3 m;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i + 1;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    if (j - i == 1) m.triangles.push_back(all[i].face);
    i = j;
  }
  std::sort(m.triangles.begin(), m.triangles.end());
  return m;
}

// ---- the surfaces of a mesh -----------------------------------------------------------------------

// Components of the mesh (edge-connected through shared vertices: the surfaces are vertex-disjoint),
// their genus, roles and parents. Roles/parents: an outer surface has the body inside it; nesting by
// the region tree when known (several parts), else every surface is outer with no parent.
std::vector<Surface3> split_surfaces(const PointSet& pts, const TriMesh3& mesh) {
  UnionFind uf(pts.size());
  for (const auto& t : mesh.triangles) {
    uf.join(t[0], t[1]);
    uf.join(t[0], t[2]);
  }
  std::vector<int> best(pts.size(), -1);
  for (const auto& t : mesh.triangles)
    for (int v : t) {
      int& b = best[uz(uf.find(v))];
      if (b < 0 || lex_less3(pts[uz(v)], pts[uz(b)])) b = v;
    }
  std::vector<int> roots;
  for (std::size_t v = 0; v < pts.size(); ++v)
    if (best[v] >= 0 && uf.find(static_cast<int>(v)) == static_cast<int>(v)) roots.push_back(static_cast<int>(v));
  std::sort(roots.begin(), roots.end(), [&](int a, int b) { return lex_less3(pts[uz(best[uz(a)])], pts[uz(best[uz(b)])]); });
  std::vector<int> index_of(pts.size(), -1);
  for (std::size_t k = 0; k < roots.size(); ++k) index_of[uz(roots[k])] = static_cast<int>(k);
  std::vector<Surface3> s(roots.size());
  std::vector<long long> edges(roots.size(), 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) s[uz(index_of[uz(uf.find(mesh.triangles[f][0]))])].triangles.push_back(static_cast<int>(f));
  std::vector<char> used(pts.size(), 0);
  for (const auto& t : mesh.triangles)
    for (int v : t) used[uz(v)] = 1;
  for (std::size_t v = 0; v < pts.size(); ++v)
    if (used[v]) s[uz(index_of[uz(uf.find(static_cast<int>(v)))])].points.push_back(static_cast<int>(v));
  for (Surface3& x : s) {
    // Closed manifold: E = 3F/2, χ = V - E + F = V - F/2, genus = (2 - χ)/2.
    const long long F = static_cast<long long>(x.triangles.size()), V = static_cast<long long>(x.points.size());
    x.genus = static_cast<int>((2 - (V - F / 2)) / 2);
  }
  return s;
}

// Roles and parents (several parts): the regions of the tetrahedralization between the surfaces
// form a tree rooted at the exterior; a surface whose inner side is at odd depth bounds a solid
// (outer), at even depth a cavity (inner); its parent is the surface its outer side was entered by.
void nest_surfaces(const Delaunay3& dt, const TriMesh3& mesh, std::vector<Surface3>& s) {
  if (s.size() < 2) return;
  std::unordered_map<FaceKey, int, FaceHash> face_surface;
  for (std::size_t k = 0; k < s.size(); ++k)
    for (int f : s[k].triangles) {
      const auto& t = mesh.triangles[uz(f)];
      face_surface.emplace(key_of(t[0], t[1], t[2]), static_cast<int>(k));
    }
  const std::size_t T = dt.tets.size();
  const auto surf_of = [&](std::size_t t, int i) {
    const auto& v = dt.tets[t];
    const auto& f = kFaceOut[i];
    auto it = face_surface.find(key_of(v[uz(f[0])], v[uz(f[1])], v[uz(f[2])]));
    return it == face_surface.end() ? -1 : it->second;
  };
  // Which faces of each tetrahedron are surface faces (bit i: face i), one lookup per face on both
  // cores (the map is only read); the flood and the sides below read the bits. (Two lookups per
  // face in sequence had been 15 % of an auto run on two concentric spheres of 2·10^5 points.)
  std::vector<std::uint8_t> on_surface(T, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t)
      for (int i = 0; i < 4; ++i)
        if (surf_of(t, i) >= 0) on_surface[t] = static_cast<std::uint8_t>(on_surface[t] | 1u << i);
  });
  std::vector<int> region;
  const int regions = surface_regions(
      dt, [&](std::size_t t, int i) { return (on_surface[t] >> i & 1u) != 0; }, region);
  // Each surface separates two regions; BFS from the exterior orders them (outer side first).
  std::vector<std::array<int, 2>> sides(s.size(), {{-1, -1}});
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i) {
      if ((on_surface[t] >> i & 1u) == 0) continue;
      const int k = surf_of(t, i);
      const int m = dt.neighbors[t][uz(i)];
      const int a = region[t], b = m < 0 ? 0 : region[uz(m)];
      sides[uz(k)] = {{std::min(a, b), std::max(a, b)}};
    }
  std::vector<std::vector<std::pair<int, int>>> adj(uz(regions));  // (other region, surface)
  for (std::size_t k = 0; k < s.size(); ++k) {
    adj[uz(sides[k][0])].push_back({sides[k][1], static_cast<int>(k)});
    adj[uz(sides[k][1])].push_back({sides[k][0], static_cast<int>(k)});
  }
  std::vector<int> depth(uz(regions), -1), via(uz(regions), -1);  // via: the surface entered through
  depth[0] = 0;
  std::vector<int> bfs{0};
  for (std::size_t q = 0; q < bfs.size(); ++q) {
    const int r = bfs[q];
    for (const auto& [o, k] : adj[uz(r)]) {
      if (depth[uz(o)] >= 0) continue;
      depth[uz(o)] = depth[uz(r)] + 1;
      via[uz(o)] = k;
      bfs.push_back(o);
      // Surface k: outer side r, inner side o.
      s[uz(k)].role = depth[uz(o)] % 2 == 1 ? SurfaceRole::Outer : SurfaceRole::Inner;
      s[uz(k)].parent = via[uz(r)];
    }
  }
}

// Roles and parents (one part: one connected body): an outer surface encloses the body, an inner
// one faces into a cavity -- the exact sign of its enclosed volume; every inner surface's parent
// is the part's one outer surface.
void nest_in_body(const PointSet& pts, const TriMesh3& mesh, std::vector<Surface3>& s) {
  int outer = -1, n_outer = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    std::vector<int> tris;
    tris.reserve(s[k].triangles.size() * 3);
    for (int f : s[k].triangles) tris.insert(tris.end(), mesh.triangles[uz(f)].begin(), mesh.triangles[uz(f)].end());
    const bool out = signed_volume_sign(pts.coords.data(), tris.data(), s[k].triangles.size()) > 0;
    s[k].role = out ? SurfaceRole::Outer : SurfaceRole::Inner;
    if (out) {
      outer = static_cast<int>(k);
      ++n_outer;
    }
  }
  if (n_outer != 1) return;
  for (Surface3& x : s)
    if (x.role == SurfaceRole::Inner) x.parent = outer;
}

// Per-surface smallest gap to another surface's points (double, the report), over Delaunay edges.
void report_gaps(const PointSet& pts, const std::vector<std::array<int, 2>>& edges, const std::vector<int>& nn,
                 std::vector<Surface3>& s) {
  if (s.size() < 2) return;
  std::vector<int> of(pts.size(), -1);
  for (std::size_t k = 0; k < s.size(); ++k)
    for (int v : s[k].points) of[uz(v)] = static_cast<int>(k);
  for (const auto& e : edges) {
    const int a = of[uz(e[0])], b = of[uz(e[1])];
    if (a < 0 || b < 0 || a == b) continue;
    const double g = gap_ratio(pts, nn, e[0], e[1]);
    for (auto [x, y] : {std::pair<int, int>{a, b}, std::pair<int, int>{b, a}})
      if (g < s[uz(x)].gap_spacings || (g == s[uz(x)].gap_spacings && y < s[uz(x)].nearest_surface)) {
        s[uz(x)].gap_spacings = g;
        s[uz(x)].nearest_surface = y;
      }
  }
}

PointSet subset(const PointSet& pts, const std::vector<int>& ids) {
  PointSet s;
  s.dim = 3;
  s.coords.reserve(ids.size() * 3);
  for (int v : ids) s.coords.insert(s.coords.end(), pts[uz(v)], pts[uz(v)] + 3);
  return s;
}

// Sums of the engine counts of the parts (the stages and timings of the parts added up).
void add_counts(Mesh3Result& sum, const Mesh3Result& r) {
  sum.grown += r.grown;
  sum.grown_outside += r.grown_outside;
  sum.grown_crawled += r.grown_crawled;
  sum.filled += r.filled;
  sum.handle_added += r.handle_added;
  sum.handle_removed += r.handle_removed;
  sum.handle_changes.insert(sum.handle_changes.end(), r.handle_changes.begin(), r.handle_changes.end());
  sum.grow_cavities += r.grow_cavities;
  sum.grow_pocket_points += r.grow_pocket_points;
  sum.grow_pocket_filled += r.grow_pocket_filled;
  sum.cavities += r.cavities;
  sum.cavity_attempts += r.cavity_attempts;
  sum.carved += r.carved;
  sum.carve_undone += r.carve_undone;
  sum.carve_capped = sum.carve_capped || r.carve_capped;
  sum.removed_one_face += r.removed_one_face;
  sum.removed_two_face += r.removed_two_face;
  sum.refine_added += r.refine_added;
  sum.refine_removed += r.refine_removed;
  sum.refine_capped = sum.refine_capped || r.refine_capped;
  sum.non_delaunay_tets += r.non_delaunay_tets;
  sum.bridge_faces += r.bridge_faces;
  sum.bridge_area += r.bridge_area;
  sum.max_bridge_ratio = std::max(sum.max_bridge_ratio, r.max_bridge_ratio);
  sum.ms_grow += r.ms_grow;
  sum.ms_fill += r.ms_fill;
  sum.ms_constrict += r.ms_constrict;
  sum.ms_fallback += r.ms_fallback;
  sum.ms_refine += r.ms_refine;
  sum.ms_validate += r.ms_validate;
  sum.ms_delaunay += r.ms_delaunay;
  sum.ms_setup += r.ms_setup;
}

// Are the parts' bounding boxes pairwise disjoint (exact comparisons of coordinates)? Then their
// bodies, each inside its own convex hull, cannot meet.
bool boxes_apart(const PointSet& pts, const Parts& parts) {
  std::vector<std::array<double, 6>> box;
  for (const auto& ids : parts.points) {
    std::array<double, 6> b{{HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
    for (int v : ids)
      for (int c = 0; c < 3; ++c) {
        b[uz(c)] = std::min(b[uz(c)], pts[uz(v)][c]);
        b[uz(c + 3)] = std::max(b[uz(c + 3)], pts[uz(v)][c]);
      }
    box.push_back(b);
  }
  for (std::size_t a = 0; a < box.size(); ++a)
    for (std::size_t b = a + 1; b < box.size(); ++b) {
      bool apart = false;
      for (int c = 0; c < 3 && !apart; ++c)
        apart = box[a][uz(c + 3)] < box[b][uz(c)] || box[b][uz(c + 3)] < box[a][uz(c)];
      if (!apart) return false;
    }
  return true;
}

// Is every pair of parts strictly on the two sides of a plane (so their convex hulls, which hold
// their bodies, are disjoint)? Rotated parts whose bounding boxes overlap, as rotated flat-faced
// parts a few spacings apart are. Tried: the plane normal to the line between the two centroids
// and the coordinate planes. Decided in double with a bound on the rounding of the dot products
// (each |u.p - fl(u.p)| <= 4 eps sum |u_i p_i|): a gap above both sets' bounds separates them for
// sure; otherwise the answer is "no" (never a wrong "yes").
bool planes_apart(const PointSet& pts, const Parts& parts) {
  const std::size_t k = parts.points.size();
  std::vector<std::array<double, 3>> centroid(k, {0, 0, 0});
  for (std::size_t a = 0; a < k; ++a) {
    for (int v : parts.points[a])
      for (int c = 0; c < 3; ++c) centroid[a][uz(c)] += pts[uz(v)][c];
    for (int c = 0; c < 3; ++c) centroid[a][uz(c)] /= static_cast<double>(parts.points[a].size());
  }
  constexpr double kRound = 4 * std::numeric_limits<double>::epsilon();
  // The smallest and largest u.p over a part, and the largest rounding bound of those products.
  struct Extent {
    double lo = HUGE_VAL, hi = -HUGE_VAL, bound = 0;
  };
  const auto extent = [&](std::size_t a, const std::array<double, 3>& u) {
    Extent e;
    for (int v : parts.points[a]) {
      const double* p = pts[uz(v)];
      const double d = u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
      e.lo = std::min(e.lo, d);
      e.hi = std::max(e.hi, d);
      // (plus the absolute error of products in the subnormal range)
      e.bound = std::max(e.bound, kRound * (std::fabs(u[0] * p[0]) + std::fabs(u[1] * p[1]) + std::fabs(u[2] * p[2])) +
                                      4 * std::numeric_limits<double>::denorm_min());
    }
    return e;
  };
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) {
      const std::array<double, 3> d = {centroid[b][0] - centroid[a][0], centroid[b][1] - centroid[a][1],
                                       centroid[b][2] - centroid[a][2]};
      bool apart = false;
      for (const std::array<double, 3>& u : {d, std::array<double, 3>{1, 0, 0}, std::array<double, 3>{0, 1, 0},
                                             std::array<double, 3>{0, 0, 1}}) {
        if (!std::isfinite(u[0] + u[1] + u[2])) continue;
        const Extent ea = extent(a, u), eb = extent(b, u);
        const double margin = 2 * (ea.bound + eb.bound);
        if (eb.lo - ea.hi > margin || ea.lo - eb.hi > margin) {
          apart = true;
          break;
        }
      }
      if (!apart) return false;
    }
  return true;
}

// The body of the parts' own surfaces in the tetrahedralization of all points, when those
// surfaces cannot be assembled as they are (noisy nested parts: a point that noise moved off its
// shell leaves a "tent" of faces that are not Delaunay faces of all points). A tetrahedron of dt
// lies inside c of the parts' closed surfaces and is in the body when c is odd: a part's depth is
// the number of other parts whose own body holds its first point (exact orient3); a tetrahedron
// of one part's points lies inside the parts around that part, and inside that part too when it
// is one of the part's own body tetrahedra (a Delaunay tetrahedron of all points is one of the
// part's points alone); a tetrahedron joining parts lies in the gap between them, inside the
// parts around the deepest of them. The tetrahedra keep dt's orientation.
std::vector<char> parts_body(const PointSet& pts, const Delaunay3& dt, const Parts& parts,
                             const std::vector<Mesh3Result>& res) {
  const std::size_t P = parts.points.size();
  std::vector<std::vector<std::array<int, 4>>> own(P);
  for (std::size_t k = 0; k < P; ++k)
    for (const auto& t : res[k].tets) {
      const auto& ids = parts.points[k];
      own[k].push_back({ids[uz(t[0])], ids[uz(t[1])], ids[uz(t[2])], ids[uz(t[3])]});
    }
  std::vector<int> depth(P, 0);
  for (std::size_t q = 0; q < P; ++q) {
    const double* x = pts[uz(parts.points[q].front())];
    for (std::size_t p = 0; p < P; ++p) {
      if (p == q) continue;
      for (const auto& t : own[p]) {
        const double* v[4] = {pts[uz(t[0])], pts[uz(t[1])], pts[uz(t[2])], pts[uz(t[3])]};
        if (orient3(x, v[1], v[2], v[3]) >= 0 && orient3(v[0], x, v[2], v[3]) >= 0 &&
            orient3(v[0], v[1], x, v[3]) >= 0 && orient3(v[0], v[1], v[2], x) >= 0) {
          ++depth[q];
          break;
        }
      }
    }
  }
  std::vector<std::array<int, 4>> inside;
  for (auto& o : own)
    for (auto t : o) {
      std::sort(t.begin(), t.end());
      inside.push_back(t);
    }
  std::sort(inside.begin(), inside.end());
  std::vector<char> body(dt.tets.size(), 0);
  for (std::size_t i = 0; i < dt.tets.size(); ++i) {
    const auto& t = dt.tets[i];
    const int k0 = parts.part_of[uz(t[0])];
    bool one = true;
    int c = 0;
    for (int v : t) {
      const int k = parts.part_of[uz(v)];
      one = one && k == k0;
      c = std::max(c, depth[uz(k)]);
    }
    if (one) {
      std::array<int, 4> key = t;
      std::sort(key.begin(), key.end());
      c = depth[uz(k0)] + (std::binary_search(inside.begin(), inside.end(), key) ? 1 : 0);
    }
    body[i] = static_cast<char>(c % 2 == 1);
  }
  return body;
}

// Repairs the points where the body of parts_body() is not a surface: a point not on it (buried
// in the body, or in a region outside it) or whose free faces do not form one disk. Toggles one
// tetrahedron of dt at the point, else two that share a face, else (a point off the surface) a
// channel of up to kChannel tetrahedra in the point's state from one at the point to one with a
// free face. A choice is valid when every vertex of its tetrahedra (the only links that change)
// ends on the surface with a link that is one cycle and the surface keeps its Euler
// characteristic (two faces more for each point brought to it: no handle, no extra surface);
// among the valid ones the one that adds the least area (double arithmetic, a choice only),
// ties by the smaller sorted vertex ids. Points in ascending order (canonical ids: the same for
// any file order). The points left then go to a local search (local_search). in_body: per
// tetrahedron of dt, updated; run() adds the toggles to changed and is false when a defect is
// left (in_body is then not a body to use) or the work bound was reached.
// Work bound: the tetrahedra read by the link and surface tests, at most kWorkPerIncidence per
// tetrahedron-vertex incidence plus kWorkFloor (as the carve's, carve3.cpp). Points along curves
// in space have thousands of tetrahedra at every point: 1 500 points on a circle and 1 500 on its
// axis (two parts) ran here for more than 10 minutes without it.
class SurfaceRepair {
  static constexpr int kChannel = 4;
  static constexpr std::size_t kSearchSteps = 16;
  static constexpr std::size_t kWorkPerIncidence = 64, kWorkFloor = std::size_t(1) << 20;

 public:
  SurfaceRepair(const PointSet& pts, const Delaunay3& dt, std::vector<char>& in_body, const std::vector<int>* part_of)
      : pts_(pts), dt_(dt), in_(in_body), part_of_(part_of), at_(dt) {
    // Face ids through the neighbour relation (a face and its mirror in the neighbour share one).
    const std::size_t T = dt.tets.size();
    face_id_.assign(T, {{-1, -1, -1, -1}});
    int faces = 0;
    for (std::size_t t = 0; t < T; ++t)
      for (int i = 0; i < 4; ++i) {
        if (face_id_[t][uz(i)] >= 0) continue;
        face_id_[t][uz(i)] = faces;
        const int m = dt.neighbors[t][uz(i)];
        if (m >= 0)
          for (int j = 0; j < 4; ++j)
            if (dt.neighbors[uz(m)][uz(j)] == static_cast<int>(t)) face_id_[uz(m)][uz(j)] = faces;
        ++faces;
      }
    work_limit_ = kWorkPerIncidence * 4 * T + kWorkFloor;
    count_.assign(uz(faces), 0);
    for (std::size_t t = 0; t < T; ++t)
      if (in_[t])
        for (int i = 0; i < 4; ++i) ++count_[uz(face_id_[t][uz(i)])];
    for (const int c : count_) nfree_ += c == 1 ? 1 : 0;
  }

  bool capped() const { return capped_; }
  // The work done (on_surface, vertex_ok and the local search's tries), and work done before by
  // another repair of the same body, which counts against this one's bound.
  std::size_t work() const { return work_; }
  void start_after(std::size_t work) { work_ = work; }
  // Past the work bound (class comment): run() gives up, and says so.
  bool over_budget() {
    capped_ = capped_ || work_ > work_limit_;
    return capped_;
  }
  // target_faces: the face count of the parts' own surfaces (the same Euler characteristic).
  bool run(std::size_t target_faces, std::size_t& changed) {
    std::vector<int> left;  // points the first pass could not repair
    for (std::size_t v = 0; v < pts_.size(); ++v) {
      if (over_budget()) return false;
      const int vi = static_cast<int>(v);
      if (vertex_ok(vi)) continue;
      std::vector<int> best;
      double best_gain = HUGE_VAL;
      std::vector<std::array<int, 4>> best_key;
      const auto consider = [&](const std::vector<int>& set) {
        // The surface's Euler characteristic V - F/2 (closed, edge-manifold) must not change: the
        // points brought to the surface, two faces each.
        std::vector<int> verts;
        for (int t : set)
          for (int x : dt_.tets[uz(t)]) verts.push_back(x);
        std::sort(verts.begin(), verts.end());
        verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
        long long off = 0;
        for (int x : verts) off += on_surface(x) ? 0 : 1;
        const double before = area_of(set);
        const long long f0 = free_faces_of(set);
        for (int t : set) toggle(t);
        bool ok = free_faces_of(set) - f0 == 2 * off;
        for (int x : verts) ok = ok && vertex_ok(x);
        const double gain = area_of(set) - before;
        for (int t : set) toggle(t);
        if (!ok) return;
        std::vector<std::array<int, 4>> key;
        for (int t : set) {
          std::array<int, 4> k = dt_.tets[uz(t)];
          std::sort(k.begin(), k.end());
          key.push_back(k);
        }
        std::sort(key.begin(), key.end());
        if (best.empty() || gain < best_gain || (gain == best_gain && key < best_key)) {
          best = set;
          best_gain = gain;
          best_key = key;
        }
      };
      for (int t : at_.of(vi)) consider({t});
      // Two that share a face (a pair of the point's own tetrahedra once).
      if (best.empty())
        for (int t : at_.of(vi))
          for (int m : dt_.neighbors[uz(t)])
            if (m >= 0 && in_[uz(m)] == in_[uz(t)] && (m > t || !contains(at_.of(vi), m))) consider({t, m});
      // Deeper: a channel of tetrahedra in the point's state, from one at the point to one with
      // a free face (breadth first through their faces, at most kChannel long).
      if (best.empty() && !on_surface(static_cast<int>(v))) {
        bool buried = false;
        for (int t : at_.of(vi)) buried = buried || in_[uz(t)];
        std::unordered_map<int, int> parent;  // tetrahedron -> the one it was reached from (-1: at v)
        std::vector<int> layer;
        for (int t : at_.of(vi))
          if ((in_[uz(t)] != 0) == buried) {
            parent.emplace(t, -1);
            layer.push_back(t);
          }
        for (int depth = 1; depth <= kChannel && best.empty() && !layer.empty(); ++depth) {
          std::vector<int> next;
          for (int t : layer)
            for (int m : dt_.neighbors[uz(t)]) {
              if (m < 0 || (in_[uz(m)] != 0) != buried || parent.count(m)) continue;
              parent.emplace(m, t);
              next.push_back(m);
            }
          std::sort(next.begin(), next.end());
          for (int m : next) {
            bool touches = false;
            for (int i = 0; i < 4; ++i) touches = touches || free_face(m, i);
            if (!touches) continue;
            std::vector<int> path;
            for (int x = m; x >= 0; x = parent[x]) path.push_back(x);
            consider(path);
          }
          layer = std::move(next);
        }
      }
      if (best.empty()) {
        left.push_back(static_cast<int>(v));
        continue;
      }
      for (int t : best) toggle(t);
      changed += best.size();
    }
    return (left.empty() || local_search(left, target_faces, changed)) && nfree_ == target_faces;
  }

 private:
  static bool contains(VertexTets::Range r, int x) { return std::find(r.begin(), r.end(), x) != r.end(); }
  int face(int t, int i) const { return face_id_[uz(t)][uz(i)]; }
  void toggle(int t) {
    const int d = in_[uz(t)] ? -1 : 1;
    in_[uz(t)] = static_cast<char>(!in_[uz(t)]);
    for (int i = 0; i < 4; ++i) {
      int& c = count_[uz(face(t, i))];
      nfree_ -= c == 1 ? 1 : 0;
      c += d;
      nfree_ += c == 1 ? 1 : 0;
    }
  }
  bool free_face(int t, int i) const { return count_[uz(face(t, i))] == 1; }
  bool on_surface(int x) {
    work_ += at_.of(x).size();
    for (int t : at_.of(x))
      for (int i = 0; i < 4; ++i)
        if (dt_.tets[uz(t)][uz(i)] != x && free_face(t, i)) return true;
    return false;
  }
  // The free faces at x: their edges opposite x form one cycle (each free face once: from the
  // tetrahedron in the body; a face on the convex hull has no other side).
  bool vertex_ok(int x) {
    work_ += at_.of(x).size();
    std::vector<std::array<int, 2>> link;
    for (int t : at_.of(x)) {
      if (!in_[uz(t)]) continue;
      for (int i = 0; i < 4; ++i) {
        const auto& v = dt_.tets[uz(t)];
        if (v[uz(i)] == x || !free_face(t, i)) continue;
        std::array<int, 2> e{};
        int k = 0;
        for (int l = 0; l < 3; ++l) {
          const int y = v[uz(kFaceOut[i][l])];
          if (y == x) continue;
          if (part_of_ && (*part_of_)[uz(y)] != (*part_of_)[uz(x)]) return false;  // a face across two parts
          e[uz(k++)] = y;
        }
        link.push_back(e);
      }
    }
    return detail::link_is_one_cycle(link);
  }
  // The points the first pass left: single toggles of a tetrahedron at a bad vertex (one not on
  // the surface or whose link is not one cycle), each time the one that leaves the smallest
  // defect 4 * (bad vertices) + |F - target_faces| (ties: the smaller sorted vertex ids), also
  // when that is no smaller (a point two layers deep needs a step that first pinches a
  // neighbour), under a tabu list (a toggled tetrahedron is not toggled again); at most
  // kSearchSteps per point left. The fill's local search in the engine (carve3.cpp) works alike.
  bool local_search(const std::vector<int>& left, std::size_t target_faces, std::size_t& changed) {
    std::set<int> bad(left.begin(), left.end());
    std::set<int> tabu;
    const auto defect = [&] {
      const long long df = static_cast<long long>(nfree_) - static_cast<long long>(target_faces);
      return 4 * static_cast<long long>(bad.size()) + (df < 0 ? -df : df);
    };
    const auto update = [&](int t) {  // the bad set after t was toggled
      for (int x : dt_.tets[uz(t)]) {
        if (vertex_ok(x))
          bad.erase(x);
        else
          bad.insert(x);
      }
    };
    std::size_t steps = 0;
    const std::size_t max_steps = kSearchSteps * left.size();
    while (defect() > 0 && steps++ < max_steps) {
      if (over_budget()) return false;
      long long best_d = 0;
      int best_t = -1;
      std::array<int, 4> best_key{};
      const std::vector<int> now(bad.begin(), bad.end());
      for (int v : now)
        for (int t : at_.of(v)) {
          if (tabu.count(t)) continue;
          work_ += bad.size();
          const std::set<int> saved = bad;
          toggle(t);
          update(t);
          const long long d = defect();
          toggle(t);
          bad = saved;
          std::array<int, 4> key = dt_.tets[uz(t)];
          std::sort(key.begin(), key.end());
          if (best_t < 0 || d < best_d || (d == best_d && key < best_key)) {
            best_d = d;
            best_t = t;
            best_key = key;
          }
        }
      if (best_t < 0) return false;
      toggle(best_t);
      update(best_t);
      tabu.insert(best_t);
      ++changed;
    }
    return defect() == 0;
  }
  // The free faces among the faces of these tetrahedra (each face once).
  long long free_faces_of(const std::vector<int>& set) {
    std::vector<int> fs;
    for (int t : set)
      for (int i = 0; i < 4; ++i)
        if (free_face(t, i)) fs.push_back(face(t, i));
    std::sort(fs.begin(), fs.end());
    return std::unique(fs.begin(), fs.end()) - fs.begin();
  }
  // The area of the free faces of these tetrahedra.
  double area_of(const std::vector<int>& set) {
    double a = 0;
    for (int t : set)
      for (int i = 0; i < 4; ++i) {
        if (!free_face(t, i)) continue;
        const auto& v = dt_.tets[uz(t)];
        a += triangle_area3(pts_[uz(v[uz(kFaceOut[i][0])])], pts_[uz(v[uz(kFaceOut[i][1])])],
                            pts_[uz(v[uz(kFaceOut[i][2])])]);
      }
    return a;
  }

  const PointSet& pts_;
  const Delaunay3& dt_;
  std::vector<char>& in_;
  const std::vector<int>* part_of_;  // when given, a surface face joins the points of one part only
  const VertexTets at_;
  std::vector<std::array<int, 4>> face_id_;  // per tetrahedron, the id of the face opposite vertex i
  std::vector<int> count_;                   // per face id, its tetrahedra in the body
  std::size_t nfree_ = 0;                    // faces with one body tetrahedron
  std::size_t work_ = 0, work_limit_ = 0;    // the work bound (class comment)
  bool capped_ = false;                       // run() gave up at the bound
};

// Several parts: one engine run each; their body from the tetrahedralization of all points when
// every part's surface is made of its Delaunay faces, else (noisy or random samples: a face of one
// part's tetrahedralization need not be one of all points) the union of the parts' own bodies when
// their bounding boxes are apart (*separate = true: no part inside another). False (nothing
// usable) when a part cannot have a surface of its own or the parts do not fit.
bool several_parts(const PointSet& pts, const Delaunay3& dt, const Parts& parts, const Constrict3Options& o,
                   Surfaces3Result& r, Status& err, bool* separate) {
  *separate = false;
  std::vector<Mesh3Result> res(parts.points.size());
  for (std::size_t k = 0; k < parts.points.size(); ++k) {
    if (parts.points[k].size() < 4) {
      r.decision = SurfacesDecision::SmallPart;
      return false;
    }
    const PointSet sub = subset(pts, parts.points[k]);
    const Status s = reconstruct3(sub, o, res[k]);
    if (s.code() == StatusCode::Coplanar || s.code() == StatusCode::TooFewPoints || (s.is_ok() && !res[k].complete)) {
      r.decision = SurfacesDecision::SmallPart;
      return false;
    }
    if (!s) {
      err = s;
      return false;
    }
  }
  std::vector<std::array<int, 3>> faces;
  for (std::size_t k = 0; k < res.size(); ++k)
    for (const auto& t : res[k].mesh.triangles) {
      const auto& ids = parts.points[k];
      faces.push_back({ids[uz(t[0])], ids[uz(t[1])], ids[uz(t[2])]});
    }
  const auto t0 = Clock::now();
  std::vector<std::array<int, 4>> body;
  bool assembled = assemble_body(dt, faces, body);
  // Parts inside others need the common tetrahedralization: a few faces that are not Delaunay
  // faces of all points are flipped where they can be (parts apart keep their own bodies below).
  if (!assembled && !boxes_apart(pts, parts) && flip_to_delaunay_faces(dt, faces, faces.size() / 64 + 16) > 0)
    assembled = assemble_body(dt, faces, body);
  // Still not: the body that the parts' surfaces put in the common tetrahedralization, with the
  // points it buries brought to its surface by dimples; taken when that is a valid set of surfaces.
  if (!assembled && !boxes_apart(pts, parts)) {
    std::vector<char> in_body = parts_body(pts, dt, parts, res);
    std::size_t freed = 0;
    // run(): every point on the surface with a disk link (a closed 2-manifold through all points,
    // oriented out of the body) and the parts' face count; kept with as many surfaces as parts
    // (then the same Euler characteristic: the parts' topology). validate_surfaces3() checks all.
    // First with every surface face inside one part (each point on its own part's surface); where
    // that cannot be had, with faces across parts too (linked grid tori: a valid pair of tori
    // with one point on the other's surface, where the fallback makes one surface).
    // Both tries share one work bound.
    const std::vector<char> start = in_body;
    std::size_t spent = 0;
    for (const std::vector<int>* own : {&parts.part_of, static_cast<const std::vector<int>*>(nullptr)}) {
      if (!own) in_body = start;
      freed = 0;
      SurfaceRepair repair(pts, dt, in_body, own);
      repair.start_after(spent);
      const bool repaired = repair.run(faces.size(), freed);
      spent = repair.work();
      r.repair_capped = repair.capped();
      if (repair.capped()) break;
      if (!repaired) continue;
      body.clear();
      for (std::size_t t = 0; t < dt.tets.size(); ++t)
        if (in_body[t]) body.push_back(dt.tets[t]);
      const TriMesh3 surface = body_surface(body);
      UnionFind uf(pts.size());
      for (const auto& f : surface.triangles) {
        uf.join(f[0], f[1]);
        uf.join(f[0], f[2]);
      }
      std::size_t components = 0;
      for (std::size_t v = 0; v < pts.size(); ++v) components += uf.find(static_cast<int>(v)) == static_cast<int>(v);
      assembled = components == parts.points.size();
      if (assembled) {
        r.repaired_tetrahedra = freed;
        break;
      }
    }
  }
  if (!assembled) {
    if (!boxes_apart(pts, parts) && !planes_apart(pts, parts)) {
      r.decision = SurfacesDecision::NotDelaunay;
      return false;
    }
    body.clear();
    for (std::size_t k = 0; k < res.size(); ++k)
      for (const auto& t : res[k].tets) {
        const auto& ids = parts.points[k];
        body.push_back({ids[uz(t[0])], ids[uz(t[1])], ids[uz(t[2])], ids[uz(t[3])]});
      }
    *separate = true;
  }
  r.decision = SurfacesDecision::Parts;
  Mesh3Result& m = r.mesh;
  m = Mesh3Result{};
  m.method = res[0].method;
  m.complete = true;
  m.delaunay_tets = dt.tets.size();
  for (const Mesh3Result& x : res) add_counts(m, x);
  m.tets = std::move(body);
  std::sort(m.tets.begin(), m.tets.end());
  m.mesh = body_surface(m.tets);
  m.volume = mesh_volume(pts, m.mesh);  // (exact where the double sum cancels: finish_surfaces)
  m.surface_area = mesh_area(pts, m.mesh);
  m.validated = true;  // every part was validated by reconstruct3(); the whole below
  r.ms_assemble = ms_since(t0);
  return true;
}

// Engine / work ids -> input ids (order[k] = the input id of work point k).
void to_input_ids(const std::vector<int>& order, Surfaces3Result& r) {
  const auto map = [&](int& v) { v = order[uz(v)]; };
  for (auto& t : r.mesh.mesh.triangles) std::for_each(t.begin(), t.end(), map);
  for (auto& t : r.mesh.tets) std::for_each(t.begin(), t.end(), map);
  for (auto* list : {&r.mesh.stuck_points, &r.mesh.unplaced_points}) {
    std::for_each(list->begin(), list->end(), map);
    std::sort(list->begin(), list->end());
  }
  for (Surface3& s : r.surfaces) {
    std::for_each(s.points.begin(), s.points.end(), map);
    std::sort(s.points.begin(), s.points.end());
  }
}

// The total genus, then the exact validation of the surfaces and the body.
Status finish_surfaces(const PointSet& points, const Surfaces3Options& o, Surfaces3Result& r) {
  r.genus = 0;
  for (const Surface3& s : r.surfaces) r.genus += s.genus;
  r.mesh.genus = r.genus;
  r.mesh.surfaces = static_cast<int>(r.surfaces.size());
  if (o.validate && r.mesh.complete) {
    const auto t0 = Clock::now();
    MeshCheck mc;
    const Status vs = validate_surfaces3(points, r.mesh.mesh, r.mesh.tets, o.surface.validate_self_intersections, &mc);
    if (!vs) return {StatusCode::Internal, "reconstruct_surfaces3 produced invalid surfaces: " + vs.message()};
    if (mc.volume_exact) r.mesh.volume = mc.volume;  // (the double sum cancelled: check_outward)
    r.validated = true;
    r.ms_validate = ms_since(t0);
  }
  return Status::ok();
}

}  // namespace

bool topology_from_name(const std::string& name, Topology3& out) noexcept {
  if (name == "single") out = Topology3::Single;
  else if (name == "auto") out = Topology3::Auto;
  else return false;
  return true;
}
const char* to_string(Topology3 t) noexcept { return t == Topology3::Single ? "single" : "auto"; }
const char* to_string(SurfaceRole r) noexcept { return r == SurfaceRole::Outer ? "outer" : "inner"; }
const char* to_string(SurfacesDecision d) noexcept {
  switch (d) {
    case SurfacesDecision::OnePart: return "one-part";
    case SurfacesDecision::SmallPart: return "small-part";
    case SurfacesDecision::NotDelaunay: return "not-delaunay";
    case SurfacesDecision::Parts: return "parts";
  }
  return "?";
}

Status reconstruct_surfaces3(const PointSet& points, const Surfaces3Options& o, Surfaces3Result& r) {
  r = Surfaces3Result{};
  r.topology = o.topology;
  r.gap_threshold = o.topology_gap;
  if (points.dim != 3) return {StatusCode::InvalidArgument, "reconstruct_surfaces3 needs 3D points"};
  if (!(o.topology_gap >= 0) || !std::isfinite(o.topology_gap))
    return {StatusCode::InvalidArgument, "topology gap must be a finite number >= 0, not " + std::to_string(o.topology_gap)};
  if (Status s = detail::check_points_deferred(points); !s) return s;
  Constrict3Options eo = o.surface;
  eo.handles = o.topology == Topology3::Auto && o.handles;
  eo.validate = o.validate;
  if (o.topology == Topology3::Single) {
    if (Status s = reconstruct3(points, eo, r.mesh); !s) return s;
    r.surfaces = split_surfaces(points, r.mesh.mesh);
    return finish_surfaces(points, o, r);
  }
  // Auto works on the points in the engine's canonical order (so that one part shares the
  // tetrahedralization with the engine, and the parts do not depend on the file order); the
  // result is mapped back to input ids at the end.
  const std::vector<int> order = detail::canonical_order(points);
  const PointSet work = detail::permuted(points, order);
  if (detail::has_adjacent_duplicate(work)) return check_points(points);
  const auto t0 = Clock::now();
  Delaunay3 dt;
  if (Status s = build_delaunay3(work, dt); !s) return s;
  detail::order_large_tets(dt);  // (as the engine orders its own: the same surface on one part)
  const std::vector<int> nn = spacing_neighbours(work, dt);
  Parts fine;
  Parts parts = find_parts(work, dt, nn, o.topology_gap, kNarrowGap * o.topology_gap, o.min_part_points, r.small_parts_merged, fine);
  parts = split_by_labels(work, dt, nn, std::move(parts), fine, o.min_part_points, r.parts_split_by_labels);
  parts = join_patches(work, dt, nn, std::move(parts), o.topology_gap, r.patches_joined);
  r.parts = parts.points.size();
  for (const auto& p : parts.points) r.part_sizes.push_back(p.size());
  r.min_gap_spacings = parts.min_gap;
  r.ms_infer = ms_since(t0);
  bool done = false, separate = false;
  if (parts.points.size() > 1) {
    Status err = Status::ok();
    done = several_parts(work, dt, parts, eo, r, err, &separate);
    if (!err) return err;
  }
  if (done) {
    r.surfaces = split_surfaces(work, r.mesh.mesh);
    if (separate) nest_in_body(work, r.mesh.mesh, r.surfaces);  // (all outer: no part inside another)
    else nest_surfaces(dt, r.mesh.mesh, r.surfaces);
  } else {
    std::vector<int> part_of;
    if (parts.points.size() > 1) part_of = parts.part_of;
    if (Status s = detail::reconstruct3_sharing(work, eo, std::move(dt), r.mesh, std::move(part_of)); !s) return s;
    r.surfaces = split_surfaces(work, r.mesh.mesh);
    nest_in_body(work, r.mesh.mesh, r.surfaces);
  }
  report_gaps(work, parts.long_edges, nn, r.surfaces);
  to_input_ids(order, r);
  return finish_surfaces(points, o, r);
}

Status validate_surfaces3(const PointSet& points, const TriMesh3& mesh, const std::vector<std::array<int, 4>>& body,
                          bool self_intersections, MeshCheck* details) {
  MeshCheckOptions mo;
  mo.any_topology = true;
  mo.self_intersections = self_intersections;
  MeshCheck own;
  MeshCheck& mc = details ? *details : own;
  // The two checks side by side (each parallel inside); the surface's verdict first, as before.
  Status surface_status = Status::ok(), body_status = Status::ok();
  tbb::parallel_invoke([&] { surface_status = validate_mesh3(points, mesh, &mc, mo); },
                       [&] { body_status = validate_body3(points, mesh, body); });
  return !surface_status ? surface_status : body_status;
}

}  // namespace constrict
