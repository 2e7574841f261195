// SPDX-License-Identifier: GPL-3.0-or-later
// The 3D pipeline (docs/architecture.md): init builds the Delaunay tetrahedralization and the
// labels; finish runs the named stages in order over one Body3 state —
//   grow -> fill | gamma (constriction from the hull) -> cavity (lock fallback) -> carve ->
//   sculpt -> refine (flips) -> sculpt (bridges) -> result + validation.
// reconstruct3 adds the variant selection (variants3.cpp). The stages live in their own files
// (detail/stages3.hpp); this file only orders them and fills the result.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/detail/constrict3_impl.hpp"
#include "constrict/detail/share3.hpp"
#include "constrict/mesh.hpp"
#include "constrict/validate.hpp"
#include "core/detail/canonical_order.hpp"
#include "core/detail/check_points.hpp"
#include "core/detail/ordered_pack.hpp"
#include "core/detail/surface_components.hpp"
#include "core/detail/tet_order.hpp"

namespace constrict {

using detail::kAlive;
using detail::uz;

namespace {
// Option ranges of the size bias and the label weight.
constexpr double kMaxWeight = 100;
bool weights_ok(double size_bias, double label_weight) {
  return size_bias >= 0 && size_bias <= kMaxWeight && label_weight >= 0 && label_weight <= kMaxWeight;
}
}  // namespace

// ---- names -------------------------------------------------------------------------------------

const char* to_string(Stage3 s) noexcept {
  switch (s) {
    case Stage3::Hull: return "hull";
    case Stage3::Grow: return "grow";
    case Stage3::Fill: return "fill";
    case Stage3::Handles: return "handles";
    case Stage3::Gamma: return "gamma";
    case Stage3::Cavity: return "cavity";
    case Stage3::Carve: return "carve";
    case Stage3::Sculpt: return "sculpt";
    case Stage3::Refine: return "refine";
    case Stage3::Candidates: return "candidates";
  }
  return "?";
}

const char* to_string(Method3 m) noexcept {
  switch (m) {
    case Method3::Gamma: return "gamma";
    case Method3::Grow: return "grow";
    case Method3::Cavity: return "cavity";
    case Method3::Locked: return "locked";
    case Method3::Stopped: return "stopped";
    case Method3::VoronoiSkeleton: return "voronoi-skeleton";
    case Method3::Incomplete: return "incomplete";
  }
  return "?";
}

const char* to_string(Fallback3 f) noexcept { return f == Fallback3::None ? "none" : "auto"; }

bool fallback3_from_name(const std::string& name, Fallback3& out) noexcept {
  if (name == "auto") out = Fallback3::Auto;
  else if (name == "none") out = Fallback3::None;
  else return false;
  return true;
}

Status Constrict3Options::from_preset(const std::string& name, Constrict3Options& out) {
  if (name == "default") out = Constrict3Options{};
  else if (name == "paper") out = paper();
  else if (name == "fast") out = fast();
  else return {StatusCode::InvalidArgument, "unknown 3D preset '" + name + "' (use default, paper or fast)"};
  return Status::ok();
}

// ---- Impl: the set-up and the stages in order --------------------------------------------------

void Constrictor3::Impl::IdMapVisitor::on_event(const Constrict3Event& e) {
  Constrict3Event m = e;
  for (int& v : m.tet)
    if (v >= 0) v = (*order)[uz(v)];
  if (m.point >= 0) m.point = (*order)[uz(m.point)];
  inner->on_event(m);
}

void Constrictor3::Impl::set_visitor(Constrict3Visitor* v) {
  id_map.inner = v;
  id_map.order = order.get();
  visitor = v ? &id_map : nullptr;
}

std::vector<int> Constrictor3::Impl::input_ids(std::vector<int> ids) const {
  detail::to_input_ids(*order, ids);
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::array<int, 4> Constrictor3::Impl::input_ids(std::array<int, 4> t) const {
  for (int& v : t) v = (*order)[uz(v)];
  return t;
}

TriMesh3 Constrictor3::Impl::input_ids(TriMesh3 m) const {
  detail::to_input_ids(*order, m.triangles);
  return m;
}

void Constrictor3::Impl::reset_to_hull() {
  body.reset_to_hull(nbr_delaunay);
  growth = {};
  filled = 0;
  grew = false;
  hull.heap.clear();
  hull_ready = false;
}

void Constrictor3::Impl::ensure_hull_start() {
  if (hull_ready) return;
  auto t0 = Clock::now();
  if (!keys.dg) {
    // Same builder, same input: the same tetrahedra in the same order (checked).
    auto dg = std::make_shared<DelaunayGamma3>();
    const Status st = delaunay_gamma3(*body.pts, *dg, false);
    if (st.is_ok() && tets_ordered) detail::order_tets_by_vertex(dg->dt, &dg->simplex_face);
    CONSTRICT_CHECK(st.is_ok() && dg->dt.tets.size() == body.T0 &&
                        std::equal(dg->dt.tets.begin(), dg->dt.tets.end(), body.tets.begin()),
                    "the γ pass did not reproduce the tetrahedralization");
    dg->dt = Delaunay3{};
    keys.dg = std::move(dg);
    ms_delaunay += ms_since(t0);
    t0 = Clock::now();
  }
  if (!keys.terms) keys.terms = detail::compute_face_terms3(body, *keys.dg);
  if (need_size && !keys.face_log) {
    if (!keys.spacing) keys.spacing = std::make_shared<const std::vector<double>>(detail::nearest_spacing3(body));
    keys.face_log = detail::compute_face_log3(body, *keys.dg, *keys.spacing);
  }
  constriction().start_heap();
  hull_ready = true;
  ms_setup += ms_since(t0);
}

bool Constrictor3::Impl::step() {
  if (!ready || hull.stopped || body.n_onb == body.n) return false;
  stepped = true;
  ensure_hull_start();
  if (hull.removed >= opt.stop_after) {
    hull.stopped = true;
    return false;
  }
  if (constriction().pop_and_remove(kAnyKey, Stage3::Gamma)) return true;
  if (visitor) {
    Constrict3Event e;
    e.kind = Constrict3Event::Kind::Lock;
    e.stage = Stage3::Gamma;
    visitor->on_event(e);
  }
  return false;
}

void Constrictor3::Impl::stage_event(Stage3 stage) const {
  if (!visitor) return;
  Constrict3Event e;
  e.kind = Constrict3Event::Kind::StageBegin;
  e.stage = stage;
  visitor->on_event(e);
}

// (0) Growth from the inside (docs/reconstruction-3d.md §4.7), only from the untouched initial
// state; once per state (a second finish() returns the grown body again), then the fill.
Constrictor3::Impl::Growth Constrictor3::Impl::grow_stage(Mesh3Result& r) {
  if (!grew && can_grow() && !stepped) {
    auto t0 = Clock::now();
    stage_event(Stage3::Grow);
    const bool ok = detail::grow_body3(body, *keys.labels, opt, visitor, growth, nbr_delaunay, keys.spacing.get(),
                                       growth_prep.get());
    growth_prep.reset();
    stepped = true;
    r.ms_grow = ms_since(t0);
    r.cavity_capped = growth.cavity_capped;  // (a failed growth's result is not kept: here)
    if (!ok) {
      r.grow_unreached = body.n - body.n_onb;
      reset_to_hull();
      return Growth::Failed;
    }
    grew = true;
    stage_event(Stage3::Fill);
    t0 = Clock::now();
    detail::Carve3Stats fs;
    filled = detail::fill_inside3(body, *keys.labels, detail::fill_confidence(opt), fs);
    fill_capped = fs.capped;
    r.ms_fill = ms_since(t0);
  }
  if (!grew) return Growth::NotRun;
  r.grown = growth.grown;
  r.cavity_capped = r.cavity_capped || growth.cavity_capped;
  r.grow_cavities = growth.cavities;
  r.grow_pocket_points = growth.pocket_reached;
  r.grow_pocket_filled = growth.pocket_filled;
  r.grown_outside = growth.grown_outside;
  r.grown_crawled = growth.crawled;
  r.filled = filled;
  r.carve_capped = r.carve_capped || fill_capped;
  r.stages.push_back({Stage3::Grow, body.n - n_hull, 0});
  r.stages.push_back({Stage3::Fill, 0, 0});
  handles_stage(r);
  return Growth::Grown;
}

// (0') The handle stage after the fill (Constrict3Options::handles; docs/topology.md §"3D"): loops
// closed through the inside regions the growth left out, tunnels opened through outside ones,
// cavities sealed, each kept only where it lowers the bridge measure; one body, else undone.
void Constrictor3::Impl::handles_stage(Mesh3Result& r) {
  if (!opt.handles || !keys.labels) return;
  stage_event(Stage3::Handles);
  const auto t0 = Clock::now();
  const std::vector<std::uint8_t> state0 = body.state;
  handles_closed = handles_opened = {};
  const double conf = detail::fill_confidence(opt);
  auto log = std::make_shared<std::vector<Handle3Change>>();
  const std::size_t changed =
      detail::handles3(body, *keys.labels, conf, detail::bridge_handle_decision(body, part_of.get(), log, keys.labels.get(), keys.spacing), handles_closed,
                       handles_opened, /*local_repair=*/!part_of);
  // (Enclosed voids are the cavities of inner shells: allowed here.)
  if (changed > 0 && !body.side_connected(kAlive)) {
    body.state = state0;
    handles_closed.changed = handles_opened.changed = 0;
    log->clear();
  }
  r.handle_changes = std::move(*log);
  r.handle_added = handles_closed.changed;
  r.carve_capped = r.carve_capped || handles_closed.capped || handles_opened.capped;
  r.handle_removed = handles_opened.changed;
  r.stages.push_back({Stage3::Handles, 0, handles_opened.changed});
  r.ms_fill += ms_since(t0);
}

// (1) The γ-constriction from the hull (the caller may have stepped already).
void Constrictor3::Impl::constriction_stage(Mesh3Result& r) {
  const auto t0 = Clock::now();
  while (step()) {
  }
  r.ms_constrict = ms_since(t0);
  r.stages.push_back({Stage3::Gamma, body.n_onb - n_hull, hull.removed});
}

// (2) The lock fallback: star cavities around the stuck points, then the constriction goes on.
void Constrictor3::Impl::lock_fallback_stage(Mesh3Result& r) {
  if (body.n_onb == body.n || hull.stopped) return;
  r.locked = true;
  r.stuck_points = body.inside();
  if (opt.fallback != Fallback3::Auto) return;
  stage_event(Stage3::Cavity);
  const auto t0 = Clock::now();
  const std::size_t onb0 = body.n_onb, rem0 = hull.removed;
  detail::Cavity3 cav(body, cavity, opt, detail::CavitySide::Body, visitor);
  detail::HullConstriction3 hc = constriction();
  cav.index_vertices();
  detail::CavityMade made;
  for (bool progress = true; body.n_onb < body.n && progress;) {
    progress = false;
    for (int p : body.inside()) {
      if (body.onb[uz(p)] || !cav.place(p, made)) continue;
      progress = true;
      for (int t : made.created)
        if (body.boundary_face(t, 3)) hc.try_push(t);
      while (hc.pop_and_remove(kAnyKey, Stage3::Cavity))
        if (body.n_onb == body.n) break;
      if (body.n_onb == body.n) break;
    }
  }
  r.ms_fallback = ms_since(t0);
  r.cavity_capped = r.cavity_capped || cavity.capped;
  r.stages.push_back({Stage3::Cavity, body.n_onb - onb0, hull.removed - rem0});
  if (body.n_onb > onb0) r.method = Method3::Cavity;
}

// (3) The carve pass (docs/reconstruction-3d.md §4.6).
void Constrictor3::Impl::carve_stage(Mesh3Result& r) {
  if (!(opt.carve_confidence <= 1 && opt.criterion == Criterion::Gamma && keys.labels)) return;
  stage_event(Stage3::Carve);
  const auto t0 = Clock::now();
  carve = {};
  hull.removed += detail::carve_outside3(body, *keys.labels, opt.carve_confidence, carve);
  r.ms_carve = ms_since(t0);
  r.carved = carve.changed;
  r.carve_undone = carve.undone;
  r.carve_capped = r.carve_capped || carve.capped;
  r.stages.push_back({Stage3::Carve, 0, carve.changed});
}

// (4) The two-face sculpting (seed paper §4.2, candlestick figure): all points stay on the
// surface since two-face removals add no point and remove none.
void Constrictor3::Impl::sculpt_stage(Mesh3Result& r) {
  if (opt.sculpt != Sculpt3::TwoFace) return;
  stage_event(Stage3::Sculpt);
  const auto t0 = Clock::now();
  const std::size_t rem0 = hull.removed, r2 = hull.removed2;
  detail::HullConstriction3 hc = constriction();
  while (hc.pop_and_remove(opt.sculpt_threshold, Stage3::Sculpt)) {
  }
  CONSTRICT_CHECK(hull.removed - rem0 == hull.removed2 - r2, "sculpting removed a one-face tetrahedron");
  removed_sculpt = hull.removed - rem0;
  r.ms_sculpt = ms_since(t0);
  r.stages.push_back({Stage3::Sculpt, 0, removed_sculpt});
}

// (5) Refine3 flips. Alternate: the local minimum of one energy is usually not one of the other:
// one more Circumradius pass, then Area again. Further rounds only ping-pong (measured: +0.2 % of
// GT triangles at 2.5 x the time; docs/reconstruction-3d.md §4.1).
void Constrictor3::Impl::refine_stage(Mesh3Result& r) {
  if (opt.refine == Refine3::None) return;
  stage_event(Stage3::Refine);
  const auto t0 = Clock::now();
  if (opt.refine == Refine3::Alternate) {
    for (Refine3 e : {Refine3::Area, Refine3::Circumradius, Refine3::Area}) detail::flip_pass3(body, e, flips);
  } else {
    detail::flip_pass3(body, opt.refine, flips);
  }
  r.ms_refine = ms_since(t0);
  r.stages.push_back({Stage3::Refine, 0, flips.removed});
}

// (6) Bridge sculpting after the flips (the area flips keep big bridging faces).
void Constrictor3::Impl::bridge_stage(Mesh3Result& r) {
  if (opt.sculpt != Sculpt3::Bridges) return;
  stage_event(Stage3::Sculpt);
  const auto t0 = Clock::now();
  const std::size_t rem0 = hull.removed;
  detail::HullConstriction3 hc(body, hull, keys, opt, visitor, detail::RemovalKey::Bridge);
  hc.push_all_alive();
  while (hc.pop_and_remove(opt.bridge_ratio, Stage3::Sculpt)) {
  }
  hull.heap.clear();
  removed_sculpt = hull.removed - rem0;
  r.ms_sculpt = ms_since(t0);
  r.stages.push_back({Stage3::Sculpt, 0, removed_sculpt});
}

// The result from the body: surface, tetrahedra, counts; volume and area at the input's scale.
void Constrictor3::Impl::collect(Mesh3Result& r) const {
  r.refine_added = flips.added;
  r.refine_removed = flips.removed;
  r.refine_capped = flips.capped;
  r.removed_one_face = hull.removed1;
  r.removed_two_face = hull.removed2;
  r.removed_sculpt = removed_sculpt;
  r.cavities = cavity.made;
  r.cavity_attempts = cavity.attempts;
  r.unplaced_points = input_ids(body.inside());
  r.stuck_points = input_ids(r.stuck_points);
  const TriMesh3 surface = body.surface();  // (engine ids: the volume and area read body.pts)
  r.ms_setup = ms_setup;  // (the hull start may have been made on demand, with the γ pass)
  r.ms_delaunay = ms_delaunay;
  // The rest reads the surface and the body and writes separate fields: side by side. (Each sum
  // runs in one task in face order, as before: the same bits.)
  double volume = 0, area = 0;
  tbb::parallel_invoke(
      [&] { r.mesh = input_ids(surface); },
      [&] {
        r.tets = detail::ordered_pack<std::array<int, 4>>(body.tets.size(), [&](std::size_t t, const auto& push) {
          if (body.state[t] == kAlive) push(input_ids(body.tets[t]));
        });
        for (std::size_t t = body.T0; t < body.tets.size(); ++t) r.non_delaunay_tets += body.state[t] == kAlive;
      },
      [&] { measure_bridges(surface, r); },
      // F = 2N - 4c + 4g for c closed surfaces of total genus g through all N points; the volume
      // about each surface's own origin (one union-find for both).
      [&] {
        const std::vector<int> comp = detail::surface_of_vertex(body.pts->size(), surface);
        r.surfaces = 0;
        for (int c : comp) r.surfaces = std::max(r.surfaces, c + 1);
        volume = detail::mesh_volume_of_surfaces(*body.pts, surface, comp);
      },
      [&] { area = mesh_area(*body.pts, surface); });
  if (r.complete)
    r.genus = static_cast<int>((static_cast<long long>(surface.triangles.size()) - 2LL * static_cast<long long>(body.n) +
                                4LL * r.surfaces) / 4);
  r.volume = std::ldexp(volume, 3 * scale_exp);
  r.surface_area = std::ldexp(area, 2 * scale_exp);
}

// The bridge measure of the surface (Mesh3Result::bridge_faces): ratios against the spacing along
// the Delaunay edges (the constriction's, when its size bias made them).
void Constrictor3::Impl::measure_bridges(const TriMesh3& surface, Mesh3Result& r) const {
  std::vector<double> own;
  if (!keys.spacing) own = detail::nearest_spacing3(body);
  const std::vector<double>& spacing = keys.spacing ? *keys.spacing : own;
  const PointSet& p = *body.pts;
  const std::size_t nf = surface.triangles.size();
  std::vector<double> ratio(nf);
  r.max_bridge_ratio = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nf, std::size_t{1} << 14), r.max_bridge_ratio,
      [&](const tbb::blocked_range<std::size_t>& rg, double m) {
        for (std::size_t f = rg.begin(); f != rg.end(); ++f) {
          const auto& t = surface.triangles[f];
          ratio[f] = detail::bridge_ratio3(p, spacing, t[0], t[1], t[2]);
          m = std::max(m, ratio[f]);
        }
        return m;
      },
      [](double a, double b) { return std::max(a, b); });
  TriMesh3 bridges;
  bridges.triangles = detail::ordered_pack<std::array<int, 3>>(nf, [&](std::size_t f, const auto& push) {
    if (ratio[f] >= Mesh3Result::kBridgeRatio) push(surface.triangles[f]);
  });
  // (One mesh_area call: it scans every point once for its magnitude, so not once per face.)
  r.bridge_faces = bridges.triangles.size();
  r.bridge_area = bridges.triangles.empty() ? 0.0 : std::ldexp(mesh_area(p, bridges), 2 * scale_exp);
}

