// SPDX-License-Identifier: GPL-3.0-or-later
// The connected surfaces of a triangle mesh (triangles joined at their vertices), per vertex:
// shared by mesh_volume() (each surface about its own origin), the 3D engine's surface count and
// the mesh check (which has its own union-find of the faces already).
#pragma once
#include <cstddef>
#include <vector>

#include "constrict/mesh.hpp"
#include "constrict/points.hpp"
#include "constrict/predicates.hpp"

namespace constrict::detail {

/// For each of the n points, the index of its connected surface in the mesh, numbered in the order
/// of their smallest vertex, or -1 when the point is in no triangle. O(n + F).
std::vector<int> surface_of_vertex(std::size_t n, const TriMesh3& mesh);

/// The same numbering from a union-find the caller has built over the faces' vertices: root(v)
/// is the representative of v's surface.
template <class Root>
std::vector<int> number_surfaces(std::size_t n, const TriMesh3& mesh, Root&& root) {
  std::vector<int> comp(n, -1), index(n, -1);
  for (const auto& t : mesh.triangles)
    for (int v : t) comp[static_cast<std::size_t>(v)] = 0;  // (in a triangle)
  int count = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (comp[v] < 0) continue;
    const auto r = static_cast<std::size_t>(root(static_cast<int>(v)));
    if (index[r] < 0) index[r] = count++;
    comp[v] = index[r];
  }
  return comp;
}

/// mesh_volume() with the surfaces of surface_of_vertex() given (the same bits); with estimate,
/// also signed_volume_estimate() of the same triangles in the same pass (the same bits).
double mesh_volume_of_surfaces(const PointSet& pts, const TriMesh3& mesh, const std::vector<int>& comp,
                               VolumeEstimate* estimate = nullptr);

}  // namespace constrict::detail
