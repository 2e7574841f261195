// SPDX-License-Identifier: GPL-3.0-or-later
// 2D γ-constriction of the Delaunay triangulation (seed paper §4.1, §5; spec §3.1-3.5), the ladder
// of local fallbacks after a lock (paper §4.3; spec §3.6, §3.7; their steps are in fallback2.cpp)
// and a final repair. See docs/reconstruction-2d.md for the algorithm and its guarantees.
#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include "constrict/detail/engine2.hpp"
#include "constrict/detail/refine2.hpp"
#include "constrict/detail/share2.hpp"
#include "constrict/memory.hpp"
#include "constrict/validate.hpp"
#include "core/detail/canonical_order.hpp"
#include "core/detail/check_points.hpp"
#include "core/detail/ordered_pack.hpp"
#include "cgal/detail/delaunay_local.hpp"

namespace constrict {
using engine2::Clock;  // (the engine's names: detail/engine2.hpp)
using engine2::ms_since;

// ---- the Delaunay stage (spec §3.5) ------------------------------------------------------------
Status Constrictor2::Impl::init(const PointSet& points) {
  pts = &rpts;
  visitor_triangles = visitor == nullptr || visitor->wants_triangles();
  if (points.dim != 2) return {StatusCode::InvalidArgument, "reconstruct2: points must be 2D"};
  // Duplicates are found by the triangulation (fewer vertices than points); check_points then
  // names them.
  Status st = detail::check_points_deferred(points);
  if (!st) return st;
  const auto t0 = Clock::now();
  n = points.size();
  // Far from 1 in magnitude, the double parts (apex values, grid cells, search radii) would
  // underflow or overflow: work on a copy scaled by a power of two when that is exact (it
  // changes no predicate, so the polygon is the one of the input at any scale); otherwise keep
  // the input's coordinates (the grid and the searches are scale free, the keys may degrade).
  const PointSet* build_from = &points;
  PointSet scaled;
  if (const int e = max_coordinate_exponent(points); e > kRescaleExponent || e < -kRescaleExponent)
    if (exact_power_of_two_scale(points, scaled, scale_exp).is_ok()) build_from = &scaled;
  st = detail::build_delaunay2_ranked(*build_from, dt, rpts, gid);
  if (st.code() == StatusCode::Duplicate) return check_points(points);
  if (!st) return st;
  ms_delaunay = ms_since(t0);
  const std::size_t nt = dt.triangles.size();
  // The state arrays are made once CGAL's triangulation is gone (beside it, they were the
  // run's peak memory), on both cores.
  tbb::parallel_invoke([&] { alive.assign(nt, 1); }, [&] { ver.assign(nt, 0); },
                       [&] {
                         onb.assign(n, 0);
                         nxt.assign(n, -1);
                         prv.assign(n, -1);
                       });
  // Convex hull: DT edges without a neighbour; collinear hull points are hull vertices. The
  // triangles with such an edge, in triangle order, found on both cores.
  const std::vector<std::uint32_t> hull = detail::ordered_pack<std::uint32_t>(nt, [&](std::size_t t, auto&& push) {
    const auto& nb = dt.neighbors[t];
    if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0) push(static_cast<std::uint32_t>(t));
  });
  for (const std::uint32_t t : hull)
    for (int i = 0; i < 3; ++i)
      if (dt.neighbors[t][U(i)] < 0) {
        const int a = dt.triangles[t][U((i + 1) % 3)], b = dt.triangles[t][U((i + 2) % 3)];
        nxt[U(a)] = b;
        prv[U(b)] = a;
        if (!onb[U(a)]) {
          onb[U(a)] = 1;
          ++n_onb;
        }
        if (!onb[U(b)]) {
          onb[U(b)] = 1;
          ++n_onb;
        }
      }
  for (const std::uint32_t t : hull)
    for (int i = 0; i < 3; ++i)
      if (dt.neighbors[t][U(i)] < 0) push_triangle(static_cast<int>(t));
  ready = true;
  return Status::ok();
}

