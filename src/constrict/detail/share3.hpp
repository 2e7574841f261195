// SPDX-License-Identifier: GPL-3.0-or-later
// Sharing the Delaunay tetrahedralization with the 3D engine (the auto topology,
// src/topology/surfaces3.cpp, builds it for its own inference first).
#pragma once

#include <array>
#include <vector>

#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"

namespace constrict::detail {

// reconstruct3() on points that are already in canonical order (canonical_order(points) is the
// identity: the engine ids are the indices) with dt = build_delaunay3(points): the engine uses it
// instead of building its own when it runs the growth (the default options); the result is the
// same as reconstruct3()'s, bit for bit. dt is consumed. part_of (per point, or empty): the parts
// of the gap rule, which lets the handle stage seal the cavities that separate them.
Status reconstruct3_sharing(const PointSet& points, const Constrict3Options& options, Delaunay3&& dt, Mesh3Result& result,
                            std::vector<int> part_of = {});

// The engine's circumball labels of dt's tetrahedra (+confidence outside, -confidence inside;
// docs/reconstruction-3d.md §4.5), as the growth reads them: the auto topology's test of parts
// that nearly touch (docs/topology.md). dt is unchanged when this returns (its arrays are lent).
std::vector<float> circumball_labels3(const PointSet& points, Delaunay3& dt);

// A tetrahedron's bridge ratio: its longest edge over the largest spacing of its four vertices
// (hull3.cpp). The handle stage measures a cavity's width by it, the auto topology a void's.
double bridge_ratio3(const PointSet& pts, const std::vector<double>& spacing, const std::array<int, 4>& tet);

}  // namespace constrict::detail
