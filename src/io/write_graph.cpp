// SPDX-License-Identifier: GPL-3.0-or-later
// Graph writers (CSV, JSON, SVG, OFF, PLY, OBJ). Numbers use std::to_chars (shortest decimal that
// round-trips), so output is exact and locale independent.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "constrict/io.hpp"
#include "io/detail/write_util.hpp"

namespace constrict {
namespace {

using detail::extension;
using detail::json_escape;
using detail::put_double;
using detail::put_int;
using detail::write_file;
using detail::xml_escape;

void face_row(std::string& s, const GammaFaces& g, std::size_t f, char sep) {
  for (int j = 0; j < g.dim; ++j) {
    put_int(s, g.vertex(f, j));
    s += sep;
  }
  put_double(s, g.gamma_a[f]);
  s += sep;
  put_double(s, g.gamma_b[f]);
  s += sep;
  put_double(s, g.delta[f]);
}

std::string to_csv(const GammaFaces& g) {
  std::string s = g.dim == 2 ? "i,j,gamma_a,gamma_b,delta\n" : "i,j,k,gamma_a,gamma_b,delta\n";
  s.reserve(s.size() + g.size() * 48);
  for (std::size_t f = 0; f < g.size(); ++f) {
    face_row(s, g, f, ',');
    s += '\n';
  }
  return s;
}

std::string to_json(const PointSet& pts, const GammaFaces& g, const std::string& desc) {
  std::string s = "{\n  \"dimension\": ";
  put_int(s, pts.dim);
  s += ",\n  \"points\": ";
  put_int(s, static_cast<long long>(pts.size()));
  s += ",\n  \"graph\": \"" + json_escape(desc) + "\",\n  \"columns\": [";
  s += g.dim == 2 ? "\"i\", \"j\"" : "\"i\", \"j\", \"k\"";
  s += ", \"gamma_a\", \"gamma_b\", \"delta\"],\n  \"faces\": [";
  for (std::size_t f = 0; f < g.size(); ++f) {
    s += f ? ",\n    [" : "\n    [";
    face_row(s, g, f, ',');
    s += ']';
  }
  s += g.size() ? "\n  ]\n}\n" : "]\n}\n";
  return s;
}

std::string to_svg(const PointSet& pts, const GammaFaces& g, const std::string& desc) {
  const detail::SvgFrame fr(pts);
  std::string s = fr.open(desc);
  s += "<g stroke=\"#1f4e8c\" stroke-width=\"1\" fill=\"none\">\n";
  for (std::size_t f = 0; f < g.size(); ++f)
    fr.line(s, pts[static_cast<std::size_t>(g.vertex(f, 0))], pts[static_cast<std::size_t>(g.vertex(f, 1))]);
  s += "</g>\n<g fill=\"#c0392b\">\n";
  const double r = detail::SvgFrame::point_radius(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) fr.circle(s, pts[i], r);
  s += "</g>\n</svg>\n";
  return s;
}

void put_vertex(std::string& s, const PointSet& pts, std::size_t i) {
  for (int k = 0; k < 3; ++k) {
    if (k) s += ' ';
    put_double(s, k < pts.dim ? pts[i][k] : 0.0);
  }
}

std::string to_off(const PointSet& pts, const GammaFaces& g) {
  std::string s = "OFF\n";
  put_int(s, static_cast<long long>(pts.size()));
  s += ' ';
  put_int(s, static_cast<long long>(g.size()));
  s += " 0\n";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    put_vertex(s, pts, i);
    s += '\n';
  }
  for (std::size_t f = 0; f < g.size(); ++f) {
    s += '3';
    for (int j = 0; j < 3; ++j) {
      s += ' ';
      put_int(s, g.vertex(f, j));
    }
    s += '\n';
  }
  return s;
}

std::string to_obj(const PointSet& pts, const GammaFaces& g, const std::string& desc) {
  std::string s = "# " + desc + "\n";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    s += "v ";
    put_vertex(s, pts, i);
    s += '\n';
  }
  for (std::size_t f = 0; f < g.size(); ++f) {
    s += g.dim == 2 ? 'l' : 'f';
    for (int j = 0; j < g.dim; ++j) {
      s += ' ';
      put_int(s, g.vertex(f, j) + 1);  // OBJ is 1-based
    }
    s += '\n';
  }
  return s;
}