// One removal (or the lock); the caller keeps the time (one clock read per removal would be
// a tenth of the constriction).
bool Constrictor2::Impl::step_untimed() {
  if (!ready || n_onb == n || locked || stopped) return false;
  if (removed >= opt.stop_after) {
    stopped = true;
    return false;
  }
  while (!heap.empty()) {
    const TriEntry e = heap.top();
    heap.pop();
    if (!heap.empty()) prefetch_triangle(heap.top().t);
    const int t = static_cast<int>(e.t);
    if ((e.version_edge >> 2) != (ver[U(t)] & 0x3fffffffu) || removable_edge(t) < 0) continue;  // stale (lazy deletion)
    const auto& tr = dt.triangles[U(t)];
    const unsigned i = e.version_edge & 3u;
    const int y = tr[i], a = tr[(i + 1) % 3], b = tr[(i + 2) % 3];
    alive[U(t)] = 0;
    ++ver[U(t)];
    splice_boundary(a, y, b);
    ++removed;
    emit(Constrict2Event::Kind::RemoveTriangle, a, b, y, e.key, "gamma");
    for (int j = 0; j < 3; ++j) {
      const int nb = dt.neighbors[U(t)][U(j)];
      if (nb >= 0 && alive[U(nb)]) push_triangle(nb);
    }
    return n_onb < n;
  }
  locked = true;
  emit(Constrict2Event::Kind::Lock, -1, -1, -1, 0, "gamma");
  return false;
}

bool Constrictor2::Impl::step() {
  const auto t0 = Clock::now();
  const bool more = step_untimed();
  ms_constrict += ms_since(t0);
  return more;
}

void Constrictor2::Impl::run_all() {
  const auto t0 = Clock::now();
  // The constriction runs on one core. Meanwhile the second one builds the Delaunay adjacency,
  // which a lock's fallback reads first and the refinement reads too: it reads only the
  // triangles and their neighbours, which the constriction does not change, and it is the same
  // whenever it is built. (Without a lock and a refinement it is not needed: a core's otherwise
  // idle time. The points' grid was built here too and saved about 30 ms more on the 10^6
  // square, but its arrays, allocated on a TBB thread, raised the noisy curve's peak by 4 MB.)
  const bool beside = ready && !locked && !stopped && n_onb < n && removed < opt.stop_after && !adj_ready &&
                      (opt.fallback != Fallback::None || opt.refine != Refine2::None);
  tbb::task_group side;
  if (beside) side.run([this] { build_adjacency(); });
  try {
    // (A cancel is looked at every 4096 removals: a relaxed load, and the run stops within
    // about a millisecond.)
    for (std::size_t k = 1; step_untimed(); ++k)
      if ((k & 4095) == 0 && cancelled()) break;
  } catch (...) {
    // Wait for the task (not ~task_group, which would cancel the adjacency's sorts midway),
    // and report the constriction's exception rather than the task's.
    try {
      side.wait();
    } catch (...) {}
    throw;
  }
  side.wait();  // (counted in the constriction's time when the adjacency takes longer)
  ms_constrict += ms_since(t0);
}

// ---- the ladder (finish) and the results -------------------------------------------------------
// The polygon in ranked ids, from the boundary vertex with the smallest input id.
std::vector<int> Constrictor2::Impl::boundary_list() const {
  std::vector<int> out;
  int s = -1;
  for (std::size_t v = 0; v < n; ++v)
    if (onb[v] && (s < 0 || gid[v] < gid[U(s)])) s = static_cast<int>(v);
  if (s < 0) return out;
  int v = s;
  do {
    out.push_back(v);
    v = nxt[U(v)];
  } while (v != s && out.size() <= n);
  return out;
}

Status Constrictor2::Impl::finish(Polygon2Result& r) {
  if (!ready) return {StatusCode::Internal, "Constrictor2::finish called without a successful init"};
  if (finished) {
    r = *finished;
    return Status::ok();
  }
  const Status st = finish_once(r);
  if (st) finished = std::make_unique<Polygon2Result>(r);
  return st;
}