// ---- Constrictor3 --------------------------------------------------------------------------------

Constrictor3::Constrictor3() : impl_(std::make_unique<Impl>()) {}
Constrictor3::~Constrictor3() = default;

Status Constrictor3::init(const PointSet& points, const Constrict3Options& options, Constrict3Visitor* visitor) {
  Impl& s = *impl_;
  std::shared_ptr<Delaunay3> shared = std::move(s.shared_dt);
  std::shared_ptr<const std::vector<int>> part_of = std::move(s.part_of);
  s = Impl{};
  s.shared_dt = std::move(shared);
  s.part_of = std::move(part_of);
  if (points.dim != 3) return {StatusCode::InvalidArgument, "reconstruct3 needs 3D points"};
  if (!(options.sculpt_threshold >= 0 && options.sculpt_threshold <= 4))
    return {StatusCode::InvalidArgument, "sculpt_threshold must be in [0, 4]"};
  if (!weights_ok(options.size_bias, options.label_weight))
    return {StatusCode::InvalidArgument, "size_bias and label_weight must be in [0, 100]"};
  // Duplicates are found below, next to each other in the canonical order (O(N), not check_points'
  // sort); check_points() then names them.
  if (Status st = detail::check_points_deferred(points); !st) return st;
  s.input = &points;
  // The engine runs on the points in a canonical order of their coordinates, so that the same
  // points in any file order give the same surface (ties everywhere are broken by engine ids);
  // the result is mapped back to input ids in collect().
  // (With a shared tetrahedralization the caller's points are in canonical order already:
  // detail::reconstruct3_sharing's precondition.)
  if (s.shared_dt) {
    std::vector<int> id(points.size());
    for (std::size_t k = 0; k < id.size(); ++k) id[k] = static_cast<int>(k);
    s.order = std::make_shared<const std::vector<int>>(std::move(id));
  } else {
    s.order = std::make_shared<const std::vector<int>>(detail::canonical_order(points));
  }
  // (Shared: the caller's points are the canonical ones and outlive the engine, so they are used
  // as they are; a copy was 24 bytes per point more at the peak of a 10^6-point auto run.)
  std::shared_ptr<const PointSet> work =
      s.shared_dt ? std::shared_ptr<const PointSet>(std::shared_ptr<const PointSet>(), &points)
                  : std::make_shared<const PointSet>(detail::permuted(points, *s.order));
  if (detail::has_adjacent_duplicate(*work)) return check_points(points);
  // Far from 1 in magnitude, the double parts (γ magnitudes, circumballs, lengths) would overflow
  // or underflow: work on a copy scaled by a power of two, which changes no predicate and makes
  // every magnitude scale free (the result is then the same at any scale); areas and volumes are
  // scaled back in collect(). Refused (Unsupported) when no exact rescaling exists: the
  // coordinates span too many orders of magnitude for the double-valued parts.
  if (const int e = max_coordinate_exponent(points); e > kRescaleExponent || e < -kRescaleExponent) {
    auto scaled = std::make_shared<PointSet>();
    int exp = 0;
    if (Status st = exact_power_of_two_scale(*work, *scaled, exp); !st) {
      // (The check again in the caller's order, so that the message names the caller's point.)
      PointSet unused;
      Status in_order = exact_power_of_two_scale(points, unused, exp);
      return in_order.is_ok() ? st : in_order;
    }
    s.scale_exp = exp;
    work = std::move(scaled);
  }
  s.body.pts = work.get();
  s.work = std::move(work);
  s.opt = options;
  s.set_visitor(visitor);
  s.body.n = points.size();
  if (Status st = s.build_tetrahedralization(); !st) return st;
  return Status::ok();
}

