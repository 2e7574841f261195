// SPDX-License-Identifier: GPL-3.0-or-later
// 2D polygon and ring-set writers (.idx .csv .geojson .wkt .svg .rings). Exact shortest decimals
// via std::to_chars.
#include <algorithm>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "constrict/io.hpp"
#include "io/detail/write_util.hpp"

namespace constrict {
namespace {
using detail::put_double;
using detail::put_int;

void coords(std::string& s, const double* p, char sep) {
  put_double(s, p[0]);
  s += sep;
  put_double(s, p[1]);
}

// The optional graph layer under a polygon or rings picture: its 2D edges, dashed.
void graph_layer(std::string& s, const detail::SvgFrame& fr, const PointSet& pts, const PolygonSvgLayers* layers) {
  if (!layers || !layers->graph || layers->graph->dim != 2) return;
  const GammaFaces& g = *layers->graph;
  s += "<g stroke=\"#8a8a8a\" stroke-width=\"0.7\" stroke-dasharray=\"4 3\" fill=\"none\">\n";
  for (std::size_t f = 0; f < g.size(); ++f)
    fr.line(s, pts[static_cast<std::size_t>(g.vertex(f, 0))], pts[static_cast<std::size_t>(g.vertex(f, 1))]);
  s += "</g>\n";
}

std::string to_svg(const PointSet& pts, const std::vector<int>& b, const PolygonSvgLayers* layers) {
  const detail::SvgFrame fr(pts);
  std::string s = fr.open(layers && !layers->title.empty() ? layers->title : "constrict polygon");
  graph_layer(s, fr, pts, layers);
  s += "<polygon fill=\"#dce8f5\" fill-opacity=\"0.6\" stroke=\"#1f4e8c\" stroke-width=\"1.6\" "
       "stroke-linejoin=\"round\" points=\"";
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (i) s += ' ';
    const double* p = pts[static_cast<std::size_t>(b[i])];
    put_double(s, fr.x(p[0]));
    s += ',';
    put_double(s, fr.y(p[1]));
  }
  s += "\"/>\n";
  if (layers && !layers->highlight_edges.empty()) {
    s += "<g stroke=\"#e67e22\" stroke-width=\"2.4\" fill=\"none\">\n";
    for (const auto& e : layers->highlight_edges)
      fr.line(s, pts[static_cast<std::size_t>(e[0])], pts[static_cast<std::size_t>(e[1])]);
    s += "</g>\n";
  }
  const double r = detail::SvgFrame::point_radius(pts.size());
  s += "<g fill=\"#c0392b\">\n";
  for (std::size_t i = 0; i < pts.size(); ++i) fr.circle(s, pts[i], r);
  s += "</g>\n";
  if (layers && !layers->highlight_points.empty()) {
    s += "<g fill=\"none\" stroke=\"#8e44ad\" stroke-width=\"1.5\">\n";
    for (int i : layers->highlight_points) fr.circle(s, pts[static_cast<std::size_t>(i)], 2.5 * r + 2);
    s += "</g>\n";
  }
  s += "</svg>\n";
  return s;
}

// The ring-set text format (io.hpp write_rings2(); the shared ground truth's layout).
std::string rings_text(std::size_t n_points, const std::vector<Ring2>& rings) {
  std::size_t shells = 0;
  for (const Ring2& r : rings) shells += r.role == RingRole::Shell;
  std::string s = "# constrict rings ";
  put_int(s, static_cast<long long>(rings.size()));
  s += " shells ";
  put_int(s, static_cast<long long>(shells));
  s += " holes ";
  put_int(s, static_cast<long long>(rings.size() - shells));
  s += " points ";
  put_int(s, static_cast<long long>(n_points));
  s += '\n';
  for (std::size_t k = 0; k < rings.size(); ++k) {
    s += "# ring ";
    put_int(s, static_cast<long long>(k));
    s += rings[k].role == RingRole::Shell ? " shell parent " : " hole parent ";
    put_int(s, rings[k].parent);
    s += '\n';
  }
  for (const Ring2& r : rings) {
    s += 'c';
    for (int i : r.indices) {
      s += ' ';
      put_int(s, i);
    }
    s += '\n';
  }
  return s;
}

// A closed ring of coordinates: `[[x, y], ..., [x0, y0]]` (GeoJSON) or `(x y, ..., x0 y0)` (WKT).
void ring_coords(std::string& s, const PointSet& pts, const std::vector<int>& b, bool json) {
  s += json ? '[' : '(';
  for (std::size_t k = 0; k <= b.size(); ++k) {
    if (k) s += ", ";
    if (json) s += '[';
    coords(s, pts[static_cast<std::size_t>(b[k % b.size()])], json ? ',' : ' ');
    if (json) s += ']';
  }
  s += json ? ']' : ')';
}

// The polygons of a ring set: each shell with the holes whose parent it is (OGC / RFC 7946 model).
std::vector<std::vector<std::size_t>> polygons_of(const std::vector<Ring2>& rings) {
  std::vector<std::vector<std::size_t>> polys;
  std::vector<long long> poly_of(rings.size(), -1);
  for (std::size_t k = 0; k < rings.size(); ++k)
    if (rings[k].role == RingRole::Shell) {
      poly_of[k] = static_cast<long long>(polys.size());
      polys.push_back({k});
    }
  for (std::size_t k = 0; k < rings.size(); ++k)
    if (rings[k].role == RingRole::Hole && rings[k].parent >= 0 && poly_of[static_cast<std::size_t>(rings[k].parent)] >= 0)
      polys[static_cast<std::size_t>(poly_of[static_cast<std::size_t>(rings[k].parent)])].push_back(k);
  return polys;
}

// GeoJSON (json) or WKT text of a ring set: Polygon for one shell, MultiPolygon for several.
std::string multipolygon_text(const PointSet& pts, const std::vector<Ring2>& rings, bool json) {
  const auto polys = polygons_of(rings);
  const bool multi = polys.size() > 1;
  std::string s;
  const auto polygon = [&](const std::vector<std::size_t>& p) {
    s += json ? '[' : '(';
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (i) s += ", ";
      ring_coords(s, pts, rings[p[i]].indices, json);
    }
    s += json ? ']' : ')';
  };
  if (json) {
    s += "{\"type\": \"Feature\", \"properties\": {\"generator\": \"constrict\", \"vertices\": ";
    put_int(s, static_cast<long long>(pts.size()));
    s += ", \"rings\": ";
    put_int(s, static_cast<long long>(rings.size()));
    s += multi ? "}, \"geometry\": {\"type\": \"MultiPolygon\", \"coordinates\": " : "}, \"geometry\": {\"type\": \"Polygon\", \"coordinates\": ";
  } else {
    s += multi ? "MULTIPOLYGON " : "POLYGON ";
  }
  if (multi) s += json ? '[' : '(';
  for (std::size_t i = 0; i < polys.size(); ++i) {
    if (i) s += ", ";
    polygon(polys[i]);
  }
  if (multi) s += json ? ']' : ')';
  s += json ? "}}\n" : "\n";
  return s;
}

