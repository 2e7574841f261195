// SPDX-License-Identifier: GPL-3.0-or-later
// `constrict compare RESULT REFERENCE`: measures a reconstruction against a ground truth.
// 2D: a polygon (.idx .csv .gt) against a .gt reference over the same points (--points);
// 3D: two meshes (.off .ply .obj .stl). The numbers come from the library (compare.hpp, metrics.hpp).
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "constrict/compare.hpp"
#include "constrict/mesh.hpp"
#include "constrict/metrics.hpp"

namespace constrict::cli {
namespace {

// A fraction as a percentage with `decimals` places; from 10^6 % on in the shortest exponent form
// (a far-off vertex gave a 60-digit figure).
std::string percent(double fraction, int decimals) {
  char buf[64];
  const double p = 100 * fraction;
  if (std::fabs(p) < 1e6) std::snprintf(buf, sizeof buf, "%.*f", decimals, p);
  else std::snprintf(buf, sizeof buf, "%.4g", p);
  return buf;
}

struct CompareArgs {
  std::string result, reference, points, report;
  std::string columns;  // --columns: the x,y columns of a text --points file
  double spacing = 2e-3;
  double max_samples = 1e6;  // (a double: "1e6", as the help writes it, is accepted)
  bool quiet = false;
};

// MeshDistance and CurveDistance2 share these fields: one writer keeps the 2D and 3D reports alike.
template <class Distance>
void put_distance(nlohmann::json& j, const Distance& d) {
  j["hausdorff"] = d.hausdorff;
  j["hausdorff_result_to_reference"] = d.hausdorff_result_to_reference;
  j["hausdorff_reference_to_result"] = d.hausdorff_reference_to_result;
  j["mean_result_to_reference"] = d.mean_result_to_reference;
  j["mean_reference_to_result"] = d.mean_reference_to_result;
  j["mean"] = d.mean;
  j["bbox_diagonal"] = d.bbox_diagonal;
  j["relative_hausdorff"] = d.relative_hausdorff;
  j["relative_mean"] = d.relative_mean;
  j["sampling"] = {{"spacing_result", d.spacing_result},
                   {"spacing_reference", d.spacing_reference},
                   {"samples_result", d.samples_result},
                   {"samples_reference", d.samples_reference}};
}

int run_compare2(const CompareArgs& a, nlohmann::json& j, const DistanceOptions& o) {
  if (a.points.empty())
    return fail({StatusCode::InvalidArgument, "2D compare needs --points INPUT (the .gt indices refer to it)"});
  PointSet pts;
  ReadOptions ro;
  ro.check = false;
  if (!a.columns.empty())
    if (Status s = parse_columns(a.columns, ro.columns); !s) return fail(s);
  if (Status s = read_points(a.points, ro, pts); !s) return fail(s);
  // (The dimension from the data: a forced 2 had cut 3D points to x, y without a word.)
  if (pts.dim != 2)
    return fail({StatusCode::InvalidArgument, a.points + ": 3D points; the indices of a 2D result refer to 2D points "
                                                          "(give the 2D input, or choose its x,y columns with --columns)"});
  Reference2 ref;
  if (Status s = read_reference2(a.reference, pts.size(), ref); !s) return fail(s);
  std::vector<std::vector<int>> rings;
  if (Status s = read_rings_result(a.result, pts, rings); !s) return fail(s);
  const RingsComparison rc = compare_rings2(rings, ref);
  const PolygonComparison& pc = rc.edges;
  std::vector<Polyline2> lines;
  for (const auto& r : rings) lines.push_back(polygon_polyline2(pts, r));
  CurveDistance2 d;
  if (Status s = compare_curves2(lines, reference_polylines2(pts, ref), d, o); !s) return fail(s);
  j["dimension"] = 2;
  j["rings"] = {
      {"result", rc.result_rings}, {"reference", rc.reference_rings}, {"same_point_sets", rc.same_point_sets}};
  j["points"] = pts.size();
  j["exact_match"] = pc.exact_match;
  j["reference_edges"] = pc.reference_edges;
  j["result_edges"] = pc.polygon_edges;
  j["recovered_edges"] = pc.recovered_edges;
  j["edge_recall"] = pc.edge_recall;
  j["edge_precision"] = pc.edge_precision;
  put_distance(j, d);
  if (!a.quiet) {
    std::printf("%s: edges recovered %zu/%zu (%.1f%%), precision %.1f%%, hausdorff %.6g (%s%% of bbox diagonal), "
                "mean %.6g (%s%%)\n",
                pc.exact_match ? "exact match" : "differs", pc.recovered_edges, pc.reference_edges,
                100 * pc.edge_recall, 100 * pc.edge_precision, d.hausdorff, percent(d.relative_hausdorff, 3).c_str(), d.mean,
                percent(d.relative_mean, 4).c_str());
    if (rc.result_rings > 1 || rc.reference_rings > 1)
      std::printf("rings: %zu in the result, %zu in the reference, %zu of them with the same point set\n",
                  rc.result_rings, rc.reference_rings, rc.same_point_sets);
  }
  return 0;
}

int run_compare3(const CompareArgs& a, nlohmann::json& j, const DistanceOptions& o) {
  // (They were ignored without a word: a mesh carries its own points.)
  if (!a.points.empty() || !a.columns.empty())
    return fail({StatusCode::InvalidArgument, std::string(a.points.empty() ? "--columns" : "--points") +
                                                  " applies to 2D compare (indices over points); 3D meshes carry their points: drop it"});
  PointSet rp, bp;
  TriMesh3 rm, bm;
  if (!is_mesh_ext(lower_ext(a.result)))
    return fail({StatusCode::InvalidArgument, a.result + ": unknown mesh format (use .off, .ply, .obj or .stl)"});
  if (Status s = read_mesh(a.result, rp, rm); !s) return fail(s);
  if (Status s = read_mesh(a.reference, bp, bm); !s) return fail(s);
  // STL stores 32-bit floats: its vertices are matched to the other mesh's by float rounding.
  DistanceOptions match = o;
  match.match_single_precision = lower_ext(a.result) == "stl" || lower_ext(a.reference) == "stl";
  MeshDistance d;
  if (Status s = compare_meshes3(rp, rm, bp, bm, d, match); !s) return fail(s);
  j["dimension"] = 3;
  j["vertex_matching"] = match.match_single_precision ? "float32" : "exact";
  j["identical"] = d.identical;
  j["reference_triangles"] = d.reference_triangles;
  j["result_triangles"] = d.result_triangles;
  j["recovered_triangles"] = d.recovered_triangles;
  j["triangle_recovery"] = d.triangle_recovery;
  j["triangle_precision"] = d.triangle_precision;
  j["matched_vertices"] = d.matched_vertices;
  put_distance(j, d);
  // Where the worst errors are: the centroid of the triangle holding each one-sided maximum.
  const auto centroid = [](const PointSet& p, const TriMesh3& m, long t) {
    nlohmann::json c = nlohmann::json::array();
    if (t < 0) return c;
    const auto& f = m.triangles[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k)
      c.push_back((p[static_cast<std::size_t>(f[0])][k] + p[static_cast<std::size_t>(f[1])][k] +
                   p[static_cast<std::size_t>(f[2])][k]) / 3);
    return c;
  };
  j["worst"] = {{"result_triangle", d.worst_result_element},
                {"result_at", centroid(rp, rm, d.worst_result_element)},
                {"reference_triangle", d.worst_reference_element},
                {"reference_at", centroid(bp, bm, d.worst_reference_element)}};
  if (!a.quiet)
    std::printf("%s: triangles recovered %zu/%zu (%.1f%%), precision %.1f%%, hausdorff %.6g (%s%% of bbox "
                "diagonal; result->reference %.6g, reference->result %.6g), mean %.6g (%s%%)\n",
                d.identical ? "identical" : "differs", d.recovered_triangles, d.reference_triangles,
                100 * d.triangle_recovery, 100 * d.triangle_precision, d.hausdorff, percent(d.relative_hausdorff, 3).c_str(),
                d.hausdorff_result_to_reference, d.hausdorff_reference_to_result, d.mean, percent(d.relative_mean, 4).c_str());
  return 0;
}

int run_compare(const CompareArgs& a) {
  const auto t0 = Clock::now();
  if (Status s = check_distinct_files({{"RESULT", &a.result}, {"REFERENCE", &a.reference}, {"--points", &a.points}}, {{"--report", &a.report}}); !s)
    return fail(s);
  DistanceOptions o;
  o.relative_spacing = a.spacing;
  // A whole number of samples up to 2^53 (the doubles' whole numbers; larger ones passed unchecked).
  if (!(a.max_samples >= 1 && a.max_samples <= 9007199254740992.0 && std::floor(a.max_samples) == a.max_samples))
    return fail({StatusCode::InvalidArgument, "--max-samples must be a whole number from 1 to 2^53 (for example 1e6)"});
  o.max_samples = static_cast<std::size_t>(a.max_samples);
  nlohmann::json j;
  j["command"] = "compare";
  j["result"] = a.result;
  j["reference"] = a.reference;
  const std::string re = lower_ext(a.reference);
  int rc = 0;
  if (re == "gt") rc = run_compare2(a, j, o);
  else if (is_mesh_ext(re)) rc = run_compare3(a, j, o);
  else
    return fail({StatusCode::InvalidArgument, a.reference + ": unknown reference format (2D .gt; 3D .off .ply .obj .stl)"});
  if (rc != 0) return rc;
  j["timings_ms"] = {{"total", ms(t0, Clock::now())}};
  if (!a.report.empty())
    if (Status s = write_report(a.report, j); !s) return fail(s);
  return 0;
}

}  // namespace

namespace {

// A result visits each point at most once: a repeated index would be counted as recovered edges
// twice over (and is no simple polygon), so it is refused, naming the index.
Status check_no_repeated_index(const std::string& path, const std::vector<std::vector<int>>& rings, std::size_t n) {
  std::vector<std::size_t> ring_of(n, 0);  // 1 + the ring that holds the index, 0: none yet
  for (std::size_t r = 0; r < rings.size(); ++r)
    for (const int i : rings[r]) {
      std::size_t& at = ring_of[static_cast<std::size_t>(i)];
      if (at != 0) {
        const std::string where = rings.size() == 1 ? std::string()
                                  : at == r + 1     ? " (in ring " + std::to_string(r + 1) + ")"
                                                    : " (in rings " + std::to_string(at) + " and " + std::to_string(r + 1) + ")";
        return {StatusCode::ParseError, path + ": index " + std::to_string(i) + " appears twice" + where +
                                            "; a result visits each point at most once"};
      }
      at = r + 1;
    }
  return Status::ok();
}

Status read_rings_any(const std::string& path, const PointSet& pts, std::vector<std::vector<int>>& rings) {
  const std::string e = lower_ext(path);
  if (e != "gt" && e != "rings") {
    rings.emplace_back();
    return read_polygon_result(path, pts, rings.back());
  }
  Reference2 r;
  if (Status s = read_reference2(path, pts.size(), r); !s) return s;
  if (!r.open.empty())
    return {StatusCode::InvalidArgument, path + ": " + std::to_string(r.open.size()) +
                                             " open polyline(s); a result is closed rings ('c' lines) only"};
  for (std::size_t k = 0; k < r.closed.size(); ++k)
    if (r.closed[k].size() < 3)
      return {StatusCode::InvalidArgument, path + ": ring " + std::to_string(k + 1) + " has " +
                                               std::to_string(r.closed[k].size()) + " indices; a ring needs at least 3"};
  rings = r.closed;
  return Status::ok();
}

}  // namespace

Status read_rings_result(const std::string& path, const PointSet& pts, std::vector<std::vector<int>>& rings) {
  rings.clear();
  Status s = read_rings_any(path, pts, rings);
  if (s) s = check_no_repeated_index(path, rings, pts.size());
  if (!s) rings.clear();
  return s;
}

// A 2D polygon result as input indices: .gt (one closed curve), .idx (one index per line) or
// .csv (x,y rows, matched to --points by exact coordinates).
Status read_polygon_result(const std::string& path, const PointSet& pts, std::vector<int>& poly) {
  const std::string e = lower_ext(path);
  poly.clear();
  if (e == "gt") {
    Reference2 r;
    if (Status s = read_reference2(path, pts.size(), r); !s) return s;
    if (!r.single_closed_curve())
      return {StatusCode::InvalidArgument, path + ": the result must be one closed curve"};
    poly = r.closed[0];
    return Status::ok();
  }
  if (e != "idx" && e != "csv")
    return {StatusCode::InvalidArgument, path + ": unknown 2D result format (use .idx, .csv, .gt or .rings)"};
  if (e == "idx") {
    std::ifstream f(path);
    if (!f) return {StatusCode::FileNotFound, path + ": cannot open"};
    std::string line;
    std::size_t lineno = 0;
    while (std::getline(f, line)) {
      ++lineno;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      try {
        std::size_t used = 0;
        const long long v = std::stoll(line, &used);
        if (line.find_first_not_of(" \t\r", used) != std::string::npos) throw std::invalid_argument("trailing");
        if (v < 0 || static_cast<std::size_t>(v) >= pts.size())
          return {StatusCode::ParseError, path + ":" + std::to_string(lineno) + ": index " + std::to_string(v) +
                                              " out of range (" + std::to_string(pts.size()) + " points)"};
        poly.push_back(static_cast<int>(v));
      } catch (const std::exception&) {
        return {StatusCode::ParseError, path + ":" + std::to_string(lineno) + ": malformed index"};
      }
    }
    if (poly.size() < 3) return {StatusCode::ParseError, path + ": a polygon needs at least 3 indices"};
    return Status::ok();
  }
  // .csv: the point reader parses it (header line, two columns).
  PointSet col;
  ReadOptions ro;
  ro.check = false;
  ro.dim = 2;
  if (Status s = read_points(path, ro, col); !s) return s;
  std::map<std::pair<double, double>, int> id;
  for (std::size_t i = 0; i < pts.size(); ++i) id.emplace(std::make_pair(pts[i][0] + 0.0, pts[i][1] + 0.0), static_cast<int>(i));
  for (std::size_t i = 0; i < col.size(); ++i) {
    const auto it = id.find({col[i][0] + 0.0, col[i][1] + 0.0});
    if (it == id.end())
      return {StatusCode::InvalidArgument, path + ": vertex " + std::to_string(i) + " is not one of the input points"};
    poly.push_back(it->second);
  }
  if (poly.size() < 3) return {StatusCode::ParseError, path + ": a polygon needs at least 3 vertices"};
  return Status::ok();
}

Command add_compare_command(CLI::App& app) {
  auto a = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "measure a result against a reference: 2D polygon vs .gt, 3D mesh vs mesh (Hausdorff, recovery)");
  cmd->add_option("RESULT", a->result, "the result: 2D .idx .csv .gt; 3D .off .ply .obj .stl")->required()->check(non_empty_path());
  cmd->add_option("REFERENCE", a->reference, "the reference: 2D .gt; 3D .off .ply .obj .stl")->required()->check(non_empty_path());
  cmd->add_option("--points", a->points, "2D: the input points the indices refer to (required in 2D)")->check(non_empty_path());
  cmd->add_option("--columns", a->columns, "2D: the x,y columns of a text --points file, 1-based numbers (2,3) or header names (x,y)")
      ->check(non_empty());
  cmd->add_option("--report", a->report, "write a JSON report")->check(non_empty_path());
  cmd->add_option("--spacing", a->spacing, "sample spacing relative to the reference's bbox diagonal (default 0.002)")
      ->check(positive_number());
  cmd->add_option("--max-samples", a->max_samples, "at most this many samples per side (default 1e6)")
      ->check(positive_number());
  cmd->add_flag("-q,--quiet", a->quiet, "no summary line");
  return {cmd, [a] { return run_compare(*a); }};
}

}  // namespace constrict::cli