Status Constrictor3::Impl::build_tetrahedralization() {
  const auto t0 = Clock::now();
  if (grow_planned()) {
    // The growth reads the tetrahedralization and the labels only: the γ-values are computed
    // when the constriction from the hull needs them (ensure_hull_start).
    Delaunay3 dt;
    // (Not after a rescaling: CGAL's spatial sort of the scaled copy may insert in another order.)
    if (shared_dt && scale_exp == 0 && shared_dt->n_vertices == body.n && order_is_identity()) {
      dt = std::move(*shared_dt);
    } else {
      if (Status st = build_delaunay3(*body.pts, dt); !st) return st;
      detail::order_large_tets(dt);
    }
    tets_ordered = detail::ordered_size(dt.tets.size());  // (a shared one: auto ordered it by the same rule)
    shared_dt.reset();
    body.tets = std::move(dt.tets);
    body.nbr = std::move(dt.neighbors);
  } else {
    auto dg = std::make_shared<DelaunayGamma3>();
    // The DT faces only: the co-spherical completion (every triple of a co-spherical cluster) is
    // part of the γ graph, not of the tetrahedralization the constriction carves.
    if (Status st = delaunay_gamma3(*body.pts, *dg, false); !st) return st;
    tets_ordered = detail::order_large_tets(dg->dt, &dg->simplex_face);
    body.tets = std::move(dg->dt.tets);
    body.nbr = std::move(dg->dt.neighbors);
    dg->dt = Delaunay3{};
    keys.dg = std::move(dg);
  }
  ms_delaunay = ms_since(t0);
  body.T0 = body.tets.size();
  const auto t_setup = Clock::now();
  need_size = opt.size_bias > 0 || opt.sculpt == Sculpt3::Bridges;
  bool need_label = opt.label_weight > 0 || (opt.carve_confidence <= 1 && opt.criterion == Criterion::Gamma) || grow_planned();
  for (const Constrict3Variant& v : opt.variants) {
    need_size = need_size || v.size_bias > 0;
    need_label = need_label || v.label_weight > 0;
  }
  // The start state (the hull) and the growth's set-up read only the tetrahedralization.
  const auto start_state = [&] {
    body.ver.assign(body.T0, 0);
    body.mark.assign(body.T0, 0);
    hull.heap.reserve(body.T0 / 4 + 16);
    reset_to_hull();
    n_hull = body.n_onb;
    if (grow_planned() && n_hull < body.n)
      growth_prep = std::make_shared<const detail::GrowthPrep3>(detail::prepare_growth3(body));
  };
  if (need_label) {
    // The spacing (the bridge measure of every complete result, the growth's outside steps) and
    // the start state are made on the other core while the labels propagate (the propagation
    // reads the tetrahedra and their neighbours only).
    auto spacing = std::make_shared<std::vector<double>>();
    keys.labels = detail::compute_labels3(body, [&] {
      *spacing = detail::nearest_spacing3(body);
      start_state();
    });
    keys.spacing = std::move(spacing);
  } else {
    start_state();
  }
  ms_setup = ms_since(t_setup);
  // (Every point on the hull after a DT-only build: nothing will be removed, so no γ pass and no
  // second tetrahedralization; the post-passes do not read γ.)
  if (!can_grow() && (keys.dg || body.n_onb < body.n)) ensure_hull_start();
  ready = true;
  return Status::ok();
}