std::string rings_svg(const PointSet& pts, const std::vector<Ring2>& rings, const PolygonSvgLayers* layers) {
  const detail::SvgFrame fr(pts);
  std::string s = fr.open(layers && !layers->title.empty() ? layers->title : "constrict rings");
  graph_layer(s, fr, pts, layers);
  s += "<path fill=\"#dce8f5\" fill-opacity=\"0.6\" fill-rule=\"evenodd\" stroke=\"#1f4e8c\" stroke-width=\"1.6\" "
       "stroke-linejoin=\"round\" d=\"";
  for (const Ring2& r : rings) {
    for (std::size_t i = 0; i < r.indices.size(); ++i) {
      const double* p = pts[static_cast<std::size_t>(r.indices[i])];
      s += i ? " L" : "M";
      put_double(s, fr.x(p[0]));
      s += ',';
      put_double(s, fr.y(p[1]));
    }
    s += " Z ";
  }
  s += "\"/>\n";
  const double rad = detail::SvgFrame::point_radius(pts.size());
  s += "<g fill=\"#c0392b\">\n";
  for (std::size_t i = 0; i < pts.size(); ++i) fr.circle(s, pts[i], rad);
  s += "</g>\n</svg>\n";
  return s;
}

}  // namespace

PolygonFormat polygon_format_from_path(const std::string& path) noexcept {
  try {
    const std::string e = detail::extension(path);
    if (e == "idx") return PolygonFormat::Idx;
    if (e == "csv") return PolygonFormat::Csv;
    if (e == "geojson" || e == "json") return PolygonFormat::GeoJson;
    if (e == "wkt") return PolygonFormat::Wkt;
    if (e == "svg") return PolygonFormat::Svg;
    if (e == "rings") return PolygonFormat::Rings;
  } catch (...) {
  }
  return PolygonFormat::Auto;
}

// One index per line. Large polygons are formatted in blocks on all cores, each into its own
// string, then joined in order: the same text as one sequential pass.
static std::string index_lines(const std::vector<int>& ids) {
  constexpr std::size_t kBlock = std::size_t{1} << 16;
  const auto format = [&](std::size_t b, std::size_t e, std::string& out) {
    out.reserve(out.size() + (e - b) * 12);
    for (std::size_t k = b; k < e; ++k) {
      put_int(out, ids[k]);
      out += '\n';
    }
  };
  std::string s;
  if (ids.size() < 2 * kBlock) {
    format(0, ids.size(), s);
    return s;
  }
  std::vector<std::string> part((ids.size() + kBlock - 1) / kBlock);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, part.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t p = r.begin(); p != r.end(); ++p)
      format(p * kBlock, std::min(ids.size(), (p + 1) * kBlock), part[p]);
  });
  std::size_t total = 0;
  for (const std::string& p : part) total += p.size();
  s.reserve(total);
  for (const std::string& p : part) s += p;
  return s;
}

