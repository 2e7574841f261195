// SPDX-License-Identifier: GPL-3.0-or-later
// The stages of the 3D engine (docs/architecture.md). Each works on the shared Body3 and reads
// the inputs it needs (labels, γ face terms); each has its own small state. The pipeline in
// constrict3.cpp calls them in order:
//   labels (labels3.cpp) -> growth + its lock cavities (grow3.cpp, cavity3.cpp) -> fill
//   (carve3.cpp) | constriction from the hull (hull3.cpp) -> lock cavities (cavity3.cpp) ->
//   carve (carve3.cpp) -> sculpt (hull3.cpp) -> flips (flips3.cpp) -> variant selection
//   (variants3.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/detail/body3.hpp"
#include "constrict/detail/share3.hpp"
#include "constrict/gamma_graph.hpp"

namespace constrict::detail {

// ---- labels (labels3.cpp) ----------------------------------------------------------------------

// Below every ln circumradius: the value of a flat tetrahedron.
constexpr double kFlatLogRadius = -1e300;

// Inside/outside labels of the Delaunay tetrahedra (docs/reconstruction-3d.md §4.6).
struct Labels3 {
  std::vector<float> label;  // +confidence outside / -confidence inside, per Delaunay tetrahedron
  std::vector<double> lrad;  // ln circumradius (kFlatLogRadius if flat)
};
// Circumball propagation from the convex hull (power-crust style). Deterministic: sequential
// bucket queue. Reads the Delaunay tetrahedra of the body (tets[0, T0), nbr). `beside`, if given,
// runs on another thread during the sequential propagation (work that reads neither the labels
// nor anything the propagation writes), and has returned when this does.
std::shared_ptr<const Labels3> compute_labels3(const Body3& body, const std::function<void()>& beside = {});
// Nearest-neighbour distance per point along the Delaunay edges.
std::vector<double> nearest_spacing3(const Body3& body);

// ---- keys of the constriction (hull3.cpp) ------------------------------------------------------

// What the constriction keys read besides the body: shared by the variant runs, read-only.
struct Keys3 {
  std::shared_ptr<const DelaunayGamma3> dg;                          // γ-values (lazy)
  std::shared_ptr<const std::vector<std::array<double, 4>>> terms;  // 1 - γ per Delaunay tet face
  std::shared_ptr<const std::vector<double>> spacing;               // nearest_spacing3 (size bias)
  std::shared_ptr<const std::vector<double>> face_log;              // ln bridge ratio per γ face
  std::shared_ptr<const Labels3> labels;
};
std::shared_ptr<const std::vector<std::array<double, 4>>> compute_face_terms3(const Body3& body, const DelaunayGamma3& dg);
std::shared_ptr<const std::vector<double>> compute_face_log3(const Body3& body, const DelaunayGamma3& dg,
                                                             const std::vector<double>& spacing);

// ---- the constriction from the convex hull and the sculpting (hull3.cpp) -----------------------

struct Constriction3State {
  TetHeap heap;
  std::size_t removed = 0, removed1 = 0, removed2 = 0;  // all, by the one-face / two-face rule
  bool stopped = false;  // stop_after reached
};
// Which tetrahedra are removable and by which key: the paper's rules with the option's
// criterion, or (Sculpt3::Bridges) two-face tetrahedra by their larger surface face's bridge ratio.
enum class RemovalKey { Criterion, Bridge };

// A view over the body and the constriction's state: the removal rules (spec gamma-graph.md
// §3.3) and keys (spec §3.4) of the paper's constriction (seed paper §4.2, §5).
class HullConstriction3 {
 public:
  HullConstriction3(Body3& body, Constriction3State& st, const Keys3& keys, const Constrict3Options& opt,
                    Constrict3Visitor* visitor, RemovalKey rule = RemovalKey::Criterion)
      : b_(body), s_(st), k_(keys), opt_(opt), visitor_(visitor), rule_(rule) {}
  // The initial heap: the tetrahedra on the convex hull.
  void start_heap();
  // The heap from every body tetrahedron (the bridge sculpting).
  void push_all_alive();
  void try_push(int t);
  // Pops until one removal is done; false when the heap is empty or its best key < min_key.
  bool pop_and_remove(double min_key, Stage3 stage);

 private:
  int removable(int t, double* key) const;
  double criterion_key(int t, const int* bi, int nb) const;
  double face_term(int t, int i) const;
  double face_log_ratio(int t, int i) const;
  double face_bridge(int t, int i) const;
  void remove(int t, int kind, double key, Stage3 stage);

