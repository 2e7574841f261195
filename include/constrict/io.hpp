// SPDX-License-Identifier: GPL-3.0-or-later
/// @file io.hpp
/// @brief Reading point sets (XYZ/CSV/TXT, PLY ascii/binary, OFF, OBJ, STL, GeoJSON).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// Input file formats. Auto picks by extension: .ply, .off, .obj, .stl, .geojson/.json; anything
/// else is text columns. LAS/LAZ and E57 (by extension or their magic bytes) are refused with
/// Unsupported and a conversion hint, whatever the format.
enum class PointFormat { Auto, Text, Ply, Off, Obj, Stl, GeoJson };

/// Short stable name of a format: "auto", "text", "ply", "off", "obj", "stl", "geojson".
const char* to_string(PointFormat format) noexcept;

/// The format of a name as the CLI's --format takes it: "auto", "text", "ply", "off", "obj",
/// "stl", "geojson" (lower case).
/// @return Ok, or InvalidArgument naming the accepted names
Status point_format_from_name(const std::string& name, PointFormat& out);

/// Which text columns hold x, y[, z] (ReadOptions::columns). Exactly one of the two lists is set,
/// with 2 or 3 entries in coordinate order.
struct ColumnSelection {
  std::vector<std::size_t> numbers;  ///< 1-based column numbers, e.g. {2, 3, 4}
  std::vector<std::string> names;    ///< header names (case-insensitive), e.g. {"x", "y", "z"}
  bool empty() const noexcept { return numbers.empty() && names.empty(); }
};

/// Parses a column list as the CLI's --columns takes it: "2,3,4" (1-based numbers) or "x,y,z"
/// (header names); 2 or 3 distinct entries, all numbers or all names.
/// @return Ok, or InvalidArgument saying what is wrong with @p text
Status parse_columns(const std::string& text, ColumnSelection& out);

/// How read_points() messages about text columns it cannot choose end (too many fields, or a
/// header without x and y): the CLI's --columns. A caller without such an option (the CLI's
/// render) replaces it with its own advice.
inline constexpr const char* kChooseColumnsAdvice =
    "choose the coordinate columns with --columns (1-based numbers such as 2,3,4, or header "
    "names such as x,y,z) or name them x, y, z in a header line";

/// Options of read_points().
struct ReadOptions {
  int dim = 0;                    ///< 0: from the data (2 columns -> 2D, 3 -> 3D); 2 or 3: forced
  PointFormat format = PointFormat::Auto;  ///< Auto: by file extension
  /// Text columns holding x, y[, z]. Empty (default): a header naming x and y (and z) selects
  /// those columns (case-insensitive); otherwise the first 2 or 3 fields, and more than 3 fields
  /// per line is a ParseError asking for a selection. Set: these columns, any number of fields
  /// per line; the entry count is the dimension (a forced dim 2 keeps the first two). Only for
  /// text input (InvalidArgument for the other formats).
  ColumnSelection columns;
  /// false: duplicates are an error (Duplicate, when `check`); true: keep the first occurrence of
  /// each point, drop later copies and add a warning (done even when `check` is false)
  bool merge_duplicates = false;
  /// run check_points() at the end (duplicates, too few, collinear, coplanar); false returns the
  /// points as parsed. Parse-level defects (ParseError, NonFinite, EmptyInput) are always errors.
  bool check = true;
};

/// Per-point attributes a file carries besides the coordinates, as plain arrays in the order of
/// the returned points (after merge_duplicates). Read from PLY vertex properties; empty when the
/// file has none (or for the other formats).
struct PointAttributes {
  /// nx, ny, nz per point (PLY scalar properties nx, ny, nz, any numeric type), as written
  std::vector<double> normals;
  /// color_channels values per point (PLY red, green, blue[, alpha]), scaled to [0, 1]: integer
  /// types divided by 255 (ushort: 65535), float types kept as written
  std::vector<double> colors;
  int color_channels = 0;  ///< 0 (no colours), 3 (red green blue) or 4 (with alpha)
};