Status write_polygon2(const std::string& path, const PointSet& points, const std::vector<int>& boundary,
                      PolygonFormat format, const PolygonSvgLayers* layers) {
  if (points.dim != 2) return {StatusCode::InvalidArgument, path + ": a polygon needs 2D points"};
  if (Status st = detail::check_finite_coordinates(path, points); !st) return st;
  // (Fewer made "POLYGON (())" in WKT, an empty GeoJSON ring: files other programs refuse.)
  if (boundary.size() < 3)
    return {StatusCode::InvalidArgument, path + ": a polygon needs at least 3 vertices, got " + std::to_string(boundary.size())};
  for (int i : boundary)
    if (i < 0 || static_cast<std::size_t>(i) >= points.size())
      return {StatusCode::InvalidArgument, path + ": polygon index " + std::to_string(i) + " out of range"};
  if (format == PolygonFormat::Auto) format = polygon_format_from_path(path);
  std::string s;
  if (format != PolygonFormat::Idx) s.reserve(boundary.size() * 24 + 64);  // (index_lines sizes its own)
  switch (format) {
    case PolygonFormat::Idx: s = index_lines(boundary); break;
    case PolygonFormat::Csv:
      s += "x,y\n";
      for (int i : boundary) {
        coords(s, points[static_cast<std::size_t>(i)], ',');
        s += '\n';
      }
      break;
    case PolygonFormat::GeoJson: {
      s += "{\"type\": \"Feature\", \"properties\": {\"generator\": \"constrict\", \"vertices\": ";
      put_int(s, static_cast<long long>(boundary.size()));
      s += "}, \"geometry\": {\"type\": \"Polygon\", \"coordinates\": [[";
      for (std::size_t k = 0; k <= boundary.size() && !boundary.empty(); ++k) {
        if (k) s += ", ";
        s += '[';
        coords(s, points[static_cast<std::size_t>(boundary[k % boundary.size()])], ',');
        s += ']';
      }
      s += "]]}}\n";
      break;
    }
    case PolygonFormat::Wkt:
      s += "POLYGON ((";
      for (std::size_t k = 0; k <= boundary.size() && !boundary.empty(); ++k) {
        if (k) s += ", ";
        coords(s, points[static_cast<std::size_t>(boundary[k % boundary.size()])], ' ');
      }
      s += "))\n";
      break;
    case PolygonFormat::Svg:
      s = to_svg(points, boundary, layers);
      break;
    case PolygonFormat::Rings: {
      Ring2 shell;
      shell.indices = boundary;
      s = rings_text(points.size(), {shell});
      break;
    }
    case PolygonFormat::Auto:
      return {StatusCode::InvalidArgument,
              path + ": unknown output extension (use .idx, .csv, .geojson, .wkt, .svg or .rings)"};
  }
  return detail::write_file(path, s);
}

Status write_rings2(const std::string& path, const PointSet& points, const std::vector<Ring2>& rings,
                    PolygonFormat format, const PolygonSvgLayers* layers) {
  if (points.dim != 2) return {StatusCode::InvalidArgument, path + ": rings need 2D points"};
  if (Status st = detail::check_finite_coordinates(path, points); !st) return st;
  if (rings.size() == 1 && rings[0].role == RingRole::Shell)
    return write_polygon2(path, points, rings[0].indices, format, layers);
  for (std::size_t k = 0; k < rings.size(); ++k) {
    const Ring2& r = rings[k];
    if (r.indices.size() < 3) return {StatusCode::InvalidArgument, path + ": ring " + std::to_string(k) + " has fewer than 3 vertices"};
    if (r.parent < -1 || r.parent >= static_cast<int>(rings.size()))
      return {StatusCode::InvalidArgument, path + ": ring " + std::to_string(k) + " has parent " + std::to_string(r.parent) + ", out of range"};
    for (int i : r.indices)
      if (i < 0 || static_cast<std::size_t>(i) >= points.size())
        return {StatusCode::InvalidArgument, path + ": ring index " + std::to_string(i) + " out of range"};
  }
  if (format == PolygonFormat::Auto) format = polygon_format_from_path(path);
  std::string s;
  switch (format) {
    case PolygonFormat::Idx:
    case PolygonFormat::Csv:
      return {StatusCode::InvalidArgument, path + ": .idx and .csv hold one polygon; " + std::to_string(rings.size()) +
                                               " rings need .rings, .geojson, .wkt or .svg"};
    case PolygonFormat::GeoJson: s = multipolygon_text(points, rings, true); break;
    case PolygonFormat::Wkt: s = multipolygon_text(points, rings, false); break;
    case PolygonFormat::Svg: s = rings_svg(points, rings, layers); break;
    case PolygonFormat::Rings: s = rings_text(points.size(), rings); break;
    case PolygonFormat::Auto:
      return {StatusCode::InvalidArgument, path + ": unknown output extension (use .rings, .geojson, .wkt or .svg)"};
  }
  return detail::write_file(path, s);
}

}  // namespace constrict
