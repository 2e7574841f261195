// SPDX-License-Identifier: GPL-3.0-or-later
// What every reader fuzz target asserts: the reader returns, with Ok and a well-formed result, or
// with one of its documented error codes and a one-line message starting with the input's name.
// Anything else (a crash, a sanitizer report, an exception, a timeout, an allocation over the
// -malloc_limit_mb, or a violated check below) is a finding: docs/fuzzing.md.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <string>
#include <string_view>

#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/status.hpp"

namespace constrict_fuzz {

inline void require(bool ok, const char* what, const constrict::Status& st) {
  if (ok) return;
  std::fprintf(stderr, "fuzz check failed: %s (%s: %s)\n", what, constrict::to_string(st.code()),
               st.message().c_str());
  std::abort();
}

inline void check_message(const constrict::Status& st, const std::string& name,
                          std::initializer_list<constrict::StatusCode> allowed) {
  if (st) return;
  bool documented = false;
  for (constrict::StatusCode c : allowed) documented = documented || st.code() == c;
  require(documented, "undocumented status code", st);
  require(st.message().rfind(name, 0) == 0, "message does not start with the file name", st);
  require(st.message().find('\n') == std::string::npos, "message is not one line", st);
}

/// read_points_from_buffer with two option sets (dimension from the data with checks; forced
/// 2D, merged duplicates, no checks), and the report.
inline void fuzz_points(std::string_view data, const std::string& name,
                        constrict::PointFormat format) {
  using constrict::StatusCode;
  for (int round = 0; round < 2; ++round) {
    constrict::ReadOptions o;
    o.dim = round == 0 ? 0 : 2;
    o.check = round == 0;
    o.merge_duplicates = round == 1;
    constrict::PointSet p;
    constrict::ReadReport report;
    const constrict::Status st = constrict::read_points_from_buffer(data, name, format, o, p, &report);
    check_message(st, name,
                  {StatusCode::ParseError, StatusCode::EmptyInput, StatusCode::NonFinite,
                   StatusCode::Duplicate, StatusCode::TooFewPoints, StatusCode::Collinear,
                   StatusCode::Coplanar, StatusCode::Unsupported /* LAS/E57 magic bytes */});
    if (!st) continue;
    require(p.dim == 2 || p.dim == 3, "dimension", st);
    require(p.coords.size() % static_cast<std::size_t>(p.dim) == 0, "coordinate count", st);
    for (double v : p.coords) require(std::isfinite(v), "non-finite coordinate", st);
    require(report.original_index.size() == p.size(), "original_index size", st);
    const constrict::PointAttributes& a = report.attributes;
    require(a.normals.empty() || a.normals.size() == 3 * p.size(), "normals size", st);
    require(a.colors.size() == static_cast<std::size_t>(a.color_channels) * p.size() ||
                a.colors.empty(),
            "colours size", st);
  }
}

/// read_mesh_from_buffer: triangles index the vertices.
inline void fuzz_mesh(std::string_view data, const std::string& name) {
  using constrict::StatusCode;
  constrict::PointSet p;
  constrict::TriMesh3 m;
  constrict::MeshReadReport report;
  const constrict::Status st = constrict::read_mesh_from_buffer(data, name, p, m, &report);
  check_message(st, name, {StatusCode::ParseError, StatusCode::EmptyInput, StatusCode::NonFinite});
  if (!st) return;
  require(p.dim == 3 && p.coords.size() % 3 == 0, "mesh vertices", st);
  for (double v : p.coords) require(std::isfinite(v), "non-finite vertex", st);
  for (const auto& t : m.triangles)
    for (int v : t) require(v >= 0 && static_cast<std::size_t>(v) < p.size(), "triangle index", st);
  require(!m.triangles.empty() && report.polygons > 0, "no faces but Ok", st);
}

inline std::string_view as_view(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace constrict_fuzz
