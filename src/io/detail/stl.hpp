// SPDX-License-Identifier: GPL-3.0-or-later
// The one STL reader (binary and ASCII), used by read_points() and read_mesh(). STL stores every
// facet with its own corner coordinates; corners with identical coordinates (exact comparison)
// are one vertex, numbered in first occurrence order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/status.hpp"

namespace constrict {
namespace detail {

/// Receives the facets of an STL file as they are read.
class StlFacetSink {
 public:
  /// @param[in] ids 0-based vertex ids of the facet's corners (3 or more, ASCII may have more)
  virtual void facet(const std::vector<std::int64_t>& ids) = 0;

 protected:
  ~StlFacetSink() = default;
};

/// Reads an STL file: a binary file is recognised by its size (84 + 50 * facet count bytes),
/// anything else must be ASCII ("solid ... facet ... vertex x y z ... endloop ...").
/// @param[out] coords x y z of each distinct corner, first occurrence order (appended)
/// @param[in] facets optional receiver of the facets
/// @param[out] corners facet corners read (before the identification of equal ones)
/// @return Ok, ParseError or NonFinite ("file:LINE: ..." or "file: STL triangle F: ...")
/// @note O(C log C) for C corners (the identification)
Status read_stl(std::string_view data, const std::string& name, std::vector<double>& coords,
                StlFacetSink* facets, std::size_t& corners);

}  // namespace detail
}  // namespace constrict
