// SPDX-License-Identifier: GPL-3.0-or-later
// Post-pass of the 2D reconstruction: length-decreasing local search (2-opt and Or-opt) that keeps
// the polygon simple at every step. See docs/reconstruction-2d.md §"Refinement".
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <functional>
#include <vector>

#include "constrict/constrict.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/points.hpp"

namespace constrict::detail {

/// Improves a simple polygon through all points by 2-opt and Or-opt moves, then (deep phase, in
/// the region of those) Lin–Kernighan k-opt (k <= 6) and double-bridge moves, built from Delaunay
/// neighbours (candidate lists: the Delaunay 1-ring of each vertex, by distance). A move
/// is applied only if it shortens the polygon by more than a relative 1e-9 of the replaced edges
/// and the resulting polygon is simple (exact orient2 tests against the edges near the new ones).
/// @param[in] points 2D input
/// @param[in] dt the Delaunay triangulation of all points
/// @param[in,out] polygon a simple polygon through all points; stays simple and through all points
/// @param[in] work_budget maximal number of array elements moved by reversals and segment copies
///   (bounds the worst case)
/// @param[in] order optional: the ids of points, dt and polygon are a relabelling and order[v] is
///   the stable id of v; every tie and the start of the output polygon then follow order[], so
///   the result is the relabelling of what the stable ids give (null: the ids are the stable ids)
/// @param[in] adjacency optional: gives dt's vertex adjacency as CSR (the neighbours of v are
///   nb[off[v]] .. nb[off[v + 1] - 1], each once, in any order), asked for only when the search
///   runs; the candidate lists are then gathered from it instead of two passes over dt's triangles,
///   and dt.neighbors is not read after it returned (the caller may release them there)
/// @param[in] pretest false: skip the O(N) test of whether any move can apply (the caller expects
///   moves, e.g. after fallback insertions); the result is the same either way
/// @note O(N·deg) per sweep plus the reversal work (≤ work_budget) plus the deep search (≤ 256 N +
///   2^20 Lin–Kernighan nodes and 16 N + 2^20 double-bridge nodes). Deterministic.
/// @param[out] non_delaunay optional: when the search ran, set to the edges of the result that are
///   not Delaunay edges (pairs of polygon ids, in no particular order); otherwise untouched
/// @param[in] multi_start false: one start also on small inputs (Constrict2Options::refine_multi_start)
/// @param[in] cancel optional: when another thread sets it, the search stops at the next vertex it
///   visits (the polygon stays simple and through all points; the caller drops it)
/// @return whether the search ran (false: the polygon was only normalised, e.g. the pretest found
///   no possible move)
struct Adjacency2 {
  const int* off = nullptr;
  const int* nb = nullptr;
  std::function<void()> release;  ///< optional: called once the lists are no longer read
};
bool refine_polygon2(const PointSet& points, const Delaunay2& dt, std::vector<int>& polygon, std::size_t work_budget,
                     Refine2Stats& stats, const std::vector<int>* order = nullptr,
                     const std::function<Adjacency2()>& adjacency = {}, bool pretest = true,
                     std::vector<std::array<int, 2>>* non_delaunay = nullptr, bool multi_start = true,
                     const std::atomic<bool>* cancel = nullptr);

}  // namespace constrict::detail