  Body3& b_;
  Constriction3State& s_;
  const Keys3& k_;
  const Constrict3Options& opt_;
  Constrict3Visitor* visitor_;
  RemovalKey rule_;
};
// Bridge ratio of the triangle abc: its longest edge over the largest spacing of its vertices.
double bridge_ratio3(const PointSet& pts, const std::vector<double>& spacing, int a, int b, int c);
// The same for a tetrahedron: bridge_ratio3(pts, spacing, tet) in share3.hpp.

// ---- star cavities (cavity3.cpp; docs/reconstruction-3d.md §3) ---------------------------------

// Where a cavity is made: in the body (the constriction's stuck points are inside it) or,
// mirrored for the growth (§4.7), among the Delaunay tetrahedra outside the body (the growth's
// unreached points are there; the convex hull then bounds that side).
enum class CavitySide { Body, Outside };

struct CavityState3 {
  std::vector<int> vert_tet;  // a tetrahedron of the side incident to each point
  std::size_t made = 0, attempts = 0;
  // Work bound (tetrahedra visited by the searches; cavity3.cpp): index_vertices() sets the limit
  // from the triangulation's size; past it place() tries nothing more and sets capped.
  std::size_t work = 0, work_limit = 0;
  bool capped = false;
};
// What a successful cavity made.
struct CavityMade {
  std::vector<int> created;      // the cone tetrahedra (in the body for CavitySide::Body)
  std::array<int, 3> target{};   // the surface face it was made through (sorted ids)
  std::size_t replaced = 0;      // tetrahedra it replaced
};

class Cavity3 {
 public:
  Cavity3(Body3& body, CavityState3& st, const Constrict3Options& opt, CavitySide side, Constrict3Visitor* visitor)
      : b_(body), s_(st), opt_(opt), side_(side), visitor_(visitor) {}
  // vert_tet from the tetrahedra of the side.
  void index_vertices();
  // Re-tetrahedralizes a star-shaped region around p (exact orient3 tests) so that a cone
  // tetrahedron over a surface face p sees brings p to the surface side; false (nothing changed)
  // when no ranked target face works.
  // (Past the work bound: false without trying; CavityState3::capped.)
  bool place(int p, CavityMade& made);

 private:
  bool over_budget();
  struct Target {
    double key;
    int t, i;
    std::array<int, 3> ids;
  };
  bool in_side(int m) const;
  bool star_of(int p, std::vector<int>& out);
  double target_key(int a, int b, int c, int p) const;
  void targets_of(int p, const std::vector<int>& star, int depth, std::vector<Target>& out);
  bool grow_visible(int p, std::vector<int>& U, std::uint32_t in_u);
  bool try_cavity(int p, const std::vector<int>& star, const Target& tg, CavityMade& made);

