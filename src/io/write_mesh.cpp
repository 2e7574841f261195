// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh writers (OFF, PLY ascii/binary, OBJ, STL binary) and the VTK body writer. Vertices are the
// input points in input order; ASCII numbers are shortest round-trip decimals (std::to_chars).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

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
void put_ascii_mesh(std::string& s, const PointSet& pts, const TriMesh3& m, const char* vprefix, const char* fprefix,
                    long long base) {
  for (std::size_t i = 0; i < pts.size(); ++i) {
    s += vprefix;
    put_point(s, pts[i], ' ');
    s += '\n';
  }
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

std::string to_ply(const PointSet& pts, const TriMesh3& m, bool ascii) {
  std::string s = "ply\nformat ";
  s += ascii ? "ascii 1.0\n" : "binary_little_endian 1.0\n";
  s += "comment constrict 3D reconstruction (vertices = input points in input order)\nelement vertex ";
  put_int(s, static_cast<long long>(pts.size()));
  s += "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
  put_int(s, static_cast<long long>(m.triangles.size()));
  s += "\nproperty list uchar int vertex_indices\nend_header\n";
  if (ascii) {
    put_ascii_mesh(s, pts, m, "", "3 ", 0);
  } else {
    s.reserve(s.size() + pts.size() * 24 + m.triangles.size() * 13);
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (int k = 0; k < 3; ++k) put_le(s, pts[i][k]);
    for (const auto& t : m.triangles) {
      s += static_cast<char>(t.size());  // the uchar corner count of the PLY face list
      for (const std::int32_t v : t) put_le(s, v);
    }
  }
  return s;
}

std::string to_stl(const PointSet& pts, const TriMesh3& m) {
  std::string s(80, ' ');
  const char* head = "constrict 3D reconstruction (binary STL)";
  std::memcpy(&s[0], head, std::strlen(head));
  put_le(s, static_cast<std::uint32_t>(m.triangles.size()));
  s.reserve(s.size() + m.triangles.size() * 50);
  for (const auto& t : m.triangles) {
    const double* a = pts[static_cast<std::size_t>(t[0])];
    const double* b = pts[static_cast<std::size_t>(t[1])];
    const double* c = pts[static_cast<std::size_t>(t[2])];
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (len > 0) { nx /= len; ny /= len; nz /= len; }
    put_le(s, static_cast<float>(nx));
    put_le(s, static_cast<float>(ny));
    put_le(s, static_cast<float>(nz));
    for (const double* p : {a, b, c})
      for (int k = 0; k < 3; ++k) put_le(s, static_cast<float>(p[k]));
    put_le(s, static_cast<std::uint16_t>(0));
  }
  return s;
}

}  // namespace

Status write_mesh(const std::string& path, const PointSet& points, const TriMesh3& mesh,
                  const MeshWriteOptions& options) {
  if (points.dim != 3) return {StatusCode::WriteFailed, path + ": mesh output needs 3D points"};
  const std::string ext = extension(path);
  if (ext == "off") return write_file(path, to_off(points, mesh));
  if (ext == "obj") return write_file(path, to_obj(points, mesh));
  if (ext == "ply") return write_file(path, to_ply(points, mesh, options.ply_ascii));
  if (ext == "stl") return write_file(path, to_stl(points, mesh));
  return {StatusCode::WriteFailed,
          path + ": unknown mesh format '" + ext + "' (use .off, .ply, .obj or .stl)"};
}

Status write_body_vtk(const std::string& path, const PointSet& points,
                      const std::vector<std::array<int, 4>>& tets) {
  if (points.dim != 3) return {StatusCode::WriteFailed, path + ": body output needs 3D points"};
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
