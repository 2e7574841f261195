// SPDX-License-Identifier: GPL-3.0-or-later
// The one OFF reader (OFF, COFF, NOFF, CNOFF, STOFF...; ascii only), used by read_points() and
// read_mesh(). Lines are split like text columns (whitespace, ',' or ';'; '#' comments).
// Contract: the counts are never trusted for a loop or an allocation. header() refuses counts
// the rest of the file cannot hold (every vertex or face line takes at least two bytes: a value
// and a line break), and reservations are capped by the bytes left.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/status.hpp"
#include "io/detail/scan.hpp"

namespace constrict {
namespace detail {

/// OFF, COFF, NOFF, CNOFF, STOFF, STCNOFF...: the optional prefixes only add per-vertex fields
/// after x y z, which are skipped. 4OFF / nOFF (other dimensions) are not supported.
bool is_off_keyword(std::string_view w);

class OffReader {
 public:
  OffReader(std::string_view data, const std::string& name);

  /// Keyword and counts lines. @p with_faces: the face count is required and must fit as well
  /// (mesh reader; the point reader reads the vertices only and ignores the rest).
  /// Ok with empty() true when the file holds nothing but comments.
  Status header(bool with_faces);
  bool empty() const noexcept { return empty_; }
  std::uint64_t n_vertices() const noexcept { return n_vertices_; }
  std::uint64_t n_faces() const noexcept { return n_faces_; }

  /// Reads the n_vertices() vertex lines; appends the first @p dim (2 or 3) values of each.
  Status vertices(int dim, std::vector<double>& coords);

  /// The point reader, after vertices(): the header's face lines (when the counts line gives a
  /// face count), each a count and that many vertex indices below n_vertices(), then nothing but
  /// blank and comment lines (end()). Without a face count the next record, if any, must be a
  /// face line. Else the header's counts are smaller than the data and points would be lost
  /// without a word: ParseError naming the line.
  Status after_vertices();

  /// After the last face: nothing but blank and comment lines, else ParseError (more data than
  /// the counts announce).
  Status end();

  /// Reads face @p f (0-based, < n_faces()): its vertex indices as written.
  Status face(std::uint64_t f, std::vector<std::int64_t>& ids);

  std::size_t line() const noexcept { return lines_.line(); }  ///< line of the last record

 private:
  Status counts(std::vector<Span>& fields, bool with_faces);
  // The next record's fields (blank and comment lines skipped); 0 at the end of the data.
  std::size_t next_fields(const char*& b, const char*& e, std::vector<Span>& fields);

  std::string_view data_;
  const std::string& name_;
  LineReader lines_;
  bool empty_ = false;
  std::uint64_t n_vertices_ = 0;
  std::uint64_t n_faces_ = 0;
  bool faces_known_ = false;  // the counts line gave a face count
  bool ended_ = false;        // face() met the end of the data
};

}  // namespace detail
}  // namespace constrict
