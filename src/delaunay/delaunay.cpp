// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL Delaunay triangulations exported as plain index arrays. This is the only translation unit
// that includes CGAL's triangulation packages (GPL; swappable behind include/constrict/delaunay.hpp).
#include "constrict/delaunay.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <string>
#include <utility>
#include <vector>

namespace constrict {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

using Vb2 = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb2 = CGAL::Triangulation_face_base_with_info_2<int, K>;
using Tds2 = CGAL::Triangulation_data_structure_2<Vb2, Fb2>;
using DT2 = CGAL::Delaunay_triangulation_2<K, Tds2>;

using Vb3 = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Cb3 = CGAL::Triangulation_cell_base_with_info_3<int, K, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Tds3 = CGAL::Triangulation_data_structure_3<Vb3, Cb3>;
using DT3 = CGAL::Delaunay_triangulation_3<K, Tds3>;

Status check_count(const DT2& dt, std::size_t n) {
  if (dt.number_of_vertices() != n)
    return {StatusCode::Duplicate, "Delaunay: " + std::to_string(n - dt.number_of_vertices()) +
                                       " input points coincide with others (remove duplicates first)"};
  if (dt.dimension() < 2) return {StatusCode::Collinear, "Delaunay: all points are collinear"};
  return Status::ok();
}
}  // namespace

Status build_delaunay2(const PointSet& points, Delaunay2& out) {
  if (points.dim != 2) return {StatusCode::InvalidArgument, "build_delaunay2: points are not 2D"};
  const std::size_t n = points.size();
  std::vector<std::pair<K::Point_2, int>> input;
  input.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    input.emplace_back(K::Point_2(points[i][0], points[i][1]), static_cast<int>(i));
  // Range insertion: CGAL's spatial sort (BRIO with a fixed-seed boost::rand48, so the result
  // is deterministic, also for co-circular points) then hinted insertion.
  DT2 dt;
  dt.insert(input.begin(), input.end());
  if (Status s = check_count(dt, n); !s) return s;

  out.n_vertices = n;
  out.triangles.clear();
  out.neighbors.clear();
  out.triangles.reserve(dt.number_of_faces());
  out.neighbors.reserve(dt.number_of_faces());
  int id = 0;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) f->info() = id++;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    std::array<int, 3> tri{}, nb{};
    for (int i = 0; i < 3; ++i) {
      tri[i] = f->vertex(i)->info();
      auto g = f->neighbor(i);
      nb[i] = dt.is_infinite(g) ? -1 : g->info();
    }
    out.triangles.push_back(tri);
    out.neighbors.push_back(nb);
  }
  return Status::ok();
}

Status build_delaunay3(const PointSet& points, Delaunay3& out) {
  if (points.dim != 3) return {StatusCode::InvalidArgument, "build_delaunay3: points are not 3D"};
  const std::size_t n = points.size();
  std::vector<std::pair<K::Point_3, int>> input;
  input.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    input.emplace_back(K::Point_3(points[i][0], points[i][1], points[i][2]), static_cast<int>(i));
  DT3 dt;
  dt.insert(input.begin(), input.end());  // spatial sort (fixed seed) + hinted insertion
  if (dt.number_of_vertices() != n)
    return {StatusCode::Duplicate, "Delaunay: " + std::to_string(n - dt.number_of_vertices()) +
                                       " input points coincide with others (remove duplicates first)"};
  if (dt.dimension() < 3) return {StatusCode::Coplanar, "Delaunay: all points are coplanar"};

  out.n_vertices = n;
  out.tets.clear();
  out.neighbors.clear();
  out.tets.reserve(dt.number_of_finite_cells());
  out.neighbors.reserve(dt.number_of_finite_cells());
  int id = 0;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) c->info() = id++;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    std::array<int, 4> tet{}, nb{};
    for (int i = 0; i < 4; ++i) {
      tet[i] = c->vertex(i)->info();
      auto d = c->neighbor(i);
      nb[i] = dt.is_infinite(d) ? -1 : d->info();
    }
    out.tets.push_back(tet);
    out.neighbors.push_back(nb);
  }
  return Status::ok();
}

}  // namespace constrict
