// SPDX-License-Identifier: GPL-3.0-or-later
/// @file io.hpp
/// @brief Reading point sets (XYZ/CSV/TXT, PLY ascii/binary, OFF, OBJ).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// Input file formats. Auto picks by extension: .ply, .off, .obj; anything else is text columns.
enum class PointFormat { Auto, Text, Ply, Off, Obj };

/// Options of read_points().
struct ReadOptions {
  int dim = 0;                    ///< 0: from the data (2 columns -> 2D, 3 -> 3D); 2 or 3: forced
  PointFormat format = PointFormat::Auto;  ///< Auto: by file extension
  bool merge_duplicates = false;  ///< false: duplicates are an error; true: keep first, warn
  bool check = true;              ///< run check_points() (too few, collinear, coplanar) at the end
};

/// What read_points() saw besides the points.
struct ReadReport {
  std::size_t points_read = 0;              ///< points in the file, before merging
  std::size_t merged_duplicates = 0;        ///< copies dropped by merge_duplicates
  /// For each point of the result, its 0-based index in the file (identity unless merged).
  std::vector<std::size_t> original_index;
  std::vector<std::string> warnings;        ///< one line each (e.g. merged duplicates)
};

/// Reads a point set.
/// Text: one point per line, fields separated by whitespace, ',', ';' or tab; '#' starts a
/// comment; blank lines ignored; one optional non-numeric header line before the first point.
/// Every line must have the same number of fields. With dim = 0 the field count (2 or 3) is the
/// dimension; a forced dim takes the first `dim` fields of each line (so --dim 2 drops z) and
/// fewer fields than `dim` is a ParseError.
/// PLY: ascii, binary_little_endian, binary_big_endian; `vertex` element with float/double (or
/// integer) properties x, y[, z]; other elements and properties are skipped.
/// OFF / OBJ: the vertices only.
/// @param[in] path file to read
/// @param[in] options see ReadOptions
/// @param[out] out the points (dimension set)
/// @param[out] report optional details
/// @return Ok, or FileNotFound, ParseError (message names file and line), EmptyInput, NonFinite,
///         Duplicate (first few index pairs listed), TooFewPoints, Collinear, Coplanar.
/// @note Linear time; numbers parsed with fast_float (no iostreams).
Status read_points(const std::string& path, const ReadOptions& options, PointSet& out,
                   ReadReport* report = nullptr);

/// Same as read_points() on an in-memory buffer; @p name is used in messages.
Status read_points_from_buffer(std::string_view data, const std::string& name, PointFormat format,
                               const ReadOptions& options, PointSet& out,
                               ReadReport* report = nullptr);

}  // namespace constrict

#include "constrict/gamma_graph.hpp"

namespace constrict {

/// Output formats of write_graph(). Auto picks by extension.
enum class GraphFormat { Auto, Csv, Json, Svg, Off, Ply, Obj };

/// Format from a file name's extension (.csv .json .svg .off .ply .obj); Auto if unknown.
GraphFormat graph_format_from_path(const std::string& path) noexcept;

/// Writes a graph.
/// - .csv: header, then one face per row: `i,j,gamma_a,gamma_b,delta` (2D) or
///   `i,j,k,gamma_a,gamma_b,delta` (3D); 0-based input indices ascending; values in shortest
///   round-trip decimal.
/// - .json: {"dimension", "points", "graph", "faces": [[i,j(,k),gamma_a,gamma_b,delta],...]}.
/// - .svg: 2D only: points and edges (y axis up).
/// - .off/.ply/.obj: all input points as vertices, 3D: the triangles; 2D: edges as a line set
///   (OBJ `l` records, PLY `edge` element; OFF cannot store edges in 2D: InvalidArgument).
/// @param[in] description graph name written into the file where the format has room for it
/// @return Ok, InvalidArgument (unknown extension, format not possible), WriteFailed
Status write_graph(const std::string& path, const PointSet& points, const GammaFaces& faces,
                   const std::string& description, GraphFormat format = GraphFormat::Auto);

}  // namespace constrict
