// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh writers (OFF, PLY ascii/binary, OBJ, STL binary) and the VTK body writer. Vertices are the
// input points in input order; ASCII numbers are shortest round-trip decimals (std::to_chars).
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "io/detail/write_util.hpp"

namespace constrict {
namespace {

using detail::extension;
using detail::put_double;
using detail::put_int;
using detail::write_file;

template <class T>
void put_le(std::string& s, T v) {
  static_assert(std::is_trivially_copyable<T>::value, "raw value");
  char buf[sizeof(T)];
  std::memcpy(buf, &v, sizeof(T));
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  if (first == 0)  // big-endian host: reverse
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(buf[i], buf[sizeof(T) - 1 - i]);
  s.append(buf, sizeof(T));
}

void put_point(std::string& s, const double* p, char sep) {
  put_double(s, p[0]);
  s += sep;
  put_double(s, p[1]);
  s += sep;
  put_double(s, p[2]);
}

// The ASCII vertex and face lines shared by OFF, OBJ and ASCII PLY: "<vprefix>x y z" per point,
// "<fprefix>i j k" per triangle with indices shifted by `base` (1 for OBJ).
void put_ascii_faces(std::string& s, const TriMesh3& m, const char* fprefix, long long base) {
  for (const auto& t : m.triangles) {
    s += fprefix;
    put_int(s, t[0] + base);
    s += ' ';
    put_int(s, t[1] + base);
    s += ' ';
    put_int(s, t[2] + base);
    s += '\n';
  }
}

void put_ascii_mesh(std::string& s, const PointSet& pts, const TriMesh3& m, const char* vprefix, const char* fprefix,
                    long long base) {
  for (std::size_t i = 0; i < pts.size(); ++i) {
    s += vprefix;
    put_point(s, pts[i], ' ');
    s += '\n';
  }
  put_ascii_faces(s, m, fprefix, base);
}

std::string to_off(const PointSet& pts, const TriMesh3& m) {
  std::string s = "OFF\n";
  put_int(s, static_cast<long long>(pts.size()));
  s += ' ';
  put_int(s, static_cast<long long>(m.triangles.size()));
  s += " 0\n";
  put_ascii_mesh(s, pts, m, "", "3 ", 0);
  return s;
}

std::string to_obj(const PointSet& pts, const TriMesh3& m) {
  std::string s = "# constrict 3D reconstruction\n";
  put_ascii_mesh(s, pts, m, "v ", "f ", 1);
  return s;
}

// The optional per-vertex PLY properties: normals as float, colours as uchar.
struct PlyAttributes {
  const std::vector<double>* normals = nullptr;
  const std::vector<double>* colors = nullptr;
  int channels = 0;
};

std::uint8_t color_byte(double c) {
  constexpr double kMax = 255.0;
  return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * kMax));
}