Status Constrictor2::Impl::finish_once(Polygon2Result& r) {
  run_all();
  if (cancelled()) return detail::cancelled_status();
  r = Polygon2Result{};
  r.removed_simplices = removed;
  r.locked_at_gamma0 = locked;
  r.stuck_points = inside_input_ids();
  r.stages.push_back({"gamma", removed});
  r.method = "gamma";
  const auto t0 = Clock::now();
  if (stopped && n_onb < n) {
    r.method = "stopped";
  } else if (locked && opt.fallback == Fallback::None) {
    r.method = "locked";
  } else if (locked) {
    build_fallback();
    auto run = [&](Graph g, double g0, int k, const std::string& name) {
      if (n_onb == n || cancelled()) return;
      const std::size_t placed = local_constrict(g, g0, k, name);
      r.stages.push_back({name, placed, stage_candidates});
      r.fallback_insertions += placed;
      if (placed > 0) r.method = name;
    };
    if (opt.fallback == Fallback::Auto || opt.fallback == Fallback::Gamma0)
      for (double g0 : opt.gamma0_schedule) {
        if (!(g0 < 0 && g0 >= -1)) continue;
        char buf[32];
        std::snprintf(buf, sizeof buf, "gamma0=%g", g0);
        run(Graph::Gamma0, g0, 2, buf);
      }
    if ((opt.fallback == Fallback::Auto || opt.fallback == Fallback::Degree4) && n_onb < n && !cancelled()) {
      augment_degree4();
      run(Graph::Degree4, 0, 2, "degree4");
    }
    if (opt.fallback == Fallback::Auto || opt.repair) {
      for (int k = 2; n_onb < n && !cancelled(); k *= 2) {
        run(Graph::Complete, 0, k, "repair");
        if (static_cast<std::size_t>(k) > n) break;
      }
      if (n_onb < n && !cancelled()) {
        const std::size_t placed = n - n_onb;
        star_polygon();
        r.stages.push_back({"star", placed});
        r.fallback_insertions += placed;
        r.method = "star";
      }
    }
  }
  if (cancelled()) return detail::cancelled_status();
  r.ms_fallback = ms_since(t0);
  r.complete = n_onb == n;
  std::vector<int> poly = boundary_list();  // ranked ids until the end
  release_stepping_state();
  if (fb_ready) detail::return_free_memory();  // (the fallback's threads allocated: memory.hpp)
  bool refined = false;                        // the refinement's search ran
  std::vector<std::array<int, 2>> non_dt;      // the polygon's non-Delaunay edges (ranked ids)
  r.ms_delaunay = ms_delaunay;
  r.ms_constrict = ms_constrict;
  if (r.complete && opt.refine == Refine2::LocalSearch) {
    emit(Constrict2Event::Kind::StageBegin, -1, -1, -1, 0, "refine");  // (progress: the refinement's seconds)
    const auto tr = Clock::now();
    Refine2Stats rs;
    // The refinement copies the adjacency into its own lists, and says which of its result's
    // edges are not Delaunay edges: the engine's adjacency and the triangles' neighbours (the
    // check below reads only the triangles) are freed before the refinement's arrays grow.
    refined = detail::refine_polygon2(
        *pts, dt, poly, opt.refine_work_per_point * n, rs, &gid,
        [&] {
          build_adjacency();
          decltype(dt.neighbors)().swap(dt.neighbors);
          return detail::Adjacency2{adj_off.data(), adj.data(), [this] {
                                      std::vector<int>().swap(adj_off);
                                      std::vector<int>().swap(adj);
                                      adj_ready = false;
                                    }};
        },
        r.fallback_insertions == 0,  // after insertions (non-Delaunay edges) moves are the rule
        &non_dt, opt.refine_multi_start, cancel);
    if (cancelled()) return detail::cancelled_status();
    r.refine_moves = rs.moves_2opt + rs.moves_oropt + rs.moves_deep;
    r.refine_budget_hit = rs.budget_hit;
    r.perimeter_before_refine = rs.length_before;
    r.stages.push_back({"refine", 0});
    r.ms_refine = ms_since(tr);
  }
  // The polygon's non-Delaunay edges: the refinement's list when its search ran, else (only
  // after fallback insertions can there be any) from the adjacency.
  const std::size_t m = poly.size();
  if (!refined && r.method != "gamma") {
    build_adjacency();
    for (std::size_t i = 0; i < m; ++i)
      if (!is_dt_edge(poly[i], poly[(i + 1) % m])) non_dt.push_back({{poly[i], poly[(i + 1) % m]}});
  }
  for (const auto& e : non_dt) r.fallback_edges.push_back({{std::min(G(e[0]), G(e[1])), std::max(G(e[0]), G(e[1]))}});
  {
    // Each edge's terms on both cores, then summed in polygon order (the same doubles as one
    // sequential loop). The area's terms (a - o) x (b - a) about the first vertex o: as a x b about
    // the origin, a polygon far from it cancels (a unit circle at 10^12: the area came out wrong in
    // its first digit).
    std::vector<std::array<double, 2>> term(m);
    const double* o = P(poly[0]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 16384), [&](const tbb::blocked_range<std::size_t>& rg) {
      for (std::size_t i = rg.begin(); i != rg.end(); ++i) {
        const double* pa = P(poly[i]);
        const double* pb = P(poly[i + 1 == m ? 0 : i + 1]);
        const double ax = pa[0] - o[0], ay = pa[1] - o[1], ux = pb[0] - pa[0], uy = pb[1] - pa[1];
        term[i] = {{0.5 * (ax * uy - ay * ux), std::hypot(ux, uy)}};
      }
    });
    for (const auto& t : term) {
      r.area += t[0];
      r.perimeter += t[1];
    }
  }
  r.area = std::ldexp(r.area, 2 * scale_exp);
  r.perimeter = std::ldexp(r.perimeter, scale_exp);
  r.perimeter_before_refine = std::ldexp(r.perimeter_before_refine, scale_exp);
  if (r.perimeter_before_refine == 0) r.perimeter_before_refine = r.perimeter;
  r.boundary.resize(m);
  for (std::size_t i = 0; i < m; ++i) r.boundary[i] = G(poly[i]);
  if (opt.validate) {
    const auto tv = Clock::now();
    // On the ranked points: a scaled run's coordinates are the input's times an exact power of
    // two, which changes no orientation, so the verdict is the input's.
    Status vs = validate_polygon_in_triangulation(*pts, poly, dt.triangles, &r.check);
    if (!vs) {
      // The diagnostics name points and positions: redo the check in input ids and coordinates.
      std::vector<std::array<int, 3>> tris(dt.triangles.size());
      for (std::size_t t = 0; t < tris.size(); ++t)
        for (int k = 0; k < 3; ++k) tris[t][U(k)] = G(dt.triangles[t][U(k)]);
      vs = validate_polygon_in_triangulation(input_points(), r.boundary, tris, &r.check);
    }
    r.validated = true;
    r.ms_validate = ms_since(tv);
    CONSTRICT_CHECK(vs.is_ok() || !r.complete, "reconstruct2 produced an invalid polygon: " + vs.message());
  }
  // The adjacency (built beside the constriction, or by the fallback) is not read after this.
  std::vector<int>().swap(adj_off);
  std::vector<int>().swap(adj);
  adj_ready = false;
  return Status::ok();
}

