// SPDX-License-Identifier: GPL-3.0-or-later
/// @file mesh.hpp
/// @brief Closed triangle meshes over the input points (3D reconstruction output): exact
/// validation, volume/area, and writers (OFF, PLY, OBJ, STL, VTK body). See
/// docs/reconstruction-3d.md.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/points.hpp"
#include "constrict/status.hpp"

namespace constrict {

/// A triangle mesh whose vertex ids are input point indices. Triangles are oriented outward
/// (counter-clockwise seen from outside; the signed volume is positive).
struct TriMesh3 {
  std::vector<std::array<int, 3>> triangles;
  std::size_t n_faces() const noexcept { return triangles.size(); }
};

/// Options of validate_mesh3().
struct MeshCheckOptions {
  /// Require every input point to be a vertex (and hence F = 2N - 4). Off for partial results.
  bool require_all_points = true;
  /// Also test that no two triangles intersect except in their shared vertex / edge (exact,
  /// orient3-based). Cost O(F log F + K) with K = pairs of overlapping x-extents (a sweep);
  /// meant for tests and small meshes.
  bool self_intersections = false;
  /// Accept any number of components and any genus (the surfaces of reconstruct_surfaces3(),
  /// topology.hpp): each component closed and manifold, V - E + F even per mesh, and the total
  /// signed volume positive. The orientation of each component against the body is the body
  /// check's job (validate_surfaces3()).
  bool any_topology = false;
};

/// What validate_mesh3() found. Flags after the first failing check may be left false.
/// Order of checks: indices, degenerate faces, edges (closed / manifold / oriented), vertex links,
/// points used, components, Euler characteristic, face count, orientation (volume),
/// self-intersections.
struct MeshCheck {
  bool indices_ok = false;        ///< every id in [0, N), three distinct ids per face
  bool non_degenerate = false;    ///< no face with collinear vertices (exact)
  bool closed = false;            ///< every edge in at least two faces (no border edge)
  bool edge_manifold = false;     ///< every edge in exactly two faces
  bool oriented = false;          ///< the two faces of every edge use it in opposite directions
  bool vertex_manifold = false;   ///< the link of every vertex is one cycle
  bool all_points = false;        ///< every input point is a vertex
  bool one_component = false;     ///< the faces form one edge-connected component
  bool euler_ok = false;          ///< V - E + F == 2 (genus 0)
  bool face_count_ok = false;     ///< F == 2V - 4 (V = used vertices; = 2N - 4 with all points)
  bool outward = false;           ///< signed volume > 0
  bool self_intersection_checked = false;
  bool no_self_intersections = false;  ///< meaningful when self_intersection_checked
  long long vertices = 0, edges = 0, faces = 0;
  long long euler = 0;            ///< V - E + F
  int genus = -1;                 ///< (2 - χ) / 2 for a closed connected manifold, else -1; with
                                  ///< any_topology the total genus (2c - χ) / 2 over c components
  int components = 0;
  int missing_point = -1;         ///< first input point that is not a vertex
  int bad_vertex = -1;            ///< first vertex with a bad link
  std::array<int, 2> bad_edge{{-1, -1}};       ///< first bad edge
  std::array<int, 2> intersecting_faces{{-1, -1}};  ///< first intersecting pair (face indices)
  double volume = 0;              ///< signed volume (double arithmetic; exact where it is badly conditioned)
  bool volume_exact = false;      ///< volume is the exact value (signed_volume_checked)
  std::string reason;             ///< one line; empty when valid
};

/// Checks that @p mesh is the boundary of a solid: a closed, edge- and vertex-manifold,
/// consistently and outward oriented, connected triangle mesh of genus 0 through every input point.
/// Combinatorial checks are exact; degeneracy and self-intersection tests use exact orient3; the
/// outward test is the exact sign of the signed volume (signed_volume_sign); details->volume is
/// mesh_volume()'s double value, or the exact value where that is badly conditioned
/// (signed_volume_checked; details->volume_exact).
/// @param[in] points dim == 3
/// @param[in] mesh triangles over input ids
/// @param[out] details optional diagnostics
/// @return Ok, or InvalidArgument with a one-line reason (also in details->reason)
/// @note O(F log F) without the self-intersection test.
Status validate_mesh3(const PointSet& points, const TriMesh3& mesh, MeshCheck* details = nullptr,
                      const MeshCheckOptions& options = {});

/// Exact test whether the closed triangles (a,b,c) and (d,e,f) intersect in more than their
/// shared vertices/edge (ids equal ⇔ shared). Exact (orient3/orient2 on coordinate projections).
/// @pre neither triangle is degenerate.
bool triangles_intersect_improperly(const PointSet& points, const std::array<int, 3>& t1,
                                    const std::array<int, 3>& t2);

/// Signed volume enclosed by an oriented closed mesh (divergence theorem, double arithmetic): each
/// connected surface about the centre of its own bounding box (one surface through every point:
/// of all the points), each triangle's term (a - o) . ((b - a) x (c - a)) from the corner between
/// its two shortest edges, so that surfaces far apart and long thin faces keep their digits. O(F).
double mesh_volume(const PointSet& points, const TriMesh3& mesh);
/// Total area of the triangles (double arithmetic). O(F).
double mesh_area(const PointSet& points, const TriMesh3& mesh);

struct PointAttributes;  // constrict/io.hpp

/// Options of write_mesh().
struct MeshWriteOptions {
  bool ply_ascii = false;  ///< PLY: ASCII instead of binary little-endian
  /// PLY only (the other formats have no per-vertex attributes and ignore it): per-vertex normals
  /// (`nx ny nz`, float) and colours (`red green blue [alpha]`, uchar: round(255 c), c clamped to
  /// [0, 1]) of the points, in point order, e.g. ReadReport::attributes. nullptr or empty arrays:
  /// x y z only. Array sizes other than 3 or color_channels per point are InvalidArgument.
  const PointAttributes* attributes = nullptr;
};

/// Writes a mesh. The format follows the extension: .off (ASCII), .ply (binary little-endian
/// double vertices and int32 face lists unless ply_ascii), .obj (ASCII, 1-based), .stl (binary,
/// float32; STL has no shared vertices). Vertices are all input points in input order, so face
/// indices are input indices. ASCII numbers are the shortest round-trip decimals.
/// @return Ok, InvalidArgument (attribute arrays not matching the points), or WriteFailed with a
///         one-line reason (unknown extension, cannot open, I/O error)
Status write_mesh(const std::string& path, const PointSet& points, const TriMesh3& mesh,
                  const MeshWriteOptions& options = {});

/// Writes a tetrahedral body as a VTK legacy unstructured grid (ASCII, cell type 10), vertices =
/// all input points in input order. Opens in ParaView.
/// @return Ok, or WriteFailed with a one-line reason
Status write_body_vtk(const std::string& path, const PointSet& points,
                      const std::vector<std::array<int, 4>>& tets);

/// What read_mesh() saw besides the mesh.
struct MeshReadReport {
  std::size_t polygons = 0;        ///< faces in the file
  std::size_t split_polygons = 0;  ///< faces with more than 3 vertices, split into a fan
};

/// Reads a triangle mesh (e.g. a ground-truth surface). The format follows the extension: .off
/// (OFF/COFF/NOFF..., extra vertex columns ignored), .ply (ascii, binary little/big endian;
/// `vertex` x, y, z and a `face` list `vertex_indices`/`vertex_index`, other elements skipped),
/// .obj (`v` and `f` records, `a/b/c` and negative indices accepted), .stl (binary or ASCII;
/// identical corner coordinates become one vertex, first occurrence order). Polygons with more
/// than three vertices are split into a fan from their first vertex. Vertices are kept in file
/// order (OFF/PLY/OBJ), unused ones included; no geometric check is made. OFF, PLY and OBJ use the
/// readers of read_points(): a header count larger than the file can hold is a ParseError before
/// anything is allocated, and face indices must be integers (any PLY list type) in range.
/// @param[out] points dim 3, the file's vertices; unchanged on error
/// @param[out] mesh triangles over @p points; unchanged on error
/// @return Ok, FileNotFound, ParseError ("file:LINE: ..." or "file: PLY face I: ..."),
///         NonFinite, EmptyInput (no faces). One-line messages starting with @p path.
/// @note O(file size) (STL: O(F log F) for the vertex identification).
Status read_mesh(const std::string& path, PointSet& points, TriMesh3& mesh, MeshReadReport* report = nullptr);

/// read_mesh() in the format @p format ("off", "ply", "obj", "stl"; empty: by the extension),
/// whatever the extension; @p path "-" reads standard input (messages then start with "standard
/// input").
Status read_mesh(const std::string& path, const std::string& format, PointSet& points, TriMesh3& mesh,
                 MeshReadReport* report = nullptr);

/// Same as read_mesh() on an in-memory buffer; the format follows the extension of @p name,
/// which also starts every message. FileNotFound cannot occur.
Status read_mesh_from_buffer(std::string_view data, const std::string& name, PointSet& points,
                             TriMesh3& mesh, MeshReadReport* report = nullptr);

}  // namespace constrict
