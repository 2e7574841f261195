// SPDX-License-Identifier: GPL-3.0-or-later
// The connected surfaces of a triangle mesh (triangles joined at their vertices), per vertex:
// shared by mesh_volume() (each surface about its own origin) and the 3D engine's surface count.
#pragma once
#include <cstddef>
#include <vector>

#include "constrict/mesh.hpp"

namespace constrict::detail {

/// For each of the n points, the index of its connected surface in the mesh, numbered in the order
/// of their smallest vertex, or -1 when the point is in no triangle. O(n + F).
std::vector<int> surface_of_vertex(std::size_t n, const TriMesh3& mesh);

}  // namespace constrict::detail
