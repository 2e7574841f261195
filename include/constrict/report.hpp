// SPDX-License-Identifier: GPL-3.0-or-later
/// @file report.hpp
/// @brief The JSON report of a reconstruction: one writer for the CLI (`--report`), the Python
/// module (`result.report()`) and tools/. Field meanings: docs/cli.md ("Reports").
#pragma once

#include <string>

#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/topology.hpp"

namespace constrict {

/// The library's part of a 3D report, a JSON object: complete, valid, method, fallback_mode,
/// fallback, locked, stuck_points, unplaced_points, stages, removal and cavity counts,
/// body_tetrahedra, non_delaunay_tetrahedra, faces, volume, surface_area, refine, carve, grow,
/// size_bias, label_weight, variants and timings_ms (the library's phases). Callers add their own
/// fields (input, output, read/write times) to the parsed object.
/// @param[in] result the result of reconstruct3()
/// @param[in] options the options it was run with
/// @return the JSON text (compact, keys sorted)
std::string to_json(const Mesh3Result& result, const Constrict3Options& options);

/// The library's part of a 2D report: complete, valid, validation, method, fallback_mode,
/// fallback, locked, stuck_points, stages, removed_simplices, fallback_insertions,
/// fallback_edges, area, perimeter, refine and timings_ms.
std::string to_json(const Polygon2Result& result, const Constrict2Options& options);

/// The library's part of a 2D report with rings (reconstruct_rings2()): the fields of the
/// Polygon2Result report when the rings are the single polygon (else those fields for a ring set:
/// complete, valid, validation, method "rings", area and perimeter summed with signs, timings_ms),
/// plus `"rings": [{"role": "shell"|"hole", "parent": k or -1, "indices": [...], "gap_spacings",
/// "nearest_ring"}, ...]` and `"topology": {"mode", "gap_threshold", "inferred": {"decision",
/// "rings", "shells", "holes", "parts", "parts_polygon", "bad_degree_points", "split_gap_spacings",
/// "min_gap_spacings", "reason", "ring_list"}}` (ring_list: the inferred rings when they differ from "rings"; gaps in
/// local spacings, null for none; with Rings2Options::infer_multi_start false, as in the CLI's single mode, their part
/// polygons come from one start and may run through their points in another order than auto's).
std::string to_json(const Rings2Result& result, const Rings2Options& options);

}  // namespace constrict
