// SPDX-License-Identifier: GPL-3.0-or-later
// 2D polygon writers (.idx .csv .geojson .wkt .svg). Exact shortest decimals via std::to_chars.
#include <string>
#include <vector>

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

std::string to_svg(const PointSet& pts, const std::vector<int>& b, const PolygonSvgLayers* layers) {
  const detail::SvgFrame fr(pts);
  std::string s = fr.open(layers && !layers->title.empty() ? layers->title : "constrict polygon");
  if (layers && layers->graph && layers->graph->dim == 2) {
    const GammaFaces& g = *layers->graph;
    s += "<g stroke=\"#8a8a8a\" stroke-width=\"0.7\" stroke-dasharray=\"4 3\" fill=\"none\">\n";
    for (std::size_t f = 0; f < g.size(); ++f)
      fr.line(s, pts[static_cast<std::size_t>(g.vertex(f, 0))], pts[static_cast<std::size_t>(g.vertex(f, 1))]);
    s += "</g>\n";
  }
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

}  // namespace

PolygonFormat polygon_format_from_path(const std::string& path) noexcept {
  try {
    const std::string e = detail::extension(path);
    if (e == "idx") return PolygonFormat::Idx;
    if (e == "csv") return PolygonFormat::Csv;
    if (e == "geojson" || e == "json") return PolygonFormat::GeoJson;
    if (e == "wkt") return PolygonFormat::Wkt;
    if (e == "svg") return PolygonFormat::Svg;
  } catch (...) {
  }
  return PolygonFormat::Auto;
}

Status write_polygon2(const std::string& path, const PointSet& points, const std::vector<int>& boundary,
                      PolygonFormat format, const PolygonSvgLayers* layers) {
  if (points.dim != 2) return {StatusCode::InvalidArgument, path + ": a polygon needs 2D points"};
  for (int i : boundary)
    if (i < 0 || static_cast<std::size_t>(i) >= points.size())
      return {StatusCode::InvalidArgument, path + ": polygon index " + std::to_string(i) + " out of range"};
  if (format == PolygonFormat::Auto) format = polygon_format_from_path(path);
  std::string s;
  s.reserve(boundary.size() * 24 + 64);
  switch (format) {
    case PolygonFormat::Idx:
      for (int i : boundary) {
        put_int(s, i);
        s += '\n';
      }
      break;
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
    case PolygonFormat::Auto:
      return {StatusCode::InvalidArgument,
              path + ": unknown output extension (use .idx, .csv, .geojson, .wkt or .svg)"};
  }
  return detail::write_file(path, s);
}

}  // namespace constrict