bool Constrictor3::step() { return impl_->step(); }

TriMesh3 Constrictor3::surface() const { return impl_->input_ids(impl_->body.surface()); }

std::vector<int> Constrictor3::inside_points() const { return impl_->input_ids(impl_->body.inside()); }

Status Constrictor3::finish(Mesh3Result& r) { return finish_impl(*impl_, r, impl_->opt.validate); }

Status Constrictor3::finish_impl(Impl& s, Mesh3Result& r, bool validate, bool growth_only) {
  if (!s.ready) return {StatusCode::Internal, "Constrictor3::finish before a successful init"};
  r = Mesh3Result{};
  r.size_bias = s.opt.size_bias;
  r.label_weight = s.opt.label_weight;
  r.ms_delaunay = s.ms_delaunay;
  r.ms_setup = s.ms_setup;
  r.delaunay_tets = s.body.T0;
  r.stages.push_back({Stage3::Hull, s.n_hull, 0});
  const Impl::Growth growth = s.grow_stage(r);
  if (growth == Impl::Growth::Failed && growth_only) return Status::ok();  // (variants3.cpp)
  const bool grown = growth == Impl::Growth::Grown;
  if (!grown) s.constriction_stage(r);
  r.method = grown ? Method3::Grow : Method3::Gamma;
  s.lock_fallback_stage(r);
  r.complete = s.body.n_onb == s.body.n;
  if (!r.complete) r.method = s.hull.stopped ? Method3::Stopped : Method3::Locked;
  if (r.complete && !grown) s.carve_stage(r);
  if (r.complete) s.sculpt_stage(r);
  if (r.complete && !grown) s.refine_stage(r);
  if (r.complete) s.bridge_stage(r);
  s.collect(r);
  if (validate) validate_result(s, r);
  return Status::ok();
}

