// SPDX-License-Identifier: GPL-3.0-or-later
// The one OBJ reader ('v' and 'f' records), used by read_points() and read_mesh(). Other records
// (vt, vn, o, g, usemtl, ...) are ignored; '#' starts a comment. Memory grows with the records
// actually present, never with a count from the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/status.hpp"

namespace constrict {
namespace detail {

/// Receives the faces of an OBJ file as they are read.
class ObjFaceSink {
 public:
  /// @param[in] line 1-based line of the 'f' record
  /// @param[in] ids 0-based vertex indices (negative ones already resolved against the vertices
  ///            read so far; not range checked)
  virtual Status face(std::size_t line, const std::vector<std::int64_t>& ids) = 0;

 protected:
  ~ObjFaceSink() = default;
};

/// Reads the 'v' records (the first @p dim of x y z appended to @p coords) and, if @p faces is
/// given, the 'f' records (a, a/b, a/b/c, a//c; 1-based or negative).
/// @return Ok, ParseError or NonFinite ("file:LINE: ...")
Status read_obj(std::string_view data, const std::string& name, int dim,
                std::vector<double>& coords, ObjFaceSink* faces);

}  // namespace detail
}  // namespace constrict
