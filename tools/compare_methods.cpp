// SPDX-License-Identifier: GPL-3.0-or-later
// constrict_compare: runs every reconstruction method on folders of point sets and writes one
// table (Markdown or CSV): validity, points on the boundary, ground truth recovered, Hausdorff and
// mean distance to the ground truth (compare.hpp, relative to the GT bounding-box diagonal), time.
// Layouts understood (docs/comparison-methods.md, "Comparison table"):
//   DIR/points/NAME.xy with optional DIR/gt/NAME.gt   (../shared/data/2d)
//   DIR/NAME.xyz with optional DIR/NAME_gt.off          (../shared/data/3d; GT vertex i = point i)
//   DIR/NAME.xy, DIR/NAME.xyz                            (anything else, no ground truth)
// Methods: gamma, min-area-change, boissonnat, voronoi-skeleton; a suffix ":paper" runs the 3D
// constriction with Constrict3Options::paper() (no Refine3 post-pass, two-face key = sum).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "constrict/compare.hpp"
#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/metrics.hpp"
#include "constrict/validate.hpp"
#include "constrict/voronoi_skeleton.hpp"

namespace fs = std::filesystem;
using namespace constrict;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Input {
  std::string dir, name;
  fs::path points, gt;  // gt empty when absent
  int dim = 2;
};

struct Row {
  std::string dir, name, method;
  int dim = 2;
  std::size_t n = 0, on_boundary = 0;
  bool ok = false;        // the method ran (input accepted, no internal error)
  bool complete = false;  // every point on the boundary
  bool valid = false;     // complete and validated
  std::string error;
  // 2D ground truth
  bool gt = false, gt_single = false, exact = false;
  double recall = -1;
  // 3D ground truth
  double tri_recovered = -1, area_ratio = -1, volume_ratio = -1;
  double roughness = -1, gt_roughness = -1;  // mean angle between the normals of adjacent faces (deg)
  // Distances to the ground truth (compare_meshes3 / compare_curves2, default sampling), relative
  // to the GT bounding-box diagonal: symmetric Hausdorff, both one-sided values, mean of the two
  // mean distances; -1 without ground truth or when the comparison was refused.
  double hausdorff = -1, hausdorff_to_gt = -1, hausdorff_from_gt = -1, mean_dist = -1;
  double ms_compare = 0;               // time of the distance computation (not in ms_total)
  double ms_total = 0, ms_method = 0;  // wall time of the library call; method part (no Delaunay)
  std::string note;                    // seeds for the skeleton
};

std::vector<Input> scan(const std::string& dir) {
  std::vector<Input> out;
  const fs::path d(dir);
  const bool layout2d = fs::is_directory(d / "points");
  const fs::path pdir = layout2d ? d / "points" : d;
  if (!fs::is_directory(pdir)) return out;
  for (const auto& e : fs::directory_iterator(pdir)) {
    const std::string ext = e.path().extension().string();
    if (ext != ".xy" && ext != ".xyz") continue;
    Input in;
    in.dir = d.filename().string();
    in.name = e.path().stem().string();
    in.points = e.path();
    in.dim = ext == ".xy" ? 2 : 3;
    if (layout2d && fs::exists(d / "gt" / (in.name + ".gt"))) in.gt = d / "gt" / (in.name + ".gt");
    if (!layout2d && fs::exists(d / (in.name + ".gt"))) in.gt = d / (in.name + ".gt");
    if (fs::exists(d / (in.name + "_gt.off"))) in.gt = d / (in.name + "_gt.off");
    out.push_back(in);
  }
  std::sort(out.begin(), out.end(), [](const Input& a, const Input& b) { return a.name < b.name; });
  return out;
}

