// SPDX-License-Identifier: GPL-3.0-or-later
// GeoJSON input (RFC 7946): the positions of Point and MultiPoint geometries, in document order,
// inside a FeatureCollection, a Feature, a GeometryCollection or bare. Properties are ignored.
// Every error names the place by a JSON pointer (RFC 6901), e.g. "/features/3/geometry".
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "io/detail/geojson.hpp"
#include "io/detail/scan.hpp"

namespace constrict {
namespace detail {
namespace {

using Json = nlohmann::json;

class GeoJsonPoints {
 public:
  GeoJsonPoints(const std::string& name, int forced_dim, PointSet& out)
      : name_(name), dim_(forced_dim), out_(out) {}

  // Nesting of collections and features beyond this is refused (RFC 7946 §3.1.8 asks not to
  // nest GeometryCollections at all): every level costs stack and a longer error location.
  static constexpr int kMaxDepth = 64;

  // geometry_only: j is in a Feature's "geometry" or a GeometryCollection's "geometries", where
  // RFC 7946 allows geometry objects only (no Feature, no FeatureCollection).
  Status object(const Json& j, const std::string& at, bool geometry_only = false, int depth = 0) {
    if (!j.is_object() || !j.contains("type") || !j["type"].is_string())
      return bad(at, "not a GeoJSON object (an object with a \"type\" member)");
    const std::string type = j["type"].get<std::string>();
    if (geometry_only && (type == "Feature" || type == "FeatureCollection"))
      return bad(at, "a " + type + " where RFC 7946 allows a geometry only (Point, MultiPoint, GeometryCollection, ...)");
    const bool nests = type == "FeatureCollection" || type == "GeometryCollection" || type == "Feature";
    if (nests && depth >= kMaxDepth)
      return bad(at.substr(0, 60) + (at.size() > 60 ? "..." : ""),
                 "collections and features nested deeper than " + std::to_string(kMaxDepth) + " levels; flatten the file");
    if (type == "FeatureCollection") return list(j, at, "features", false, depth + 1);
    if (type == "GeometryCollection") return list(j, at, "geometries", true, depth + 1);
    if (type == "Feature") {
      if (!j.contains("geometry")) return bad(at, "Feature without a \"geometry\" member");
      const Json& g = j["geometry"];
      return g.is_null() ? Status::ok() : object(g, at + "/geometry", true, depth + 1);  // unlocated: no point
    }
    // (The type is the file's text: quoted, so that a control character cannot break the line.)
    const std::string shown = quote(type.data(), type.data() + type.size());
    if (!j.contains("coordinates")) return bad(at, shown + " without \"coordinates\"");
    const Json& c = j["coordinates"];
    if (type == "Point") return position(c, at + "/coordinates");
    if (type == "MultiPoint") {
      if (!c.is_array()) return bad(at + "/coordinates", "MultiPoint coordinates must be an array of positions");
      for (std::size_t i = 0; i < c.size(); ++i) {
        Status st = position(c[i], at + "/coordinates/" + std::to_string(i));
        if (!st) return st;
      }
      return Status::ok();
    }
    return bad(at, "geometry type " + shown +
                       " is not a point set; only Point and MultiPoint are read (take the "
                       "vertices out of lines and polygons first)");
  }

  int dim() const noexcept { return dim_ == 0 ? 2 : dim_; }

 private:
  Status bad(const std::string& at, const std::string& what) const {
    return error_in(StatusCode::ParseError, name_, (at.empty() ? "/" : at) + ": " + what);
  }

  Status list(const Json& j, const std::string& at, const char* member, bool geometry_only, int depth) {
    if (!j.contains(member) || !j[member].is_array())
      return bad(at, std::string("\"") + member + "\" must be an array");
    const Json& items = j[member];
    for (std::size_t i = 0; i < items.size(); ++i) {
      Status st = object(items[i], at + "/" + member + "/" + std::to_string(i), geometry_only, depth);
      if (!st) return st;
    }
    return Status::ok();
  }

  Status position(const Json& p, const std::string& at) {
    if (!p.is_array() || p.size() < 2 || p.size() > 3)
      return bad(at, "a position must be an array of 2 or 3 numbers");
    for (const Json& v : p)
      if (!v.is_number()) return bad(at, "a position must be an array of 2 or 3 numbers");
    if (first_count_ == 0) first_count_ = p.size();
    if (p.size() != first_count_)
      return bad(at, "position with " + std::to_string(p.size()) + " coordinates, the first one had " +
                         std::to_string(first_count_));
    if (dim_ == 0) dim_ = static_cast<int>(p.size());
    if (p.size() < static_cast<std::size_t>(dim_))
      return bad(at, "position with 2 coordinates, but dimension 3 was requested");
    for (int k = 0; k < dim_; ++k) {
      const double v = p[static_cast<std::size_t>(k)].get<double>();
      if (!std::isfinite(v))
        return error_in(StatusCode::NonFinite, name_, at + ": non-finite coordinate");
      out_.coords.push_back(v);
    }
    return Status::ok();
  }

  const std::string& name_;
  int dim_;
  std::size_t first_count_ = 0;
  PointSet& out_;
};

}  // namespace

Status read_geojson_points(std::string_view data, const std::string& name, int forced_dim,
                           PointSet& out) {
  // nlohmann's messages start with "[json.exception.parse_error.101] "; the rest is kept, e.g.
  // "parse error at line 2, column 18: syntax error while parsing value - invalid literal; ...".
  const auto reason = [](const Json::exception& e) {
    std::string why = e.what();
    const std::size_t close = why.find("] ");
    return close == std::string::npos ? why : why.substr(close + 2);
  };
  Json doc;
  try {
    doc = Json::parse(data.begin(), data.end());
  } catch (const Json::out_of_range& e) {  // 406: a number beyond the range of a double
    return error_in(StatusCode::NonFinite, name, reason(e));
  } catch (const Json::exception& e) {
    return error_in(StatusCode::ParseError, name, "not valid JSON: " + reason(e));
  }
  GeoJsonPoints reader(name, forced_dim, out);
  Status st = reader.object(doc, "");
  if (st) out.dim = reader.dim();
  return st;
}

}  // namespace detail
}  // namespace constrict