// What the constriction and the fallback kept per triangle and per boundary edge is dead once
// the polygon is complete: freed before the refinement allocates its own arrays, so that the
// two do not add up (the peak of a 10^6 run). The boundary (nxt, prv, onb) stays for
// boundary() and inside_points(); a second finish() returns the first result.
void Constrictor2::Impl::release_stepping_state() {
  heap = TriHeap{TriEntryLess{&ties}};
  std::vector<std::array<int, 3>>().swap(ties.sorted);
  std::vector<char>().swap(alive);
  std::vector<unsigned>().swap(ver);
  grid = Grid{};
  std::vector<BEdge>().swap(bedges);
  std::vector<int>().swap(out_edge);
  std::vector<unsigned>().swap(mark);
  std::vector<int>().swap(vt_off);
  std::vector<int>().swap(vt);
  decltype(delta_cache)().swap(delta_cache);
  decltype(aug)().swap(aug);
  shared_caches = SideCaches{};
  fresh_caches.clear();
}

// The engine's input again (input ids, unscaled), from the ranked points: init's caller need
// not keep its copy alive.
PointSet Constrictor2::Impl::input_points() const {
  PointSet in;
  in.coords.resize(2 * n);
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 2; ++k) in.coords[2 * U(gid[v]) + U(k)] = std::ldexp(P(static_cast<int>(v))[k], scale_exp);
  return in;
}

std::vector<int> Constrictor2::Impl::inside_input_ids() const {
  std::vector<int> out;
  for (std::size_t v = 0; v < n; ++v)
    if (!onb[v]) out.push_back(gid[v]);
  std::sort(out.begin(), out.end());
  return out;
}

// The engine runs on the points in a canonical order of their coordinates
// (core/detail/canonical_order.hpp), so that the same points in any file order give the same
// polygon: every tie the engine breaks "by id" is then decided by the coordinates. The results and
// the visitor's events are mapped back to input ids here.
struct Constrictor2::Canonical {
  const PointSet* input = nullptr;
  std::vector<int> order;  // engine id k = input point order[k]
  PointSet points;         // the input in that order
  struct IdMap final : Constrict2Visitor {
    Constrict2Visitor* inner = nullptr;
    const std::vector<int>* order = nullptr;
    Constrict2Event mapped;  // reused: its stage name is copied only when it changes
    bool wants_triangles() const override { return inner->wants_triangles(); }
    void on_event(const Constrict2Event& e) override {
      mapped.kind = e.kind;
      mapped.criterion = e.criterion;
      for (std::size_t k = 0; k < 3; ++k) {
        const int v = e.triangle[k];
        mapped.triangle[k] = v >= 0 ? (*order)[static_cast<std::size_t>(v)] : v;
      }
      if (mapped.stage != e.stage) mapped.stage = e.stage;
      inner->on_event(mapped);
    }
  } id_map;
  int to_input(int v) const { return v < 0 ? v : order[static_cast<std::size_t>(v)]; }
  std::vector<int> to_input_sorted(std::vector<int> ids) const {
    for (int& v : ids) v = to_input(v);
    std::sort(ids.begin(), ids.end());
    return ids;
  }
  // A polygon in input ids, started at its smallest input id (the orientation kept).
  std::vector<int> to_input_polygon(std::vector<int> poly) const {
    for (int& v : poly) v = to_input(v);
    std::rotate(poly.begin(), std::min_element(poly.begin(), poly.end()), poly.end());
    return poly;
  }
};

