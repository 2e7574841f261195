// SPDX-License-Identifier: GPL-3.0-or-later
// Shortest Voronoi skeleton polygon (seed paper §2.7, §6; O'Rourke, Booth & Washington 1987).
// The growth and the search are in detail/skeleton_growth.hpp; this file computes the circumcentres,
// extracts the polygon of the best body and validates it. Open choices: docs/comparison-methods.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "constrict/delaunay.hpp"
#include "constrict/points.hpp"
#include "constrict/voronoi_skeleton.hpp"
#include "constrict/detail/skeleton_growth.hpp"
#include "core/detail/canonical_order.hpp"
#include "core/detail/ring_measure.hpp"

namespace constrict {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
std::size_t U(int i) { return static_cast<std::size_t>(i); }

// Circumcentre of a triangle (double arithmetic; only ranks dual edge lengths).
std::array<double, 2> circumcentre2(const double* a, const double* b, const double* c) {
  const double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
  const double d = 2.0 * (bx * cy - by * cx);
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  return {{a[0] + (cy * b2 - by * c2) / d, a[1] + (bx * c2 - cx * b2) / d}};
}

// The search on points already checked and in canonical order (ids = engine ids).
Status skeleton2(const PointSet& points, const VoronoiSkeletonOptions& options, VoronoiSkeleton2Result& result) {
  const auto t0 = Clock::now();
  Delaunay2 dt;
  if (Status st = build_delaunay2(points, dt); !st) return st;
  result.stats.ms_delaunay = ms_since(t0);

  const auto t1 = Clock::now();
  const std::size_t n = points.size(), T = dt.triangles.size();
  std::vector<std::array<double, 2>> cc(T);
  for (std::size_t t = 0; t < T; ++t) {
    const auto& v = dt.triangles[t];
    cc[t] = circumcentre2(points[U(v[0])], points[U(v[1])], points[U(v[2])]);
  }
  auto& st = result.stats;
  detail::SkeletonBody body = detail::skeleton_best_body<3>(dt.triangles, dt.neighbors, cc, n, options, st);
  const std::vector<char>& reached = body.reached;

  // The polygon: free edges of the body, each CCW triangle's edge a->b has the body on its left.
  for (int t : body.added) result.triangles.push_back(dt.triangles[U(t)]);
  std::vector<int> nxt(n, -1);
  for (int t : body.added)
    for (int i = 0; i < 3; ++i) {
      const int m = dt.neighbors[U(t)][U(i)];
      if (m >= 0 && body.in_body[U(m)]) continue;
      const auto& v = dt.triangles[U(t)];
      nxt[U(v[U((i + 1) % 3)])] = v[U((i + 2) % 3)];
    }
  int start = -1;
  for (std::size_t v = 0; v < n && start < 0; ++v)
    if (reached[v]) start = static_cast<int>(v);
  for (int v = start; v >= 0;) {
    result.boundary.push_back(v);
    v = nxt[U(v)];
    if (v == start || result.boundary.size() > n) break;
  }
  result.unplaced_points = std::move(body.unplaced);
  result.complete = result.unplaced_points.empty();
  const int e = rescale_exponent(max_coordinate_exponent(points));
  detail::add_ring_measure(points, result.boundary, e, result.area, result.perimeter);
  result.area = std::ldexp(result.area, 2 * e);
  result.perimeter = std::ldexp(result.perimeter, e);
  st.ms_grow = ms_since(t1);

  if (options.validate) {
    const auto tv = Clock::now();
    Status vs;
    if (result.complete) {
      vs = validate_polygon_in_triangulation(points, result.boundary, dt.triangles, &result.check);
    } else {
      // Over the points reached: the polygon must still be simple and counter-clockwise.
      PointSet sub;
      sub.dim = 2;
      std::vector<int> id(n, -1), poly;
      for (std::size_t v = 0; v < n; ++v)
        if (reached[v]) {
          id[v] = static_cast<int>(sub.size());
          sub.coords.push_back(points[v][0]);
          sub.coords.push_back(points[v][1]);
        }
      for (int v : result.boundary) poly.push_back(id[U(v)]);
      vs = validate_polygon(sub, poly, &result.check);
    }
    result.validated = true;
    st.ms_validate = ms_since(tv);
    CONSTRICT_CHECK(vs.is_ok(), "voronoi_skeleton2 produced an invalid polygon: " + vs.message());
  }
  return Status::ok();
}

}  // namespace

// The search runs on the points in a canonical order of their coordinates
// (core/detail/canonical_order.hpp): its ties (growth fronts of equal dual length, the seed order)
// are broken by ids, and on lattices and co-circular points they decide the polygon, even whether
// it is complete; in input ids the same points in another file order gave another one.
Status voronoi_skeleton2(const PointSet& points, const VoronoiSkeletonOptions& options,
                         VoronoiSkeleton2Result& result) {
  result = VoronoiSkeleton2Result{};
  if (points.dim != 2) return {StatusCode::InvalidArgument, "voronoi_skeleton2: points must be 2D"};
  if (Status st = check_points(points); !st) return st;
  const std::vector<int> order = detail::canonical_order(points);
  if (Status st = skeleton2(detail::permuted(points, order), options, result); !st) return st;
  detail::to_input_ids(order, result.boundary);
  std::rotate(result.boundary.begin(), std::min_element(result.boundary.begin(), result.boundary.end()),
              result.boundary.end());
  detail::to_input_ids(order, result.triangles);
  detail::to_input_ids(order, result.unplaced_points);
  std::sort(result.unplaced_points.begin(), result.unplaced_points.end());
  return Status::ok();
}

Polygon2Result as_reconstruction(VoronoiSkeleton2Result&& v) {
  Polygon2Result r;
  r.boundary = std::move(v.boundary);
  r.complete = v.complete;
  r.stuck_points = std::move(v.unplaced_points);
  r.method = v.complete ? "voronoi-skeleton" : "incomplete";
  r.validated = v.validated && v.complete;
  r.check = v.check;
  r.area = v.area;
  r.perimeter = v.perimeter;
  r.ms_delaunay = v.stats.ms_delaunay;
  r.ms_constrict = v.stats.ms_grow;
  r.ms_validate = v.stats.ms_validate;
  return r;
}

}  // namespace constrict
