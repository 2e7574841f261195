// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "parts" of reconstruct_surfaces3() (detail/surfaces3.hpp; docs/topology.md §"3D", "Parts
// that nearly touch", "Decimated meshes"): the parts are the components of the Delaunay edges
// shorter than T local spacings (the exact gap rule); between 3/4 of T and T the engine's
// circumball labels decide whether two pieces of a part are one object or two that nearly touch;
// a small dense patch of a surface joins the part whose surface it lies on.
//
// Exactness contract: the nearest neighbours (compare_distance3) and the gap rule (compare_gap3)
// are exact predicates; the rest is combinatorics over the Delaunay tetrahedralization. Doubles
// are computed for the report (gap ratios), and the split of parts that nearly touch reads the
// engine's circumball labels (doubles, as the engine's growth and handle stage read them; the same
// for the same points in any order). Parts are ordered by their lexicographically smallest point,
// so they do not depend on the file order.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "constrict/predicates.hpp"
#include "constrict/detail/share3.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/bucket_sort.hpp"
#include "core/detail/edge_key.hpp"
#include "core/detail/semi_static.hpp"
#include "core/detail/union_find.hpp"
#include "topology/detail/surfaces3.hpp"

namespace constrict::detail::surfaces3 {
namespace {

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

}  // namespace

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

// |pq| / rms(nn(p), nn(q)) in double (the report).
double gap_ratio(const PointSet& pts, const std::vector<int>& nn, int p, int q) {
  const double s = 0.5 * (len2(pts[uz(p)], pts[uz(nn[uz(p)])]) + len2(pts[uz(q)], pts[uz(nn[uz(q)])]));
  return std::sqrt(len2(pts[uz(p)], pts[uz(q)]) / s);
}

namespace {

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

}  // namespace

// Parts: components of the Delaunay edges shorter than gap local spacings, then settle_parts().
// And in the same pass over the edges the parts of the narrower rule (kNarrowGap · gap; split_by_labels).
Parts find_parts(const PointSet& pts, const Delaunay3& dt, const std::vector<int>& nn, double gap, std::size_t min_points,
                 std::size_t& merged, Parts& fine) {
  const double narrow = kNarrowGap * gap;
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

namespace {

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

}  // namespace

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

namespace {

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

}  // namespace

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

}  // namespace constrict::detail::surfaces3