  Body3& b_;
  CavityState3& s_;
  const Constrict3Options& opt_;
  CavitySide side_;
  Constrict3Visitor* visitor_;
};

// ---- growth from the inside (grow3.cpp; docs/reconstruction-3d.md §4.7) ------------------------

// What the growth sets up from the Delaunay tetrahedralization alone, so that it can be made
// beside the labels: each vertex's room for its body edges (its Delaunay degree), as offsets.
struct GrowthPrep3 {
  std::vector<std::size_t> edge_room;  // n + 1 offsets
};
GrowthPrep3 prepare_growth3(const Body3& body);

struct Growth3Stats {
  std::size_t grown = 0, grown_outside = 0, cavities = 0;
  std::size_t pocket_filled = 0, pocket_reached = 0;  // the fill during the growth: tetrahedra, points
  std::size_t crawled = 0;  // of the outside ones, joined by the two-face rule into thin parts
  bool cavity_capped = false;  // the mirrored cavities stopped at their work bound
};
// Grows the body from the inside tetrahedron of the largest circumradius by the mirror images of
// the removal rules; points it cannot reach get a mirrored star cavity (unless Fallback3::None).
// Starts from any state (it sets the body to empty). True when every point is on the surface;
// otherwise the caller restores the start (Body3::reset_to_hull with nbr_delaunay, the
// adjacency before the first cavity, saved here). `spacing`: nearest_spacing3(body) if the caller
// has it (else computed when the first outside step needs it).
// `prep`: prepare_growth3(body) if the caller made it (else made here).
bool grow_body3(Body3& body, const Labels3& labels, const Constrict3Options& opt, Constrict3Visitor* visitor,
                Growth3Stats& stats, Tets& nbr_delaunay, const std::vector<double>* spacing = nullptr,
                const GrowthPrep3* prep = nullptr);

// ---- carve and fill (carve3.cpp; docs/reconstruction-3d.md §4.6, §4.7) -------------------------

// Label confidence of the fill (and of the handle stage): the carve's, or 0.5 when the carve is
// off (carve_confidence > 1).
inline double fill_confidence(const Constrict3Options& opt) {
  return opt.carve_confidence <= 1 ? opt.carve_confidence : 0.5;
}

struct Carve3Stats {
  std::size_t changed = 0, regions = 0, undone = 0;  // tetrahedra kept removed / added; ...
  std::size_t trials = 0;  // single toggles the local repair tried (all regions of the pass)
  bool capped = false;     // the pass stopped at its bound of link evaluations (carve3.cpp)
};
// Removes the surface-connected regions of body tetrahedra labelled outside (confidence >=
// min_conf), keeping each region's removals up to its last valid state (closed 2-manifold of
// genus 0 through every point). Returns the tetrahedra removed.
std::size_t carve_outside3(Body3& body, const Labels3& labels, double min_conf, Carve3Stats& stats);
// The mirror image after the growth: adds the regions of Delaunay tetrahedra labelled inside that
// the body left out, under the same validity rule and with no enclosed void; a region it does not
// add whole is peeled once more, largest circumball first (§4.16). `reach`: during the
// growth, while points are still out of the body: those may stay out, and a region may bring them
// in (a valid state: a closed genus-0 2-manifold through the points in the body); it runs only when
// a left-out tetrahedron labelled inside has such a point (docs/reconstruction-3d.md §4.13).
std::size_t fill_inside3(Body3& body, const Labels3& labels, double min_conf, Carve3Stats& stats, bool reach = false);

// ---- handles (carve3.cpp, handles3.cpp; docs/topology.md §"3D") --------------------------------

// Whether a region's change that made a handle is kept: the tetrahedra it changed and whether they
// were added (a loop closed) or removed (a tunnel opened); the body is in the changed state.
// dF: the change of the surface's face count (> 0 a handle, < 0 a sealed cavity). pinched: the
// region reached its valid state only through a move of several tetrahedra at a pinched vertex.
// trim (null on a retry): a decision that refuses may list tetrahedra of `changed` to put back;
// the engine then tries the change without them once (if that state is valid) and asks again.
using HandleDecision = std::function<bool(const Body3& body, const std::vector<int>& changed, bool added, long long dF,
                                          bool pinched, std::vector<int>* trim)>;
// The regions labelled inside that the body left out (closing loops), then the regions labelled
// outside in the body (opening tunnels), under the manifold rule without the genus-0 condition; a
// region's change is kept only when it adds a handle and decide agrees. Returns the tetrahedra changed.
// local_repair: a closing region whose end state has a few non-manifold points is repaired by
// single toggles (also dimples that free buried points) before its undo (noisy samples); off for
// the run on several parts, whose seals are decided by the parts.
std::size_t handles3(Body3& body, const Labels3& labels, double min_conf, const HandleDecision& decide,
                     Carve3Stats& closed, Carve3Stats& opened, bool local_repair = true);
// The decision of the engine (handles3.cpp): a change is kept when it lowers the bridge measure
// of the surface around it; with part_of (the parts of the gap rule, per point; may be null) also
// a sealed cavity that leaves fewer surfaces holding points of two parts.
// log (may be null) receives every change the decision keeps. spacing (may be null): the body's
// nearest_spacing3, when the engine has it (else made on first use).
HandleDecision bridge_handle_decision(const Body3& body, const std::vector<int>* part_of,
                                      std::shared_ptr<std::vector<Handle3Change>> log, const Labels3* labels = nullptr,
                                      std::shared_ptr<const std::vector<double>> spacing = nullptr);

// ---- edge flips (flips3.cpp; docs/reconstruction-3d.md §4) -------------------------------------

struct Flips3Stats {
  std::size_t added = 0, removed = 0;
  bool capped = false;  // a pass stopped at its work bound (flips3.cpp)
  std::size_t long_rings = 0;  // candidates not tried: their edge lies in over kMaxFlipRing tetrahedra
};
// Energy-decreasing surface edge flips through Delaunay tetrahedra, best first, for one energy
// (Refine3::Area or Refine3::Circumradius).
void flip_pass3(Body3& body, Refine3 energy, Flips3Stats& stats);

}  // namespace constrict::detail
