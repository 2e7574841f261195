// SPDX-License-Identifier: GPL-3.0-or-later
// Shortest Voronoi skeleton polyhedron (seed paper §2.7, §6, Fig. 11; O'Rourke, Booth &
// Washington 1987). The growth and the search are in detail/skeleton_growth.hpp; this file
// computes the circumcentres, extracts the surface of the best body and validates it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "constrict/delaunay.hpp"
#include "constrict/predicates.hpp"
#include "constrict/voronoi_skeleton.hpp"
#include "constrict/detail/skeleton_growth.hpp"
#include "core/detail/canonical_order.hpp"
#include "core/detail/tet_faces.hpp"

namespace constrict {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
std::size_t U(int i) { return static_cast<std::size_t>(i); }

using detail::kFaceOut;

// Circumcentre of a tetrahedron (double arithmetic; only ranks dual edge lengths).
std::array<double, 3> circumcentre3(const double* a, const double* b, const double* c, const double* d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  const double u2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  const double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double w2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  const double vw[3] = {v[1] * w[2] - v[2] * w[1], v[2] * w[0] - v[0] * w[2], v[0] * w[1] - v[1] * w[0]};
  const double wu[3] = {w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2], w[0] * u[1] - w[1] * u[0]};
  const double uv[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double det = 2.0 * (u[0] * vw[0] + u[1] * vw[1] + u[2] * vw[2]);
  std::array<double, 3> c3{};
  for (int k = 0; k < 3; ++k) c3[U(k)] = a[k] + (u2 * vw[k] + v2 * wu[k] + w2 * uv[k]) / det;
  return c3;
}

// The search on points already checked and in canonical order (ids = engine ids).
Status skeleton3(const PointSet& points, const VoronoiSkeletonOptions& options, VoronoiSkeleton3Result& result) {
  const auto t0 = Clock::now();
  Delaunay3 dt;
  if (Status st = build_delaunay3(points, dt); !st) return st;
  result.stats.ms_delaunay = ms_since(t0);

  const auto t1 = Clock::now();
  const std::size_t n = points.size(), T = dt.tets.size();
  std::vector<std::array<double, 3>> cc(T);
  for (std::size_t t = 0; t < T; ++t) {
    const auto& v = dt.tets[t];
    cc[t] = circumcentre3(points[U(v[0])], points[U(v[1])], points[U(v[2])], points[U(v[3])]);
  }
  auto& st = result.stats;
  detail::SkeletonBody body = detail::skeleton_best_body<4>(dt.tets, dt.neighbors, cc, n, options, st);

  for (int t : body.added) result.tets.push_back(dt.tets[U(t)]);
  for (int t : body.added)
    for (int i = 0; i < 4; ++i) {
      const int m = dt.neighbors[U(t)][U(i)];
      if (m >= 0 && body.in_body[U(m)]) continue;
      const auto& v = dt.tets[U(t)];
      result.mesh.triangles.push_back({{v[U(kFaceOut[i][0])], v[U(kFaceOut[i][1])], v[U(kFaceOut[i][2])]}});
    }
  result.unplaced_points = std::move(body.unplaced);
  result.complete = result.unplaced_points.empty();
  result.volume = mesh_volume(points, result.mesh);
  if (result.complete && !result.mesh.triangles.empty())  // (exact where the double sum cancels)
    result.volume = signed_volume_checked(points.coords.data(), result.mesh.triangles[0].data(),
                                          result.mesh.triangles.size(), result.volume);
  result.surface_area = mesh_area(points, result.mesh);
  st.ms_grow = ms_since(t1);

  if (options.validate) {
    const auto tv = Clock::now();
    MeshCheckOptions mo;
    mo.require_all_points = result.complete;
    const Status vs = validate_mesh3(points, result.mesh, &result.check, mo);
    result.validated = true;
    st.ms_validate = ms_since(tv);
    CONSTRICT_CHECK(vs.is_ok(), "voronoi_skeleton3 produced an invalid surface: " + vs.message());
  }
  return Status::ok();
}

}  // namespace

// In a canonical order of the points, as voronoi_skeleton2 (its ties decided by ids: on the
// surface points of a 4 x 4 x 4 lattice one file order gave a complete surface, another 55 of 56).
Status voronoi_skeleton3(const PointSet& points, const VoronoiSkeletonOptions& options,
                         VoronoiSkeleton3Result& result) {
  result = VoronoiSkeleton3Result{};
  if (points.dim != 3) return {StatusCode::InvalidArgument, "voronoi_skeleton3: points must be 3D"};
  if (Status st = check_points(points); !st) return st;
  const std::vector<int> order = detail::canonical_order(points);
  if (Status st = skeleton3(detail::permuted(points, order), options, result); !st) return st;
  detail::to_input_ids(order, result.mesh.triangles);
  detail::to_input_ids(order, result.tets);
  detail::to_input_ids(order, result.unplaced_points);
  std::sort(result.unplaced_points.begin(), result.unplaced_points.end());
  return Status::ok();
}

Mesh3Result as_reconstruction(VoronoiSkeleton3Result&& v) {
  Mesh3Result r;
  r.mesh = std::move(v.mesh);
  r.tets = std::move(v.tets);
  r.complete = v.complete;
  r.validated = v.validated && v.complete;
  r.unplaced_points = std::move(v.unplaced_points);
  r.method = v.complete ? Method3::VoronoiSkeleton : Method3::Incomplete;
  r.volume = v.volume;
  r.surface_area = v.surface_area;
  r.ms_delaunay = v.stats.ms_delaunay;
  r.ms_constrict = v.stats.ms_grow;
  return r;
}

}  // namespace constrict
