// SPDX-License-Identifier: GPL-3.0-or-later
// reconstruct_surfaces3(): the 3D ladder of topology.hpp (docs/topology.md §"3D") -- parts by the
// exact gap rule on the Delaunay edges (between 3/4 of its threshold and the threshold the engine's
// labels decide: parts that nearly touch; a small part that the labels show to be a patch of its
// neighbour's surface joins it); one part -> reconstruct3() (with handles in Auto); several
// -> one reconstruct3() per part, then the body of all of them from the Delaunay tetrahedralization
// of all points by the parity of the surfaces around each tetrahedron (inner shells become
// cavities), roles and parents from the nesting tree. Any step that does not hold exactly (a part
// too small, a surface face that is not a Delaunay face of all points, an inconsistent nesting)
// falls back to one part. Then the exact validation of what came out. The stages are in
// parts3.cpp, assemble3.cpp and repair3.cpp (detail/surfaces3.hpp); this file reads as the ladder.
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
#include <string>
#include <utility>
#include <vector>

#include <tbb/parallel_invoke.h>

#include "constrict/delaunay.hpp"
#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/topology.hpp"
#include "constrict/detail/share3.hpp"
#include "core/detail/canonical_order.hpp"
#include "core/detail/check_points.hpp"
#include "core/detail/tet_order.hpp"
#include "topology/detail/surfaces3.hpp"

namespace constrict {
namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

using namespace detail::surfaces3;

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
  // points it buries brought to its surface by dimples (repair3.cpp); taken when that is a valid
  // set of surfaces.
  if (!assembled && !boxes_apart(pts, parts))
    assembled = repaired_parts_body(pts, dt, parts, res, faces.size(), body, r.repair_capped, r.repaired_tetrahedra);
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
    return {StatusCode::InvalidArgument, "topology gap must be a finite number >= 0, not " + number_text(o.topology_gap)};
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
  Parts parts = find_parts(work, dt, nn, o.topology_gap, o.min_part_points, r.small_parts_merged, fine);
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