// Roughness: mean angle (degrees) between the normals of the two faces of every edge.
double mean_normal_angle(const PointSet& p, const TriMesh3& m) {
  std::map<std::pair<int, int>, std::vector<std::size_t>> edges;
  std::vector<std::array<double, 3>> nrm(m.triangles.size());
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const auto& t = m.triangles[f];
    const double* a = p[static_cast<std::size_t>(t[0])];
    const double* b = p[static_cast<std::size_t>(t[1])];
    const double* c = p[static_cast<std::size_t>(t[2])];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    std::array<double, 3> n{{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]}};
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0)
      for (double& x : n) x /= l;
    nrm[f] = n;
    for (int i = 0; i < 3; ++i) {
      const int x = t[static_cast<std::size_t>(i)], y = t[static_cast<std::size_t>((i + 1) % 3)];
      edges[{std::min(x, y), std::max(x, y)}].push_back(f);
    }
  }
  double sum = 0;
  std::size_t k = 0;
  for (const auto& e : edges) {
    if (e.second.size() != 2) continue;
    const auto& a = nrm[e.second[0]];
    const auto& b = nrm[e.second[1]];
    const double d = std::max(-1.0, std::min(1.0, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
    sum += std::acos(d) * 180.0 / 3.14159265358979323846;
    ++k;
  }
  return k ? sum / static_cast<double>(k) : -1;
}

// The row fields of a Voronoi-skeleton run (the 2D and 3D results share these member names).
template <class Result> void skeleton_row(const Result& r, Row& row) {
  row.ok = true;
  row.complete = r.complete;
  row.valid = r.complete && r.validated && r.check.reason.empty();
  row.ms_method = r.stats.ms_grow;
  char buf[96];
  std::snprintf(buf, sizeof buf, "seeds %zu/%zu, %zu complete", r.stats.seeds_tried, r.stats.simplices,
                r.stats.seeds_complete);
  row.note = buf;
}

void run2(const Input& in, const PointSet& p, const std::string& method, std::size_t seed_limit, Row& row) {
  std::vector<int> boundary;
  const auto t0 = Clock::now();
  if (method == "voronoi-skeleton") {
    VoronoiSkeletonOptions o;
    o.seed_limit = seed_limit;
    VoronoiSkeleton2Result r;
    const Status s = voronoi_skeleton2(p, o, r);
    row.ms_total = ms_since(t0);
    if (!s) { row.error = s.message(); return; }
    skeleton_row(r, row);
    boundary = r.boundary;
  } else {
    Constrict2Options o;
    (void)criterion_from_name(method.substr(0, method.find(':')), o.criterion);
    Polygon2Result r;
    const Status s = reconstruct2(p, o, r);
    row.ms_total = ms_since(t0);
    if (!s) { row.error = s.message(); return; }
    row.ok = true;
    row.complete = r.complete;
    row.valid = r.complete && r.validated && r.check.reason.empty();
    row.ms_method = r.ms_constrict + r.ms_fallback;
    boundary = r.boundary;
    row.note = r.method;
  }
  row.on_boundary = boundary.size();
  if (in.gt.empty()) return;
  Reference2 ref;
  if (!read_reference2(in.gt.string(), p.size(), ref)) return;
  row.gt = true;
  row.gt_single = ref.single_closed_curve();
  const PolygonComparison c = compare_polygon2(boundary, ref);
  row.exact = row.gt_single && c.exact_match;
  row.recall = c.edge_recall;
  if (boundary.size() < 3) return;
  CurveDistance2 d;
  const auto tc = Clock::now();
  if (compare_curves2({polygon_polyline2(p, boundary)}, reference_polylines2(p, ref), d)) {
    row.hausdorff = d.relative_hausdorff;
    row.hausdorff_to_gt = d.hausdorff_result_to_reference / d.bbox_diagonal;
    row.hausdorff_from_gt = d.hausdorff_reference_to_result / d.bbox_diagonal;
    row.mean_dist = d.relative_mean;
  }
  row.ms_compare = ms_since(tc);
}

void run3(const Input& in, const PointSet& p, const std::string& method, std::size_t seed_limit, Row& row) {
  TriMesh3 mesh;
  const auto t0 = Clock::now();
  const std::string base = method.substr(0, method.find(':'));
  if (base == "voronoi-skeleton") {
    VoronoiSkeletonOptions o;
    o.seed_limit = seed_limit;
    VoronoiSkeleton3Result r;
    const Status s = voronoi_skeleton3(p, o, r);
    row.ms_total = ms_since(t0);
    if (!s) { row.error = s.message(); return; }
    skeleton_row(r, row);
    row.on_boundary = p.size() - r.unplaced_points.size();
    mesh = std::move(r.mesh);
  } else {
    Constrict3Options o = method.find(":paper") != std::string::npos ? Constrict3Options::paper() : Constrict3Options{};
    (void)criterion_from_name(base, o.criterion);
    Mesh3Result r;
    const Status s = reconstruct3(p, o, r);
    row.ms_total = ms_since(t0);
    if (!s) { row.error = s.message(); return; }
    row.ok = true;
    row.complete = r.complete;
    MeshCheck mc;
    row.valid = r.complete && validate_mesh3(p, r.mesh, &mc).is_ok();
    row.ms_method = r.ms_grow + r.ms_fill + r.ms_constrict + r.ms_fallback + r.ms_sculpt + r.ms_carve + r.ms_refine;
    row.on_boundary = p.size() - r.unplaced_points.size();
    mesh = std::move(r.mesh);
    row.note = std::string(to_string(r.method)) + (r.cavities ? ", " + std::to_string(r.cavities) + " cavities" : "");
  }
  if (in.gt.empty()) return;
  // The GT mesh with its own vertex list (GT vertex i = point i in the shared data, but neither the
  // triangle matching nor the distances rely on it).
  PointSet gp;
  TriMesh3 gt;
  if (!read_mesh(in.gt.string(), gp, gt)) return;
  row.gt = true;
  MeshDistance d;
  const auto tc = Clock::now();
  if (compare_meshes3(p, mesh, gp, gt, d)) {
    row.tri_recovered = d.triangle_recovery;
    row.hausdorff = d.relative_hausdorff;
    row.hausdorff_to_gt = d.hausdorff_result_to_reference / d.bbox_diagonal;
    row.hausdorff_from_gt = d.hausdorff_reference_to_result / d.bbox_diagonal;
    row.mean_dist = d.relative_mean;
  }
  row.ms_compare = ms_since(tc);
  // |volume|: some GT meshes are oriented inward.
  const double ga = mesh_area(gp, gt), gv = std::abs(mesh_volume(gp, gt));
  row.area_ratio = ga > 0 ? mesh_area(p, mesh) / ga : -1;
  row.volume_ratio = gv > 0 ? std::abs(mesh_volume(p, mesh)) / gv : -1;
  row.roughness = mean_normal_angle(p, mesh);
  row.gt_roughness = mean_normal_angle(gp, gt);
}

std::string fmt(double v, const char* f = "%.3f") {
  if (v < 0) return "-";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// Relative distance for the CSV: n/a without ground truth, "-" when the comparison failed.
std::string na(const Row& r, double v) { return r.gt ? fmt(v, "%.6f") : "n/a"; }

void write_csv(std::ostream& o, const std::vector<Row>& rows) {
  o << "dir,name,dim,n,method,ok,complete,valid,on_boundary,gt,gt_single,exact,edge_recall,tri_recovered,"
       "area_ratio,volume_ratio,roughness_deg,gt_roughness_deg,hausdorff,hausdorff_result_to_gt,hausdorff_gt_to_result,"
       "mean_distance,ms_total,ms_method,ms_compare,note,error\n";
  for (const Row& r : rows)
    o << r.dir << ',' << r.name << ',' << r.dim << ',' << r.n << ',' << r.method << ',' << r.ok << ',' << r.complete
      << ',' << r.valid << ',' << r.on_boundary << ',' << r.gt << ',' << r.gt_single << ',' << r.exact << ','
      << fmt(r.recall, "%.4f") << ',' << fmt(r.tri_recovered, "%.4f") << ',' << fmt(r.area_ratio, "%.4f") << ','
      << fmt(r.volume_ratio, "%.4f") << ',' << fmt(r.roughness, "%.2f") << ',' << fmt(r.gt_roughness, "%.2f") << ','
      << na(r, r.hausdorff) << ',' << na(r, r.hausdorff_to_gt) << ',' << na(r, r.hausdorff_from_gt) << ','
      << na(r, r.mean_dist) << ',' << fmt(r.ms_total, "%.1f") << ',' << fmt(r.ms_method, "%.1f") << ','
      << fmt(r.ms_compare, "%.1f") << ",\""
      << r.note << "\",\"" << r.error << "\"\n";
}

std::string pct(double v) { return v < 0 ? "n/a" : fmt(100.0 * v, "%.2f"); }

void write_md(std::ostream& o, const std::vector<Row>& rows, const std::vector<std::string>& methods) {
  std::map<std::string, std::vector<const Row*>> by_dir;
  for (const Row& r : rows) by_dir[r.dir].push_back(&r);
  for (const auto& [dir, rs] : by_dir) {
    const bool three = !rs.empty() && rs.front()->dim == 3;
    o << "### " << dir << " — summary per method\n\n";
    if (!three) {
      o << "| method | sets | valid & complete | incomplete | failed | exact GT match (single-curve GT) | mean GT edge recall | mean Hausdorff % (GT→result) | mean distance % | total ms | method ms (no Delaunay) |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|\n";
    } else {
      o << "| method | models | valid & complete | incomplete | failed | mean GT triangles recovered | mean area / GT | mean volume / GT | mean normal angle° (GT) | mean Hausdorff % (GT→result) | mean distance % | total ms | method ms (no Delaunay) |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    }
    for (const std::string& m : methods) {
      std::size_t sets = 0, valid = 0, incomplete = 0, failed = 0, single = 0, exact = 0, gt = 0;
      double recall = 0, tri = 0, area = 0, vol = 0, rough = 0, grough = 0, ms = 0, msm = 0;
      double haus = 0, haus_from = 0, mdist = 0;
      std::size_t dist = 0;  // rows with distances
      for (const Row* r : rs) {
        if (r->method != m) continue;
        ++sets;
        if (!r->ok) { ++failed; continue; }
        valid += r->valid;
        incomplete += !r->complete;
        ms += r->ms_total;
        msm += r->ms_method;
        if (r->gt) {
          ++gt;
          recall += std::max(0.0, r->recall);
          tri += std::max(0.0, r->tri_recovered);
          area += std::max(0.0, r->area_ratio);
          vol += std::max(0.0, r->volume_ratio);
          rough += std::max(0.0, r->roughness);
          grough += std::max(0.0, r->gt_roughness);
          if (r->hausdorff >= 0) {
            ++dist;
            haus += r->hausdorff;
            haus_from += r->hausdorff_from_gt;
            mdist += r->mean_dist;
          }
        }
        if (r->gt_single) {
          ++single;
          exact += r->exact;
        }
      }
      if (sets == 0) continue;
      const double g = gt ? static_cast<double>(gt) : 1.0;
      // Distances in % of the GT bounding-box diagonal, averaged over the inputs that have them.
      std::string dcols = "n/a | n/a | ";
      if (dist) {
        const double k = 100.0 / static_cast<double>(dist);
        dcols = fmt(haus * k, "%.2f") + " (" + fmt(haus_from * k, "%.2f") + ") | " + fmt(mdist * k, "%.3f") + " | ";
      }
      o << "| " << m << " | " << sets << " | " << valid << " | " << incomplete << " | " << failed << " | ";
      if (!three)
        o << exact << " / " << single << " | " << fmt(recall / g) << " | " << dcols;
      else
        o << fmt(tri / g) << " | " << fmt(area / g) << " | " << fmt(vol / g) << " | " << fmt(rough / g, "%.1f") << " ("
          << fmt(grough / g, "%.1f") << ") | " << dcols;
      o << fmt(ms, "%.0f") << " | " << fmt(msm, "%.0f") << " |\n";
    }
    o << "\n### " << dir << " — per input" << (three ? "" : " (sets with ground truth)") << "\n\n";
    if (!three) {
      o << "| set | n | single GT |";
      for (const auto& m : methods) o << ' ' << m << " (exact / recall / Hausdorff % / ms) |";
      o << "\n|---|---|---|";
      for (std::size_t i = 0; i < methods.size(); ++i) o << "---|";
      o << '\n';
    } else {
      o << "| model | n |";
      for (const auto& m : methods) o << ' ' << m << " (complete / GT tri / area / vol / angle° / Hausdorff % / ms) |";
      o << "\n|---|---|";
      for (std::size_t i = 0; i < methods.size(); ++i) o << "---|";
      o << '\n';
    }
    std::map<std::string, std::map<std::string, const Row*>> grid;
    for (const Row* r : rs) grid[r->name][r->method] = r;
    for (const auto& [name, ms] : grid) {
      const Row* any = ms.begin()->second;
      if (!three && !any->gt) continue;
      o << "| " << name << " | " << any->n << " |";
      if (!three) o << (any->gt_single ? " yes" : " no") << " |";
      for (const auto& m : methods) {
        auto it = ms.find(m);
        if (it == ms.end()) { o << " |"; continue; }
        const Row* r = it->second;
        if (!r->ok) { o << " error |"; continue; }
        if (!three)
          o << ' ' << (r->valid ? "" : "INVALID/INCOMPLETE ") << (r->exact ? "**exact**" : "-") << " / "
            << fmt(r->recall, "%.2f") << " / " << pct(r->hausdorff) << " / " << fmt(r->ms_total, "%.0f") << " |";
        else
          o << ' ' << (r->complete ? (r->valid ? "yes" : "INVALID") : std::to_string(r->on_boundary) + "/" + std::to_string(r->n))
            << " / " << fmt(r->tri_recovered, "%.3f") << " / " << fmt(r->area_ratio, "%.2f") << " / "
            << fmt(r->volume_ratio, "%.2f") << " / " << fmt(r->roughness, "%.1f") << " / " << pct(r->hausdorff) << " / "
            << fmt(r->ms_total, "%.0f") << " |";
      }
      o << '\n';
    }
    o << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"constrict_compare - run every reconstruction method on folders of point sets, write one table"};
  std::vector<std::string> dirs;
  std::string methods_arg = "gamma,min-area-change,boissonnat,voronoi-skeleton", out;
  std::size_t seed_limit2 = 0, seed_limit3 = 64, skeleton_max_n2 = 3000, big2 = 300, skeleton_max_n3 = 1000000;
  bool quiet = false;
  app.add_option("dirs", dirs, "folders of point sets (see the header of tools/compare_methods.cpp)")->required();
  app.add_option("--methods", methods_arg, "comma-separated: gamma, min-area-change, boissonnat, voronoi-skeleton, "
                                           "<criterion>:paper (3D: paper options)");
  app.add_option("-o,--output", out, "table.md (Markdown) or table.csv; default: Markdown on stdout");
  app.add_option("--seed-limit-2d", seed_limit2, "voronoi-skeleton seeds in 2D for n <= --skeleton-all-seeds-n (0 = all)");
  app.add_option("--skeleton-all-seeds-n", skeleton_max_n2, "2D sets larger than this get --seed-limit-2d-large seeds");
  app.add_option("--seed-limit-2d-large", big2, "voronoi-skeleton seeds for large 2D sets");
  app.add_option("--seed-limit-3d", seed_limit3, "voronoi-skeleton seeds in 3D (0 = all)");
  app.add_option("--skeleton-max-n-3d", skeleton_max_n3, "skip the 3D voronoi-skeleton above this many points");
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  CLI11_PARSE(app, argc, argv);

  std::vector<std::string> methods;
  {
    std::stringstream ss(methods_arg);
    std::string m;
    while (std::getline(ss, m, ',')) {
      Criterion c;
      const std::string base = m.substr(0, m.find(':'));
      if (base != "voronoi-skeleton" && !criterion_from_name(base, c)) {
        std::fprintf(stderr, "constrict_compare: unknown method %s\n", m.c_str());
        return 2;
      }
      methods.push_back(m);
    }
  }
  std::vector<Row> rows;
  for (const std::string& dir : dirs) {
    const std::vector<Input> inputs = scan(dir);
    if (inputs.empty()) std::fprintf(stderr, "constrict_compare: no .xy/.xyz files in %s\n", dir.c_str());
    for (const Input& in : inputs) {
      PointSet p;
      ReadOptions ro;
      ro.dim = in.dim;
      const Status rs = read_points(in.points.string(), ro, p);
      for (const std::string& m : methods) {
        Row row;
        row.dir = in.dir;
        row.name = in.name;
        row.method = m;
        row.dim = in.dim;
        row.n = p.size();
        if (!rs) {
          row.error = rs.message();
          rows.push_back(row);
          continue;
        }
        if (in.dim == 2 && m.find(":paper") != std::string::npos) continue;  // 3D option only
        const bool skel = m == "voronoi-skeleton";
        if (skel && in.dim == 3 && p.size() > skeleton_max_n3) continue;
        const std::size_t limit = in.dim == 3 ? seed_limit3 : (p.size() > skeleton_max_n2 ? big2 : seed_limit2);
        if (!quiet) std::fprintf(stderr, "%s/%s (%zu points): %s ...\n", in.dir.c_str(), in.name.c_str(), p.size(), m.c_str());
        try {
          if (in.dim == 2) run2(in, p, m, limit, row);
          else run3(in, p, m, limit, row);
        } catch (const std::exception& e) {
          row.ok = false;
          row.error = std::string("internal error: ") + e.what();
        }
        rows.push_back(row);
      }
    }
  }
  std::ofstream file;
  std::ostream* o = &std::cout;
  if (!out.empty()) {
    file.open(out);
    if (!file) {
      std::fprintf(stderr, "constrict_compare: cannot write %s\n", out.c_str());
      return 4;
    }
    o = &file;
  }
  if (out.size() > 4 && out.substr(out.size() - 4) == ".csv") write_csv(*o, rows);
  else write_md(*o, rows, methods);
  return 0;
}
