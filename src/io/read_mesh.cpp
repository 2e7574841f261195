// SPDX-License-Identifier: GPL-3.0-or-later
// Triangle mesh input (reference meshes for `constrict compare` and `constrict render`): OFF, PLY
// (ascii, binary little/big endian), OBJ and STL (binary and ascii). Every format goes through
// the same reader as the point input (io/detail/off, ply, obj, stl), so both accept the same files
// and refuse the same lies. Polygons with more than three vertices are split into a
// fan. Errors name the file and the 1-based line (binary files: the element and its index).
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "constrict/mesh.hpp"
#include "io/detail/obj.hpp"
#include "io/detail/off.hpp"
#include "io/detail/ply.hpp"
#include "io/detail/stl.hpp"
#include "io/detail/write_util.hpp"

namespace constrict {
namespace {

struct Builder {
  const std::string& name;
  PointSet pts;
  TriMesh3 mesh;
  MeshReadReport rep;

  // Adds polygon `ids` (already 0-based and in range) as a triangle fan.
  void polygon(const std::vector<std::int64_t>& ids) {
    ++rep.polygons;
    if (ids.size() > 3) ++rep.split_polygons;
    for (std::size_t k = 1; k + 1 < ids.size(); ++k)
      mesh.triangles.push_back({{static_cast<int>(ids[0]), static_cast<int>(ids[k]), static_cast<int>(ids[k + 1])}});
  }
};

Status at(StatusCode c, const std::string& name, std::size_t line, const std::string& what) {
  return {c, name + ":" + std::to_string(line) + ": " + what};
}

Status check_ids(Builder& b, const std::vector<std::int64_t>& ids, std::size_t line) {
  if (ids.size() < 3) return at(StatusCode::ParseError, b.name, line, "a face needs at least 3 vertices");
  const auto n = static_cast<std::int64_t>(b.pts.size());
  for (std::int64_t v : ids)
    if (v < 0 || v >= n)
      return at(StatusCode::ParseError, b.name, line,
                "vertex index " + std::to_string(v) + " out of range (" + std::to_string(n) + " vertices)");
  return Status::ok();
}

Status parse_off(std::string_view data, Builder& b) {
  detail::OffReader off(data, b.name);
  Status st = off.header(true);
  if (!st) return st;
  if (off.empty()) return at(StatusCode::ParseError, b.name, off.line(), "an OFF file starts with 'OFF'");
  st = off.vertices(3, b.pts.coords);
  if (!st) return st;
  std::vector<std::int64_t> ids;
  for (std::uint64_t f = 0; f < off.n_faces(); ++f) {
    st = off.face(f, ids);
    if (st) st = check_ids(b, ids, off.line());
    if (!st) return st;
    b.polygon(ids);
  }
  return off.end();
}

// Faces arrive while the vertices are still being read (negative indices are relative to the
// vertices so far), so each one is checked against the vertices read before it.
struct ObjFaces final : detail::ObjFaceSink {
  Builder& b;
  explicit ObjFaces(Builder& builder) : b(builder) {}
  Status face(std::size_t line, const std::vector<std::int64_t>& ids) override {
    Status st = check_ids(b, ids, line);
    if (st) b.polygon(ids);
    return st;
  }
};

Status parse_obj(std::string_view data, Builder& b) {
  ObjFaces faces(b);
  return detail::read_obj(data, b.name, 3, b.pts.coords, &faces);
}

// ---- PLY: 'vertex' x y z and 'face' vertex_indices (or vertex_index); other elements skipped --

Status ply_faces(detail::PlyBody& body, const detail::PlyElement& el, Builder& b) {
  int list = el.find("vertex_indices");
  if (list < 0) list = el.find("vertex_index");
  if (list >= 0 && !el.properties[static_cast<std::size_t>(list)].is_list) list = -1;
  if (list < 0) return body.skip(el);
  const detail::PlyRecordSpec spec{std::vector<int>(el.properties.size(), -1), 0, list};
  std::vector<std::int64_t> ids;
  for (std::uint64_t i = 0; i < el.count; ++i) {
    Status st = body.read_record(el, i, spec, nullptr, &ids);
    if (!st) return st;
    st = check_ids(b, ids, body.line());
    if (!st && !body.ascii())
      st = {st.code(), b.name + ": PLY face " + std::to_string(i) + ": bad vertex list (" +
                           std::to_string(ids.size()) + " indices, " + std::to_string(b.pts.size()) +
                           " vertices)"};
    if (!st) return st;
    b.polygon(ids);
  }
  return Status::ok();
}

Status ply_vertices(detail::PlyBody& body, const detail::PlyElement& el, Builder& b) {
  static const char* const kAxes[3] = {"x", "y", "z"};
  detail::PlyRecordSpec spec{std::vector<int>(el.properties.size(), -1), 3, -1};
  for (int k = 0; k < 3; ++k) {
    const int prop = el.find(kAxes[k]);
    if (prop < 0 || el.properties[static_cast<std::size_t>(prop)].is_list)
      return {StatusCode::ParseError, b.name + ": PLY vertex element needs x, y and z"};
    spec.slot[static_cast<std::size_t>(prop)] = k;
  }
  return body.read_table(el, spec, 3, b.pts.coords);
}

Status parse_ply(std::string_view data, Builder& b) {
  detail::PlyHeader header;
  Status st = detail::parse_ply_header(data, b.name, header);
  if (!st) return st;
  // 2D points (a vertex element without z) and no faces: not a mesh, as a file without faces
  // (EmptyInput, so that `render` reads it as a point set).
  bool faces = false, z = true;
  for (const detail::PlyElement& el : header.elements) {
    faces = faces || (el.name == "face" && el.count > 0);
    if (el.name == "vertex") z = el.find("z") >= 0;
  }
  if (!z && !faces) return {StatusCode::EmptyInput, b.name + ": a PLY of 2D points and no faces is not a mesh"};
  detail::PlyBody body(data, b.name, header);
  for (const detail::PlyElement& el : header.elements) {
    st = body.check_room(el);
    if (st) {
      if (el.name == "vertex") st = ply_vertices(body, el, b);
      else if (el.name == "face") st = ply_faces(body, el, b);
      else st = body.skip(el);
    }
    if (!st) return st;
  }
  // More records than the header counts (a face list longer than announced) were ignored.
  const auto last = std::find_if(header.elements.rbegin(), header.elements.rend(),
                                 [](const detail::PlyElement& el) { return el.count > 0; });
  return last == header.elements.rend() ? Status::ok() : body.check_end(*last);
}

// ---- STL: the shared reader identifies equal corners (io/detail/stl.hpp) --------------------

struct StlFaces final : detail::StlFacetSink {
  Builder& b;
  explicit StlFaces(Builder& builder) : b(builder) {}
  void facet(const std::vector<std::int64_t>& ids) override { b.polygon(ids); }
};

Status parse_stl(std::string_view data, Builder& b) {
  StlFaces faces(b);
  std::size_t corners = 0;
  return detail::read_stl(data, b.name, b.pts.coords, &faces, corners);
}

}  // namespace

namespace {

// The mesh of `data` in format `ext` (off, ply, obj, stl); `name` starts every message.
Status read_mesh_as(std::string_view data, const std::string& name, const std::string& ext, PointSet& points, TriMesh3& mesh,
                    MeshReadReport* report) {
  if (ext != "off" && ext != "ply" && ext != "obj" && ext != "stl")
    return {StatusCode::ParseError, name + ": unknown mesh format '" + ext + "' (use .off, .ply, .obj or .stl)"};
  Builder b{name, {}, {}, {}};
  b.pts.dim = 3;
  Status st;
  if (ext == "off") st = parse_off(data, b);
  else if (ext == "ply") st = parse_ply(data, b);
  else if (ext == "obj") st = parse_obj(data, b);
  else st = parse_stl(data, b);
  if (!st) return st;
  if (b.mesh.triangles.empty()) return {StatusCode::EmptyInput, name + ": no faces"};
  points = std::move(b.pts);
  mesh = std::move(b.mesh);
  if (report) *report = b.rep;
  return Status::ok();
}

}  // namespace

Status read_mesh_from_buffer(std::string_view data, const std::string& name, PointSet& points, TriMesh3& mesh,
                             MeshReadReport* report) {
  return read_mesh_as(data, name, detail::extension(name), points, mesh, report);
}

Status read_mesh(const std::string& path, PointSet& points, TriMesh3& mesh, MeshReadReport* report) {
  return read_mesh(path, "", points, mesh, report);
}

Status read_mesh(const std::string& path, const std::string& format, PointSet& points, TriMesh3& mesh,
                 MeshReadReport* report) {
  // "-": standard input, as read_points() reads it (render's piped mesh was read as points).
  const std::string name = path == "-" ? std::string("standard input") : path;
  const std::string ext = format.empty() ? detail::extension(path) : format;
  if (ext != "off" && ext != "ply" && ext != "obj" && ext != "stl")
    return {StatusCode::ParseError, name + ": unknown mesh format '" + ext + "' (use .off, .ply, .obj or .stl)"};
  std::ifstream f(path == "-" ? std::string("/dev/stdin") : path, std::ios::binary);
  if (!f) return {StatusCode::FileNotFound, name + ": cannot open: " + std::strerror(errno)};
  std::ostringstream ss;
  ss << f.rdbuf();
  return read_mesh_as(ss.str(), name, ext, points, mesh, report);
}

}  // namespace constrict