Constrictor2::Constrictor2() : impl_(new Impl) {}
Constrictor2::~Constrictor2() = default;

Status Constrictor2::init(const PointSet& points, const Constrict2Options& options, Constrict2Visitor* visitor) {
  impl_.reset(new Impl);
  impl_->opt = options;
  impl_->visitor = visitor;
  canon_.reset();
  // Non-finite or non-2D input: no canonical order (it needs a total order of the coordinates).
  if (points.dim != 2 || !detail::check_finite(points, "reconstruct2")) return impl_->init(points);
  canon_ = std::make_unique<Canonical>();
  canon_->input = &points;
  canon_->order = detail::canonical_order(points);
  canon_->points = detail::permuted(points, canon_->order);
  canon_->id_map.inner = visitor;
  canon_->id_map.order = &canon_->order;
  impl_->visitor = visitor ? &canon_->id_map : nullptr;
  const Status st = impl_->init(canon_->points);
  if (st) {
    PointSet().coords.swap(canon_->points.coords);  // the engine has its own (ranked) copy
    return st;
  }
  // The error in the input's own indices (duplicates, ...).
  if (Status in = check_points(points); !in) return in;
  return st;
}
bool Constrictor2::step() { return impl_->step(); }
std::vector<int> Constrictor2::boundary() const {
  std::vector<int> b = impl_->boundary_list();
  for (int& v : b) v = impl_->G(v);
  if (!canon_) return b;
  for (int& v : b) v = canon_->to_input(v);
  return b;
}
std::vector<int> Constrictor2::inside_points() const {
  return canon_ ? canon_->to_input_sorted(impl_->inside_input_ids()) : impl_->inside_input_ids();
}
Status Constrictor2::finish(Polygon2Result& result) {
  const Status st = impl_->finish(result);
  if (!st || !canon_) return st;
  const Canonical& c = *canon_;
  result.boundary = c.to_input_polygon(std::move(result.boundary));
  result.stuck_points = c.to_input_sorted(std::move(result.stuck_points));
  for (auto& e : result.fallback_edges) {
    e = {{c.to_input(e[0]), c.to_input(e[1])}};
    if (e[0] > e[1]) std::swap(e[0], e[1]);
  }
  std::sort(result.fallback_edges.begin(), result.fallback_edges.end());
  if (!result.check.reason.empty()) {  // (positions and ids of a failed check: on the input again)
    PolygonCheck chk;
    (void)validate_polygon(*c.input, result.boundary, &chk);
    result.check = chk;
  }
  return st;
}

struct detail::Constrictor2Access {
  static void set_cancel(Constrictor2& c, const std::atomic<bool>* cancel) { c.impl_->cancel = cancel; }
  static void share(const Constrictor2& c, const detail::Triangulation2Hook& hook) {
    const Constrictor2::Impl& e = *c.impl_;
    std::vector<int> to_input(e.n);
    for (std::size_t v = 0; v < e.n; ++v) to_input[v] = c.canon_ ? c.canon_->to_input(e.gid[v]) : e.gid[v];
    hook(e.rpts, e.dt, to_input);
  }
};

Status detail::reconstruct2_sharing(const PointSet& points, const Constrict2Options& options, Polygon2Result& result,
                                    Constrict2Visitor* visitor, const Triangulation2Hook& hook,
                                    const std::atomic<bool>* cancel) {
  result = Polygon2Result{};
  Constrictor2 c;
  Status st = c.init(points, options, visitor);
  if (!st) return st;
  Constrictor2Access::set_cancel(c, cancel);
  if (hook) Constrictor2Access::share(c, hook);
  st = c.finish(result);
  if (!st) result = Polygon2Result{};  // (cancelled: no partial result)
  return st;
}

Status reconstruct2(const PointSet& points, const Constrict2Options& options, Polygon2Result& result,
                    Constrict2Visitor* visitor) {
  result = Polygon2Result{};
  Constrictor2 c;
  Status st = c.init(points, options, visitor);
  if (!st) return st;
  return c.finish(result);  // runs the constriction to its end
}

}  // namespace constrict