/// What read_points() saw besides the points.
struct ReadReport {
  std::size_t points_read = 0;              ///< points in the file, before merging
  std::size_t merged_duplicates = 0;        ///< copies dropped by merge_duplicates
  /// For each point of the result, its 0-based index in the file (identity unless merged).
  std::vector<std::size_t> original_index;
  /// One {kept_row, dropped_row} pair per copy dropped by merge_duplicates (0-based file rows,
  /// kept_row the first occurrence), ascending by dropped_row; empty when nothing was merged.
  std::vector<std::array<std::size_t, 2>> merged;
  std::vector<std::string> warnings;        ///< one line each (e.g. merged duplicates)
  PointAttributes attributes;               ///< normals and colours (PLY), when the file has them
  PointFormat format = PointFormat::Auto;   ///< the format the file was read as
};

/// @p message (a Collinear or Coplanar message of check_points() or of an engine) for input read
/// as @p format: the hint for an outline written with a constant coordinate names --columns,
/// which only text input takes; for the other formats it says to write a text file first.
std::string degenerate_message_for(PointFormat format, const std::string& message);

/// Reads a point set (full rules and every error message: docs/input-formats.md).
/// Text: one point per line, fields separated by whitespace, ',', ';' or tab; '#' starts a
/// comment (full-line or trailing); blank lines ignored; CRLF accepted; one optional non-numeric
/// header line before the first point. Every line must have the same number of fields. The
/// coordinate columns: options.columns, else the header's x, y[, z] columns, else the first
/// fields: with dim = 0 the field count (2 or 3) is the dimension; a forced dim takes the first
/// `dim` fields of each line (so --dim 2 drops z) and fewer fields than `dim` is a ParseError;
/// more than 3 fields without a selection is a ParseError that says how to select.
/// PLY: ascii, binary_little_endian, binary_big_endian; `vertex` element with float/double (or
/// integer) properties x, y[, z]; normals nx ny nz and colours red green blue [alpha] go to
/// report->attributes; other elements and properties (lists too) are skipped. 3D if the vertex
/// has z, else 2D; a forced dim 2 drops z. A header count larger than the rest of the file can
/// hold is a ParseError before anything is allocated.
/// OFF (also COFF, NOFF...) / OBJ (`v` lines): the vertices only, 3D unless dim 2 is forced.
/// STL (binary or ASCII): the distinct facet corners (STL repeats a shared vertex in every facet;
/// identical corners are one point, first occurrence order, and a warning says so), 3D unless
/// dim 2 is forced.
/// GeoJSON: the Point and MultiPoint coordinates of a FeatureCollection, a Feature or a bare
/// geometry (a GeometryCollection too), in document order; 2 or 3 coordinates per position, the
/// same count for all; features with a null geometry are skipped, other geometry types are a
/// ParseError.
/// @param[in] path file to read
/// @param[in] options see ReadOptions
/// @param[out] out the points (dimension set); left unchanged when an error is returned
/// @param[out] report optional details; reset at the start, complete only on success
/// @return Ok, or FileNotFound (with the system's reason), InvalidArgument (options.dim not 0, 2
///         or 3; options.columns not fitting the file), Unsupported (LAS/LAZ, E57), ParseError ("file:LINE: ..."), EmptyInput, NonFinite ("file:LINE: ..." or
///         "file: PLY vertex I: ..." for binary PLY), Duplicate (first few index pairs listed),
///         TooFewPoints, Collinear, Coplanar. Every message is one line starting with @p path.
/// @note O(N) parsing with fast_float (no iostreams) on a memory-mapped file, plus O(N log N)
///       check_points(). A regular file is mapped on POSIX systems: truncating it while it is
///       being read is undefined (SIGBUS), as for any mmap reader.
Status read_points(const std::string& path, const ReadOptions& options, PointSet& out,
                   ReadReport* report = nullptr);

/// The points of the file in file order, from a result of read_points(): result point i at row
/// report.original_index[i], each copy dropped by merge_duplicates at its own row with the
/// coordinates of the point it duplicates. Equal to @p points when nothing was merged. Writers use
/// it so that indices in their output are the file's rows (map result index i to
/// report.original_index[i]).
/// @pre @p points and @p report come from the same successful read_points() call
/// @return the points of all report.points_read rows; O(N)
PointSet file_row_points(const PointSet& points, const ReadReport& report);

/// report.attributes in file order, the same way as file_row_points() (a dropped copy gets the
/// attributes of the point it duplicates). O(N).
PointAttributes file_row_attributes(const ReadReport& report);

