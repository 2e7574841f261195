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

namespace constrict {
namespace {

void put_double(std::string& s, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}
void put_int(std::string& s, long long v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

std::string extension(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

Status write_file(const std::string& path, const std::string& data) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return {StatusCode::WriteFailed, path + ": cannot open for writing: " + std::strerror(errno)};
  const std::size_t w = std::fwrite(data.data(), 1, data.size(), f);
  const int c = std::fclose(f);
  if (w != data.size() || c != 0) return {StatusCode::WriteFailed, path + ": write failed: " + std::strerror(errno)};
  return Status::ok();
}

std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') { o += '\\'; o += c; }
    else if (static_cast<unsigned char>(c) < 0x20) o += ' ';
    else o += c;
  }
  return o;
}

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '&': o += "&amp;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

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
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[2] = {-lo[0], -lo[1]};
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], pts[i][k]);
      hi[k] = std::max(hi[k], pts[i][k]);
    }
  const double w = std::max(hi[0] - lo[0], 1e-300), h = std::max(hi[1] - lo[1], 1e-300);
  const double size = 800.0, margin = 20.0;
  const double scale = (size - 2 * margin) / std::max(w, h);
  const double W = w * scale + 2 * margin, H = h * scale + 2 * margin;
  auto X = [&](double x) { return margin + (x - lo[0]) * scale; };
  auto Y = [&](double y) { return H - margin - (y - lo[1]) * scale; };  // y axis up
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"";
  put_double(s, W);
  s += "\" height=\"";
  put_double(s, H);
  s += "\" viewBox=\"0 0 ";
  put_double(s, W);
  s += ' ';
  put_double(s, H);
  s += "\">\n<title>" + xml_escape(desc) + "</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += "<g stroke=\"#1f4e8c\" stroke-width=\"1\" fill=\"none\">\n";
  for (std::size_t f = 0; f < g.size(); ++f) {
    const double* a = pts[static_cast<std::size_t>(g.vertex(f, 0))];
    const double* b = pts[static_cast<std::size_t>(g.vertex(f, 1))];
    s += "<line x1=\"";
    put_double(s, X(a[0]));
    s += "\" y1=\"";
    put_double(s, Y(a[1]));
    s += "\" x2=\"";
    put_double(s, X(b[0]));
    s += "\" y2=\"";
    put_double(s, Y(b[1]));
    s += "\"/>\n";
  }
  s += "</g>\n<g fill=\"#c0392b\">\n";
  const double r = std::clamp(400.0 / std::sqrt(static_cast<double>(pts.size()) + 1.0), 0.5, 4.0);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    s += "<circle cx=\"";
    put_double(s, X(pts[i][0]));
    s += "\" cy=\"";
    put_double(s, Y(pts[i][1]));
    s += "\" r=\"";
    put_double(s, r);
    s += "\"/>\n";
  }
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

Status write_graph(const std::string& path, const PointSet& points, const GammaFaces& faces,
                   const std::string& description, GraphFormat format) {
  if (format == GraphFormat::Auto) format = graph_format_from_path(path);
  if (faces.dim != points.dim)
    return {StatusCode::InvalidArgument, "write_graph: face dimension does not match the points"};
  switch (format) {
    case GraphFormat::Csv: return write_file(path, to_csv(faces));
    case GraphFormat::Json: return write_file(path, to_json(points, faces, description));
    case GraphFormat::Svg:
      if (points.dim != 2) return {StatusCode::InvalidArgument, path + ": SVG output is for 2D graphs; use .off, .ply or .obj in 3D"};
      return write_file(path, to_svg(points, faces, description));
    case GraphFormat::Off:
      if (points.dim != 3) return {StatusCode::InvalidArgument, path + ": OFF cannot store the edges of a 2D graph; use .obj, .ply, .svg or .csv"};
      return write_file(path, to_off(points, faces));
    case GraphFormat::Ply: return write_file(path, to_ply(points, faces, description));
    case GraphFormat::Obj: return write_file(path, to_obj(points, faces, description));
    case GraphFormat::Auto: break;
  }
  return {StatusCode::InvalidArgument,
          path + ": unknown output extension (use .csv, .json, .svg, .off, .ply or .obj)"};
}

}  // namespace constrict
