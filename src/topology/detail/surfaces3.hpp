// SPDX-License-Identifier: GPL-3.0-or-later
// The stages of reconstruct_surfaces3() (the 3D ladder of topology.hpp; docs/topology.md §"3D"),
// each in its own file over plain index arrays of the Delaunay tetrahedralization of all points:
//   parts3.cpp      the parts: the exact gap rule on the Delaunay edges, parts that nearly touch
//                   (the engine's labels), patches of one surface;
//   assemble3.cpp   the body of several parts' surfaces in the tetrahedralization of all points,
//                   and the surfaces' nesting (roles, parents, gaps);
//   repair3.cpp     that body where the parts' surfaces are not Delaunay faces of all points
//                   (noisy nested parts), repaired point by point;
//   surfaces3.cpp   the ladder itself: one part -> reconstruct3(); several -> one run each, then
//                   their body, else one part; then the exact validation.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/topology.hpp"

namespace constrict::detail::surfaces3 {

inline std::size_t uz(int i) { return static_cast<std::size_t>(i); }

inline bool lex_less3(const double* p, const double* q) { return std::lexicographical_compare(p, p + 3, q, q + 3); }

// |ab|² summed coordinate by coordinate, as compare_gap3 sums it (the same double).
inline double len2(const double* a, const double* b) {
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

// ---- parts3.cpp ------------------------------------------------------------------------------------

struct Parts {
  std::vector<int> part_of;              // per point
  std::vector<std::vector<int>> points;  // per part, ascending ids
  double min_gap = std::numeric_limits<double>::infinity();
  std::vector<std::array<int, 2>> long_edges;  // the Delaunay edges the gap rule did not join (p < q)
};

// Each point's local spacing neighbour: its third nearest Delaunay neighbour (exact comparisons;
// ties -> the lexicographically smaller point; fewer neighbours -> the farthest).
std::vector<int> spacing_neighbours(const PointSet& pts, const Delaunay3& dt);

// |pq| / rms(nn(p), nn(q)) in double (the report).
double gap_ratio(const PointSet& pts, const std::vector<int>& nn, int p, int q);

// The parts: components of the Delaunay edges shorter than `gap` local spacings (exact), the small
// ones (fewer than min_points, or flat) joined to their nearest; `merged` counts those joins. `fine`
// gets the parts of the narrower rule, for split_by_labels().
Parts find_parts(const PointSet& pts, const Delaunay3& dt, const std::vector<int>& nn, double gap, std::size_t min_points,
                 std::size_t& merged, Parts& fine);

// Parts that nearly touch: the narrower rule's pieces of a part stay apart unless tetrahedra that
// the engine labels inside join them (docs/topology.md, "Parts that nearly touch"). `split` counts
// the parts added. dt's arrays are lent to the labels and unchanged on return.
Parts split_by_labels(const PointSet& pts, Delaunay3& dt, const std::vector<int>& nn, Parts parts, const Parts& fine,
                      std::size_t min_points, std::size_t& split);

// A small dense patch of a surface joins the part whose surface it lies on (docs/topology.md,
// "Decimated meshes"). `joined` counts the joins.
Parts join_patches(const PointSet& pts, Delaunay3& dt, const std::vector<int>& nn, Parts parts, double gap,
                   std::size_t& joined);

// ---- assemble3.cpp ---------------------------------------------------------------------------------

// The body of the part surfaces (`faces`, input ids) inside dt: the regions of tetrahedra between
// the surfaces, a tree rooted at the exterior; the body is the regions at odd depth. False when a
// surface face is not a Delaunay face or the regions do not form that tree.
bool assemble_body(const Delaunay3& dt, const std::vector<std::array<int, 3>>& faces, std::vector<std::array<int, 4>>& body);

// Flips surface faces that are not Delaunay faces of dt towards ones that are, keeping every
// surface a closed oriented 2-manifold of its genus. Returns the number of flips (at most max_flips).
std::size_t flip_to_delaunay_faces(const Delaunay3& dt, std::vector<std::array<int, 3>>& faces, std::size_t max_flips);

// The free faces of a body of positively oriented tetrahedra, oriented out of it, sorted.
TriMesh3 body_surface(const std::vector<std::array<int, 4>>& body);

// Are the parts' bounding boxes pairwise disjoint (exact)? Is every pair of parts strictly on the
// two sides of a plane (never a wrong "yes")? Either way their bodies cannot meet.
bool boxes_apart(const PointSet& pts, const Parts& parts);
bool planes_apart(const PointSet& pts, const Parts& parts);

// The surfaces of a closed mesh: its components ordered by their lexicographically smallest point,
// with their genus (roles outer, no parents).
std::vector<Surface3> split_surfaces(const PointSet& pts, const TriMesh3& mesh);

// Roles and parents of several parts' surfaces from the regions of dt between them.
void nest_surfaces(const Delaunay3& dt, const TriMesh3& mesh, std::vector<Surface3>& s);

// Roles and parents in one connected body: by the exact sign of each surface's enclosed volume.
void nest_in_body(const PointSet& pts, const TriMesh3& mesh, std::vector<Surface3>& s);

// Each surface's smallest gap to another surface's points over `edges` (double, the report).
void report_gaps(const PointSet& pts, const std::vector<std::array<int, 2>>& edges, const std::vector<int>& nn,
                 std::vector<Surface3>& s);

// ---- repair3.cpp -----------------------------------------------------------------------------------

// The body that the parts' own bodies (res[k].tets, part ids) put in dt, with the points it buries
// or pinches repaired point by point, first within each part, then across parts (one work bound).
// True, with `body`, when that gives as many surfaces as parts, each point on one with a disk link;
// `repaired` is then the number of tetrahedra toggled. `capped`: the work bound was reached.
bool repaired_parts_body(const PointSet& pts, const Delaunay3& dt, const Parts& parts, const std::vector<Mesh3Result>& res,
                         std::size_t faces, std::vector<std::array<int, 4>>& body, bool& capped, std::size_t& repaired);

}  // namespace constrict::detail::surfaces3
