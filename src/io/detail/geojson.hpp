// SPDX-License-Identifier: GPL-3.0-or-later
// The GeoJSON point reader of read_points() (RFC 7946; rules in constrict/io.hpp).
#pragma once

#include <string>
#include <string_view>

#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {
namespace detail {

/// Reads the Point and MultiPoint positions of a GeoJSON document into @p out (forced_dim 0: the
/// coordinate count of the first position).
/// @return Ok, ParseError ("file: /features/3/geometry: ..." with a JSON pointer, or the JSON
///         syntax error with its line and column) or NonFinite
Status read_geojson_points(std::string_view data, const std::string& name, int forced_dim,
                           PointSet& out);

}  // namespace detail
}  // namespace constrict
