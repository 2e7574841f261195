// SPDX-License-Identifier: GPL-3.0-or-later
// The text column reader (XYZ, CSV, TXT) of read_points(): rules in constrict/io.hpp.
#pragma once

#include <string>
#include <string_view>

#include "constrict/io.hpp"
#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {
namespace detail {

/// Reads text columns into @p out (dim 2 or 3; forced_dim 0: from the first data line or from
/// the selected columns).
/// @return Ok, InvalidArgument (@p columns does not fit the file), ParseError or NonFinite
///         ("file:LINE: ...")
Status read_text_points(std::string_view data, const std::string& name, int forced_dim,
                        const ColumnSelection& columns, PointSet& out);

}  // namespace detail
}  // namespace constrict