std::string to_ply(const PointSet& pts, const GammaFaces& g, const std::string& desc) {
  std::string s = "ply\nformat ascii 1.0\ncomment " + desc + "\nelement vertex ";
  put_int(s, static_cast<long long>(pts.size()));
  s += "\nproperty double x\nproperty double y\nproperty double z\n";
  if (g.dim == 2) {
    s += "element edge ";
    put_int(s, static_cast<long long>(g.size()));
    s += "\nproperty int vertex1\nproperty int vertex2\n";
  } else {
    s += "element face ";
    put_int(s, static_cast<long long>(g.size()));
    s += "\nproperty list uchar int vertex_indices\n";
  }
  s += "end_header\n";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    put_vertex(s, pts, i);
    s += '\n';
  }
  for (std::size_t f = 0; f < g.size(); ++f) {
    if (g.dim == 3) s += "3 ";
    for (int j = 0; j < g.dim; ++j) {
      if (j) s += ' ';
      put_int(s, g.vertex(f, j));
    }
    s += '\n';
  }
  return s;
}

}  // namespace

GraphFormat graph_format_from_path(const std::string& path) noexcept {
  const std::string e = extension(path);
  if (e == "csv") return GraphFormat::Csv;
  if (e == "json") return GraphFormat::Json;
  if (e == "svg") return GraphFormat::Svg;
  if (e == "off") return GraphFormat::Off;
  if (e == "ply") return GraphFormat::Ply;
  if (e == "obj") return GraphFormat::Obj;
  return GraphFormat::Auto;
}

Status check_graph_format(const std::string& path, int dim, GraphFormat format) {
  if (format == GraphFormat::Auto) format = graph_format_from_path(path);
  switch (format) {
    case GraphFormat::Auto:
      return {StatusCode::InvalidArgument, path + ": unknown output extension (use .csv, .json, .svg, .off, .ply or .obj)"};
    case GraphFormat::Svg:
      if (dim != 2) return {StatusCode::InvalidArgument, path + ": SVG output is for 2D graphs; use .off, .ply or .obj in 3D"};
      break;
    case GraphFormat::Off:
      if (dim != 3) return {StatusCode::InvalidArgument, path + ": OFF cannot store the edges of a 2D graph; use .obj, .ply, .svg or .csv"};
      break;
    default: break;
  }
  return Status::ok();
}

Status write_graph(const std::string& path, const PointSet& points, const GammaFaces& faces,
                   const std::string& description, GraphFormat format) {
  if (format == GraphFormat::Auto) format = graph_format_from_path(path);
  if (faces.dim != points.dim)
    return {StatusCode::InvalidArgument, "write_graph: face dimension does not match the points"};
  if (Status s = check_graph_format(path, points.dim, format); !s) return s;
  switch (format) {
    case GraphFormat::Csv: return write_file(path, to_csv(faces));
    case GraphFormat::Json: return write_file(path, to_json(points, faces, description));
    case GraphFormat::Svg: return write_file(path, to_svg(points, faces, description));
    case GraphFormat::Off: return write_file(path, to_off(points, faces));
    case GraphFormat::Ply: return write_file(path, to_ply(points, faces, description));
    case GraphFormat::Obj: return write_file(path, to_obj(points, faces, description));
    case GraphFormat::Auto: break;
  }
  return {StatusCode::InvalidArgument,
          path + ": unknown output extension (use .csv, .json, .svg, .off, .ply or .obj)"};
}

}  // namespace constrict