/// Same as read_points() on an in-memory buffer (e.g. standard input).
/// @param[in] data the file contents
/// @param[in] name used in messages and, when no format is given, for the format by extension
/// @param[in] format overrides options.format unless Auto; Auto with options.format Auto picks
///            the format from the extension of @p name
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

/// Can a graph of points of this dimension be written in this format (Auto: by extension)?
/// InvalidArgument with write_graph()'s message if not (an unknown extension, SVG in 3D, OFF in
/// 2D): the CLI asks before it builds the graph.
Status check_graph_format(const std::string& path, int dim, GraphFormat format = GraphFormat::Auto);

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

#include <array>

namespace constrict {

/// Output formats of write_polygon2(). Auto picks by extension.
enum class PolygonFormat { Auto, Idx, Csv, GeoJson, Wkt, Svg, Rings };

/// Format from a file name's extension (.idx .csv .geojson/.json .wkt .svg .rings); Auto if unknown.
PolygonFormat polygon_format_from_path(const std::string& path) noexcept;

/// Optional layers of the SVG picture of a polygon (paper Figure 4 style).
struct PolygonSvgLayers {
  const GammaFaces* graph = nullptr;            ///< drawn dashed under the polygon (2D edges)
  std::vector<int> highlight_points;            ///< e.g. points stuck at a lock (drawn larger)
  std::vector<std::array<int, 2>> highlight_edges;  ///< e.g. fallback edges (drawn in a second colour)
  std::string title;                            ///< <title> of the picture
};

/// Writes a 2D polygon given as input indices in boundary order (closed implicitly).
/// - .idx: one 0-based input index per line, in order.
/// - .csv: header `x,y`, then the ordered coordinates (shortest round-trip decimals).
/// - .geojson (.json): a Feature with a Polygon geometry, the ring closed (first point repeated).
/// - .wkt: `POLYGON ((x y, ..., x y))`, ring closed.
/// - .svg: the points, the polygon solid, optional layers.
/// - .rings: the ring-set format of write_rings2() with the polygon as one shell.
/// @param[in] boundary polygon vertices as input indices (at least 3 for the polygon formats)
/// @param[in] layers optional SVG layers (ignored by the other formats)
/// @return Ok, InvalidArgument (unknown extension, not 2D, index out of range), WriteFailed
Status write_polygon2(const std::string& path, const PointSet& points, const std::vector<int>& boundary,
                      PolygonFormat format = PolygonFormat::Auto, const PolygonSvgLayers* layers = nullptr);

}  // namespace constrict

#include "constrict/topology.hpp"

namespace constrict {

/// Writes a ring set (reconstruct_rings2(), topology.hpp) given as input indices. One ring is written
/// exactly as write_polygon2() writes its polygon. Several rings:
/// - .rings: the ground-truth format of the shared topology data (docs/topology.md §"Formats"):
///   a comment line `# constrict rings R shells S holes H points N`, then one comment line per ring
///   `# ring K shell|hole parent P`, then one line per ring, in the same order, `c i0 i1 ... ik`
///   (0-based input indices, the ring closed implicitly). Shells run counter-clockwise, holes
///   clockwise.
/// - .geojson (.json): a Feature with a Polygon (one shell) or MultiPolygon geometry (RFC 7946
///   §3.1.6: each polygon its shell, counter-clockwise, then the holes directly inside it,
///   clockwise; every ring closed). An island in a lake is a polygon of its own.
/// - .wkt: `POLYGON ((shell), (hole), ...)` or `MULTIPOLYGON (((shell), (hole)), ((shell)))`, rings
///   closed: valid by the OGC Simple Features rules when the rings are (validate_rings2()).
/// - .svg: the points and the rings as one path (fill-rule evenodd), holes drawn dashed.
/// - .idx, .csv hold one polygon: InvalidArgument for several rings.
/// @param[in] rings the rings (roles, parents and indices; at least 3 indices each)
/// @return Ok, InvalidArgument (unknown extension, not 2D, index or parent out of range, a
///   one-polygon format for several rings), WriteFailed
Status write_rings2(const std::string& path, const PointSet& points, const std::vector<Ring2>& rings,
                    PolygonFormat format = PolygonFormat::Auto, const PolygonSvgLayers* layers = nullptr);

}  // namespace constrict