void Constrictor3::validate_result(Impl& s, Mesh3Result& r) {
  const auto t0 = Clock::now();
  s.body.check_body();
  MeshCheckOptions mo;
  mo.require_all_points = r.complete;
  mo.self_intersections = s.opt.validate_self_intersections;
  mo.any_topology = s.opt.handles;
  MeshCheck mc;
  const Status vs = validate_mesh3(*s.input, r.mesh, &mc, mo);  // on the input's own coordinates
  CONSTRICT_CHECK(vs.is_ok(), "reconstruct3 produced an invalid surface: " + vs.message());
  // The check's volume is exact where the double sum is badly conditioned (check_outward).
  if (mc.volume_exact) r.volume = mc.volume;
  r.validated = true;
  r.ms_validate = ms_since(t0);
}

Status reconstruct3(const PointSet& points, const Constrict3Options& options, Mesh3Result& result,
                    Constrict3Visitor* visitor) {
  Constrictor3 c;
  return Constrictor3::run(c, points, options, result, visitor);
}

std::vector<float> detail::circumball_labels3(const PointSet& points, Delaunay3& dt) {
  // The tetrahedra and their adjacency are lent to a body for the propagation (no copy) and given
  // back.
  Body3 b;
  b.pts = &points;
  b.n = points.size();
  b.tets = std::move(dt.tets);
  b.nbr = std::move(dt.neighbors);
  b.T0 = b.tets.size();
  std::shared_ptr<const Labels3> labels = compute_labels3(b);
  dt.tets = std::move(b.tets);
  dt.neighbors = std::move(b.nbr);
  return labels->label;
}