void put_float(std::string& s, float v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

Status ply_attributes(const std::string& path, const PointSet& pts, const PointAttributes* a, PlyAttributes& out) {
  if (a == nullptr) return Status::ok();
  const std::size_t n = pts.size();
  if (!a->normals.empty()) {
    if (a->normals.size() != 3 * n)
      return {StatusCode::InvalidArgument, path + ": " + std::to_string(a->normals.size()) +
                                               " normal values for " + std::to_string(n) + " points (3 per point expected)"};
    out.normals = &a->normals;
  }
  if (!a->colors.empty()) {
    const auto ch = static_cast<std::size_t>(a->color_channels);
    if ((ch != 3 && ch != 4) || a->colors.size() != ch * n)
      return {StatusCode::InvalidArgument, path + ": " + std::to_string(a->colors.size()) + " colour values in " +
                                               std::to_string(ch) + " channels for " + std::to_string(n) + " points"};
    out.colors = &a->colors;
    out.channels = a->color_channels;
  }
  return Status::ok();
}

void put_ply_vertex(std::string& s, const PointSet& pts, std::size_t i, const PlyAttributes& a, bool ascii) {
  const auto ch = static_cast<std::size_t>(a.channels);
  if (ascii) {
    put_point(s, pts[i], ' ');
    for (std::size_t k = 0; a.normals != nullptr && k < 3; ++k) {
      s += ' ';
      put_float(s, static_cast<float>((*a.normals)[3 * i + k]));
    }
    for (std::size_t k = 0; a.colors != nullptr && k < ch; ++k) {
      s += ' ';
      put_int(s, color_byte((*a.colors)[ch * i + k]));
    }
    s += '\n';
    return;
  }
  for (int k = 0; k < 3; ++k) put_le(s, pts[i][k]);
  for (std::size_t k = 0; a.normals != nullptr && k < 3; ++k) put_le(s, static_cast<float>((*a.normals)[3 * i + k]));
  for (std::size_t k = 0; a.colors != nullptr && k < ch; ++k) s += static_cast<char>(color_byte((*a.colors)[ch * i + k]));
}

std::string to_ply(const PointSet& pts, const TriMesh3& m, bool ascii, const PlyAttributes& a) {
  std::string s = "ply\nformat ";
  s += ascii ? "ascii 1.0\n" : "binary_little_endian 1.0\n";
  s += "comment constrict 3D reconstruction (vertices = input points in input order)\nelement vertex ";
  put_int(s, static_cast<long long>(pts.size()));
  s += "\nproperty double x\nproperty double y\nproperty double z\n";
  if (a.normals != nullptr) s += "property float nx\nproperty float ny\nproperty float nz\n";
  if (a.colors != nullptr) s += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (a.channels == 4) s += "property uchar alpha\n";
  s += "element face ";
  put_int(s, static_cast<long long>(m.triangles.size()));
  s += "\nproperty list uchar int vertex_indices\nend_header\n";
  if (ascii && a.normals == nullptr && a.colors == nullptr) {
    put_ascii_mesh(s, pts, m, "", "3 ", 0);
    return s;
  }
  if (ascii) {
    for (std::size_t i = 0; i < pts.size(); ++i) put_ply_vertex(s, pts, i, a, true);
    put_ascii_faces(s, m, "3 ", 0);
    return s;
  }
  s.reserve(s.size() + pts.size() * 24 + m.triangles.size() * 13);
  for (std::size_t i = 0; i < pts.size(); ++i) put_ply_vertex(s, pts, i, a, false);
  for (const auto& t : m.triangles) {
    s += static_cast<char>(t.size());  // the uchar corner count of the PLY face list
    for (const std::int32_t v : t) put_le(s, v);
  }
  return s;
}

// STL stores 32-bit floats: a coordinate beyond their range would be written as infinity, a tiny
// one as 0, and two corners of a triangle may round to one point (a degenerate triangle in the
// file). Any of these refuses the file with the formats that keep doubles, rather than writing a
// surface that is not the one computed.
Status to_stl(const std::string& path, const PointSet& pts, const TriMesh3& m, std::string& s) {
  const auto refuse = [&](const std::string& why) -> Status {
    return {StatusCode::WriteFailed, path + ": " + why + " in STL's 32-bit floats; write .ply, .off or .obj (doubles)"};
  };
  const auto g = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return std::string(buf);
  };
  const auto as_float = [](const double* p) { return std::array<float, 3>{float(p[0]), float(p[1]), float(p[2])}; };
  s.assign(80, ' ');
  const char* head = "constrict 3D reconstruction (binary STL)";
  std::memcpy(&s[0], head, std::strlen(head));
  put_le(s, static_cast<std::uint32_t>(m.triangles.size()));
  s.reserve(s.size() + m.triangles.size() * 50);
  // The points the triangles use, in point order (so the message names the first bad one).
  std::vector<char> used(pts.size(), 0);
  for (const auto& t : m.triangles)
    for (const int v : t) used[static_cast<std::size_t>(v)] = 1;
  for (std::size_t v = 0; v < pts.size(); ++v) {
    if (!used[v]) continue;
    const std::array<float, 3> f = as_float(pts[v]);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(f[k]))
        return refuse("point " + std::to_string(v) + " has a coordinate (" + g(pts[v][k]) + ") beyond the range");
      if (f[k] == 0 && pts[v][k] != 0)
        return refuse("point " + std::to_string(v) + " has a coordinate too close to 0 to be kept");
    }
  }
  for (const auto& t : m.triangles) {
    const double* a = pts[static_cast<std::size_t>(t[0])];
    const double* b = pts[static_cast<std::size_t>(t[1])];
    const double* c = pts[static_cast<std::size_t>(t[2])];
    const std::array<float, 3> f[3] = {as_float(a), as_float(b), as_float(c)};
    for (int j = 0; j < 3; ++j)
      if (f[j] == f[(j + 1) % 3]) {
        const int u = std::min(t[j], t[(j + 1) % 3]), w = std::max(t[j], t[(j + 1) % 3]);
        return refuse("points " + std::to_string(u) + " and " + std::to_string(w) + " become one point");
      }
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (len > 0) { nx /= len; ny /= len; nz /= len; }
    put_le(s, static_cast<float>(nx));
    put_le(s, static_cast<float>(ny));
    put_le(s, static_cast<float>(nz));
    for (const auto& p : f)
      for (int k = 0; k < 3; ++k) put_le(s, p[k]);
    put_le(s, static_cast<std::uint16_t>(0));
  }
  return Status::ok();
}

}  // namespace

