// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the Delaunay export plus a cache-friendly "local" copy of the triangulation, for the
// per-face loops of delaunay_gamma2/3 and the 2D engine (defined in src/cgal/delaunay.cpp, behind
// the CGAL fence; this header itself is plain data and includes no CGAL).
#pragma once
#include <array>
#include <vector>

#include "constrict/delaunay.hpp"
#include "core/detail/big_vector.hpp"

namespace constrict::detail {

/// A convex hull facet (3D): face i of finite tet t; across its edge k (the edge opposite the
/// k-th of its vertices in CGAL's infinite cell) the adjacent hull facet is face adj_i[k] of tet
/// adj_t[k], whose vertex off that edge is the local vertex far[k].
struct HullFace {
  int t, i;
  int adj_t[3], adj_i[3], far[3];
};

/// Vertices renumbered in CGAL's insertion order (its spatial sort, so neighbouring simplices
/// have nearby vertex numbers). Local vertex k has coordinates coords[D*k .. D*k+D-1] (the same
/// doubles as the input) and input index id[k]; simplices[t] are the local ids of simplex t of
/// the exported Delaunay2/3 (same order, same vertex positions).
template <int D>
struct LocalMesh {
  BigArray<double> coords;
  BigArray<int> id;
  BigArray<std::array<int, D + 1>> simplices;
  /// opposite[t][i]: local id of the vertex of the neighbour across face i that is not on that
  /// face (-1 on the hull); mirror[t] >> (2 i) & 3: index of t in that neighbour. Filled from
  /// the triangulation while its neighbour cells are being read anyway, so that the per-face
  /// loops never load a neighbour simplex (random memory access) themselves.
  BigArray<std::array<int, D + 1>> opposite;
  BigArray<unsigned char> mirror;
  /// owned[t] bit i: face i of t is numbered from t (hull face, or t < its neighbour).
  BigArray<unsigned char> owned;
  /// 3D only: the hull facets, in CGAL's infinite-cell order.
  std::vector<HullFace> hull;
};

/// Whether build_delaunay3 (without a local mesh) can give CGAL's cells back while it exports
/// them: CGAL's cell layout is the one it writes the export records into (src/cgal/delaunay.cpp).
bool released_export3_available();

/// From this many tetrahedra on (about 300 000 points), build_delaunay3 gives CGAL's cells back
/// while it exports them, so that its peak is CGAL's triangulation alone. Below, the plain export
/// is faster: the engine's next arrays are small enough for the heap to take them from the freed
/// triangulation's pages, while given-back pages are faulted in again (igea, 134 000 points:
/// 6-10 % more time in all; at 10^6 points the time is the same).
inline constexpr std::size_t kReleasedExportFromTets = std::size_t{1} << 21;

/// build_delaunay2/3 that also fills @p local (may be null). Same triangulation, same order.
/// 3D without a local mesh: the export gives the cells back from @p release_from tetrahedra on.
Status build_delaunay2_local(const PointSet& points, Delaunay2& out, LocalMesh<2>* local);
Status build_delaunay3_local(const PointSet& points, Delaunay3& out, LocalMesh<3>* local,
                             std::size_t release_from = kReleasedExportFromTets);

/// The 2D Delaunay triangulation in *ranked* vertex ids: vertex k is the k-th point of CGAL's
/// insertion order (its spatial sort), ranked.coords holds its coordinates (the input doubles)
/// and id[k] its input index. Same triangles, same order and same neighbours as build_delaunay2,
/// only relabelled, so that loops over triangles and along a curve touch nearby memory.
/// From 2^17 points on, an input that is not curve-like is triangulated in two halves on both cores
/// and joined (build_delaunay2_split): the same triangles wherever the Delaunay triangulation is
/// unique, in another order and with other ranks (L's points first, each half in its own spatial
/// order).
Status build_delaunay2_ranked(const PointSet& points, Delaunay2& out, PointSet& ranked, std::vector<int>& id);

/// The two-halves construction of build_delaunay2_ranked (src/cgal/delaunay.cpp explains it).
/// False, with nothing to use in the outputs, where the sequential construction must run: a half
/// without area, a join that fails its check, or (with @p sample_first) a sample of the points
/// whose join would leave more than a small share of them to the sequential part (curves). True
/// with @p status Duplicate when points coincide, else true with @p status ok and the result.
bool build_delaunay2_split(const PointSet& points, Delaunay2& out, PointSet& ranked, std::vector<int>& id,
                           Status& status, bool sample_first);

}  // namespace constrict::detail