Status detail::reconstruct3_sharing(const PointSet& points, const Constrict3Options& options, Delaunay3&& dt,
                                    Mesh3Result& result, std::vector<int> part_of) {
  Constrictor3 c;
  c.impl_->shared_dt = std::make_shared<Delaunay3>(std::move(dt));
  if (!part_of.empty()) c.impl_->part_of = std::make_shared<const std::vector<int>>(std::move(part_of));
  return Constrictor3::run(c, points, options, result, nullptr);
}

Status Constrictor3::run(Constrictor3& c, const PointSet& points, const Constrict3Options& options, Mesh3Result& result,
                         Constrict3Visitor* visitor) {
  const std::vector<Constrict3Variant>& cand = options.variants;
  for (const Constrict3Variant& v : cand)
    if (!weights_ok(v.size_bias, v.label_weight))
      return {StatusCode::InvalidArgument, "variants: size_bias and label_weight must be in [0, 100]"};
  if (!weights_ok(options.size_bias, options.label_weight))
    return {StatusCode::InvalidArgument, "size_bias and label_weight must be in [0, 100]"};
  // The size bias and the labels only enter the γ-type keys: min-area-change runs once.
  if (cand.size() < 2 || options.stop_after != SIZE_MAX || options.criterion == Criterion::MinAreaChange) {
    Constrict3Options o = options;
    if (!cand.empty()) {
      o.size_bias = cand[0].size_bias;
      o.label_weight = cand[0].label_weight;
    }
    o.variants.clear();
    if (Status s = c.init(points, o, visitor); !s) return s;
    return c.finish(result);
  }
  return c.run_candidates(points, options, result, visitor);
}

}  // namespace constrict