Status write_mesh(const std::string& path, const PointSet& points, const TriMesh3& mesh,
                  const MeshWriteOptions& options) {
  if (points.dim != 3) return {StatusCode::WriteFailed, path + ": mesh output needs 3D points"};
  if (Status st = detail::check_finite_coordinates(path, points); !st) return st;
  const std::string ext = extension(path);
  if (ext == "off") return write_file(path, to_off(points, mesh));
  if (ext == "obj") return write_file(path, to_obj(points, mesh));
  if (ext == "ply") {
    PlyAttributes attributes;
    if (Status st = ply_attributes(path, points, options.attributes, attributes); !st) return st;
    return write_file(path, to_ply(points, mesh, options.ply_ascii, attributes));
  }
  if (ext == "stl") {
    std::string s;
    if (Status st = to_stl(path, points, mesh, s); !st) return st;
    return write_file(path, s);
  }
  return {StatusCode::WriteFailed,
          path + ": unknown mesh format '" + ext + "' (use .off, .ply, .obj or .stl)"};
}

Status write_body_vtk(const std::string& path, const PointSet& points,
                      const std::vector<std::array<int, 4>>& tets) {
  if (points.dim != 3) return {StatusCode::WriteFailed, path + ": body output needs 3D points"};
  if (extension(path) != "vtk")
    return {StatusCode::InvalidArgument, path + ": the body is written as legacy VTK: name it .vtk"};
  if (Status st = detail::check_finite_coordinates(path, points); !st) return st;
  std::string s = "# vtk DataFile Version 3.0\nconstrict tetrahedral body\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS ";
  put_int(s, static_cast<long long>(points.size()));
  s += " double\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    put_point(s, points[i], ' ');
    s += '\n';
  }
  s += "CELLS ";
  put_int(s, static_cast<long long>(tets.size()));
  s += ' ';
  put_int(s, static_cast<long long>(tets.size() * 5));
  s += '\n';
  for (const auto& t : tets) {
    s += '4';
    for (int v : t) {
      s += ' ';
      put_int(s, v);
    }
    s += '\n';
  }
  s += "CELL_TYPES ";
  put_int(s, static_cast<long long>(tets.size()));
  s += '\n';
  for (std::size_t i = 0; i < tets.size(); ++i) s += "10\n";
  return write_file(path, s);
}

}  // namespace constrict
