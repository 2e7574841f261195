// SPDX-License-Identifier: GPL-3.0-or-later
// `constrict reconstruct`: a simple polygon (2D) through all points. Validates every result.
#include <cstdio>
#include <filesystem>
#include <future>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/mesh.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/io.hpp"
#include "constrict/report.hpp"
#include "constrict/topology.hpp"
#include "constrict/validate.hpp"
#include "constrict/voronoi_skeleton.hpp"

namespace constrict::cli {
namespace {

struct ReconstructArgs {
  InputArgs in;
  std::string out, report, body, fallback = "auto", refine = "auto";
  std::string render;  // --render PICTURE (cmd_render.cpp)
  std::string method = "gamma";  // a Criterion name or "voronoi-skeleton"
  std::size_t seed_limit = 0;    // voronoi-skeleton: 0 = every seed
  bool ascii = false;
  bool fast = false;  // 3D: one variant run instead of the default two
  bool no_grow = false;  // 3D: constriction from the convex hull only
  std::size_t stop_after = SIZE_MAX;
  bool quiet = false;
  std::string topology = "single";  // 2D: single | auto (topology.hpp)
  double topology_gap = kDefaultTopologyGap;
};

// Feeds the constriction's events to the progress printer.
class ProgressVisitor final : public Constrict2Visitor {
 public:
  ProgressVisitor(Progress& p, std::size_t n) : progress_(p), n_(n) {}
  bool wants_triangles() const override { return false; }  // (it counts them)
  void on_event(const Constrict2Event& e) override {
    if (e.kind == Constrict2Event::Kind::StageBegin && e.stage == "refine") {
      stage_ = "refining the polygon (local search)";
      progress_.phase(stage_);
    } else if (e.kind == Constrict2Event::Kind::StageBegin) {
      stage_ = "constricting (" + e.stage + "), triangles removed";
      progress_.phase(stage_);
      removed_ = 0;
    } else if (e.kind == Constrict2Event::Kind::RemoveTriangle || e.kind == Constrict2Event::Kind::InsertPoint) {
      if (stage_.empty()) {
        stage_ = "constricting (gamma), triangles removed";
        progress_.phase(stage_);
      }
      if ((++removed_ & 1023u) == 0) progress_.count(removed_, n_);
    }
  }

 private:
  Progress& progress_;
  std::size_t n_;
  std::size_t removed_ = 0;
  std::string stage_;
};

// --method: the criterion of the constriction, or the Voronoi skeleton (its result in the
// constriction's result type, so that writing and reporting stay one path).
bool is_skeleton(const ReconstructArgs& a) { return a.method == "voronoi-skeleton"; }
nlohmann::json skeleton_json(const VoronoiSkeletonStats& s) {
  return {{"seed_limit", nullptr},          {"simplices", s.simplices},      {"seeds_tried", s.seeds_tried},
          {"seeds_pruned", s.seeds_pruned}, {"seeds_complete", s.seeds_complete}, {"best_seed", s.best_seed},
          {"tree_length", s.tree_length}};
}
void add_method_json(const ReconstructArgs& a, const VoronoiSkeletonStats& s, nlohmann::json& j) {
  j["method_requested"] = a.method;
  j["criterion"] = is_skeleton(a) ? nlohmann::json(nullptr) : nlohmann::json(a.method);
  if (!is_skeleton(a)) return;
  j["voronoi_skeleton"] = skeleton_json(s);
  j["voronoi_skeleton"]["seed_limit"] = a.seed_limit;
}
// The CLI's part of a report: what was read and written.
void add_common_json(const ReconstructArgs& a, const ReadReport& rep, int dim, std::size_t n, std::size_t nb,
                     nlohmann::json& j) {
  j["command"] = "reconstruct";
  j["input"] = a.in.path;
  j["output"] = a.out;
  j["dimension"] = dim;
  j["points"] = n;
  j["points_read"] = rep.points_read;
  j["merged_duplicates"] = rep.merged_duplicates;
  j["boundary_points"] = nb;
  j["merged"] = merged_json(rep);
  j["warnings"] = rep.warnings;
}
const char* incomplete_why(const ReconstructArgs& a, const std::string& method) {
  if (is_skeleton(a)) return "voronoi skeleton: no tried seed grew through every point";
  return method == "stopped" ? "stopped early (--stop-after)" : "constriction locked (--fallback none)";
}

// Options of one dimension given for an input of the other are refused, not ignored (issue 18).
Status check_dimension_options(const ReconstructArgs& a, int dim) {
  if (dim == 2) {
    if (!a.body.empty()) return wrong_dimension("--body", 2, a.in.path);
    if (a.ascii) return wrong_dimension("--ascii", 2, a.in.path);
    if (a.fast) return wrong_dimension("--fast", 2, a.in.path);
    if (a.no_grow) return wrong_dimension("--no-grow", 2, a.in.path);
  } else if (a.ascii && lower_ext(a.out) != "ply") {
    return {StatusCode::InvalidArgument, "--ascii chooses ASCII PLY; " + a.out +
                                             " is not .ply (OFF and OBJ are text anyway, STL is written binary)"};
  } else if (!a.render.empty() && lower_ext(a.render) != "png") {
    // (Checked before the surface is written: the error came after -o's file.)
    return {StatusCode::InvalidArgument, a.render + ": 3D pictures are PNG (--render)"};
  } else if (a.fallback == "gamma0" || a.fallback == "degree4") {
    return {StatusCode::InvalidArgument, "--fallback " + a.fallback + " is a 2D fallback, but " + a.in.path +
                                             " is 3D; 3D has auto (star cavities) or none"};
  }
  return Status::ok();
}

// Indices written are the file's rows, also after --merge-duplicates (docs/cli.md): .idx and
// .rings hold indices; the other formats write coordinates, the same either way.
bool writes_indices(PolygonFormat fmt) { return fmt == PolygonFormat::Idx || fmt == PolygonFormat::Rings; }

Status write_polygon_rows(const std::string& path, const PointSet& pts, const ReadReport& rep,
                          const std::vector<int>& boundary, PolygonFormat fmt, const PolygonSvgLayers* layers) {
  if (rep.merged.empty() || !writes_indices(fmt)) return write_polygon2(path, pts, boundary, fmt, layers);
  std::vector<int> rows(boundary.size());
  for (std::size_t i = 0; i < boundary.size(); ++i) rows[i] = file_row(rep, boundary[i]);
  return write_polygon2(path, file_row_points(pts, rep), rows, fmt, layers);
}

Status write_rings_rows(const std::string& path, const PointSet& pts, const ReadReport& rep, const std::vector<Ring2>& rings,
                        PolygonFormat fmt, const PolygonSvgLayers* layers) {
  if (rep.merged.empty() || !writes_indices(fmt)) return write_rings2(path, pts, rings, fmt, layers);
  std::vector<Ring2> rows = rings;
  for (Ring2& r : rows)
    for (int& v : r.indices) v = file_row(rep, v);
  return write_rings2(path, file_row_points(pts, rep), rows, fmt, layers);
}

// The report's point indices as the file's rows (after --merge-duplicates): the rings, the
// inferred rings of single mode, the points the constriction left inside or unplaced.
void report_rows(const ReadReport& rep, nlohmann::json& j) {
  if (rep.merged.empty()) return;
  const auto rows = [&](nlohmann::json& a) {
    if (!a.is_array()) return;
    for (auto& v : a)
      if (v.is_number_integer()) v = file_row(rep, v.get<int>());
  };
  const auto ring_rows = [&](nlohmann::json& list) {
    if (!list.is_array()) return;
    for (auto& r : list)
      if (r.is_object() && r.contains("indices")) rows(r["indices"]);
  };
  for (const char* key : {"stuck_points", "unplaced_points"})
    if (j.contains(key)) rows(j[key]);
  if (j.contains("rings")) ring_rows(j["rings"]);
  if (j.contains("topology") && j["topology"].is_object() && j["topology"].contains("inferred") &&
      j["topology"]["inferred"].is_object() && j["topology"]["inferred"].contains("ring_list"))
    ring_rows(j["topology"]["inferred"]["ring_list"]);
}

// The surface (and body) with the file's points as vertices, so that face indices are file rows
// (a merged copy is an unused vertex), and the input's normals and colours on PLY vertices.
Status write_surface_rows(const ReconstructArgs& a, const PointSet& pts, const ReadReport& rep, const Mesh3Result& r) {
  const PointAttributes& in = rep.attributes;
  const bool has_attributes = !in.normals.empty() || !in.colors.empty();
  if (has_attributes && lower_ext(a.out) != "ply")
    std::fprintf(stderr, "constrict: warning: %s: the input's normals and colours are written to .ply output only\n",
                 a.out.c_str());
  MeshWriteOptions wopt;
  wopt.ply_ascii = a.ascii;
  if (rep.merged.empty()) {
    wopt.attributes = has_attributes ? &in : nullptr;
    if (Status s = write_mesh(a.out, pts, r.mesh, wopt); !s) return s;
    return a.body.empty() ? Status::ok() : write_body_vtk(a.body, pts, r.tets);
  }
  const PointSet rows = file_row_points(pts, rep);
  const PointAttributes row_attributes = file_row_attributes(rep);
  wopt.attributes = has_attributes ? &row_attributes : nullptr;
  TriMesh3 mesh = r.mesh;
  for (auto& t : mesh.triangles)
    for (int& v : t) v = file_row(rep, v);
  if (Status s = write_mesh(a.out, rows, mesh, wopt); !s) return s;
  if (a.body.empty()) return Status::ok();
  std::vector<std::array<int, 4>> tets = r.tets;
  for (auto& t : tets)
    for (int& v : t) v = file_row(rep, v);
  return write_body_vtk(a.body, rows, tets);
}

// --topology: the library's ring options around the polygon options.
Rings2Options rings_options(const ReconstructArgs& a, const Constrict2Options& polygon, std::size_t n) {
  Rings2Options o;
  (void)topology_from_name(a.topology, o.topology);
  o.topology_gap = a.topology_gap;
  o.infer_in_single = n <= kNoteMaxPoints;  // the note of single mode, where it is cheap
  if (o.topology == Topology2::Single) {    // (and stays cheap)
    o.infer_work_limit = kNoteWorkPerPoint * n;
    o.infer_multi_start = false;
  }
  o.polygon = polygon;
  return o;
}

// One line on stderr: in single mode when the data show several rings (so that auto is found), in
// auto mode when the inference stopped at its work bound (the single polygon was made).
void note_inferred(const ReconstructArgs& a, const Rings2Result& rr) {
  if (!a.quiet && rr.topology == Topology2::Auto && rr.inferred.decision == RingsDecision::Capped)
    std::fprintf(stderr,
                 "note: --topology auto stopped at its work bound (%zu parts, %zu thin parts joined one at a time; "
                 "docs/topology.md \"Many islands\"): made the single polygon through all points instead\n",
                 rr.inferred.parts, rr.inferred.thin_parts_joined);
  if (a.quiet || rr.topology != Topology2::Single || !rr.inferred.several()) return;
  const std::size_t sh = rr.inferred.shells(), ho = rr.inferred.holes();
  std::fprintf(stderr, "note: the points show %zu rings (%zu shell%s, %zu hole%s); try --topology auto\n",
               rr.inferred.rings.size(), sh, sh == 1 ? "" : "s", ho, ho == 1 ? "" : "s");
}

// The SVG layers of a 2D result: the Delaunay edges dashed under it.
Status svg_layers(const ReconstructArgs& a, const PointSet& pts, const std::string& method, GammaFaces& dt_edges,
                  PolygonSvgLayers& layers) {
  GraphSpec spec;
  (void)GraphSpec::from_preset("delaunay", spec);
  if (Status s = build_gamma_graph(pts, spec, dt_edges); !s) return s;
  layers.graph = &dt_edges;
  layers.title = "constrict: " + a.in.path + " (" + method + ")";
  return Status::ok();
}

// --topology auto found several rings: write them (rings formats), report, summary.
int finish_rings2(const ReconstructArgs& a, const PointSet& pts, const ReadReport& rep, const Rings2Result& rr,
                  const Rings2Options& ropt, PolygonFormat fmt, Progress& progress, Clock::time_point t0,
                  Clock::time_point t1) {
  progress.phase("writing");
  const auto tw = Clock::now();
  PolygonSvgLayers layers;
  GammaFaces dt_edges;
  if (fmt == PolygonFormat::Svg)
    if (Status s = svg_layers(a, pts, "rings", dt_edges, layers); !s) return fail(s);
  if (Status s = write_rings_rows(a.out, pts, rep, rr.rings, fmt, &layers); !s) return fail(s);
  const auto t4 = Clock::now();
  const std::size_t n = pts.size(), sh = rr.inferred.shells(), ho = rr.inferred.holes();
  if (!a.report.empty()) {
    nlohmann::json j = nlohmann::json::parse(to_json(rr, ropt));
    add_common_json(a, rep, 2, n, n, j);
    add_method_json(a, VoronoiSkeletonStats{}, j);
    j["timings_ms"].update({{"read", ms(t0, t1)}, {"write", ms(tw, t4)}, {"total", ms(t0, Clock::now())}});
    report_rows(rep, j);
    if (Status s = write_report(a.report, j); !s) return fail(s);
  }
  if (int rc = a.render.empty() ? 0 : render_rings2(a.render, pts, rr.rings)) return rc;
  if (!a.quiet)
    std::printf("%zu rings (%zu shell%s, %zu hole%s) through %zu/%zu points: valid (each simple, disjoint, oriented, nested; "
                "smallest gap %.2f spacings) -> %s (%.0f ms)\n",
                rr.rings.size(), sh, sh == 1 ? "" : "s", ho, ho == 1 ? "" : "s", n, n, rr.inferred.min_gap_spacings,
                a.out.c_str(), ms(t0, Clock::now()));
  return 0;
}

int run_reconstruct2(const ReconstructArgs& a, const PointSet& pts, const ReadReport& rep, Progress& progress,
                     Clock::time_point t0, Clock::time_point t1) {
  const PolygonFormat fmt = polygon_format_from_path(a.out);
  if (fmt == PolygonFormat::Auto)
    return fail(
        {StatusCode::InvalidArgument,
         a.out + ": unknown output extension for a 2D polygon (use .idx, .csv, .geojson, .wkt, .svg or .rings)"});
  Constrict2Options opt;  // --refine none: the paper's algorithm (Constrict2Options::paper())
  (void)Constrict2Options::from_preset(a.refine == "none" ? "paper" : "default", opt);
  (void)fallback_from_name(a.fallback, opt.fallback);
  opt.stop_after = a.stop_after;
  (void)criterion_from_name(a.method, opt.criterion);
  progress.phase(is_skeleton(a) ? "voronoi skeleton growth" : "delaunay + gamma-values");
  ProgressVisitor visitor(progress, pts.size());
  const Rings2Options ropt = rings_options(a, opt, pts.size());
  Rings2Result rr;
  Polygon2Result& r = rr.polygon;
  VoronoiSkeletonStats skel;
  if (is_skeleton(a)) {
    VoronoiSkeletonOptions vo;
    vo.seed_limit = a.seed_limit;
    VoronoiSkeleton2Result v;
    if (Status s = voronoi_skeleton2(pts, vo, v); !s) return fail_in(a.in.path, rep, s);
    skel = v.stats;
    r = as_reconstruction(std::move(v));
  } else if (Status s = reconstruct_rings2(pts, ropt, rr, progress.enabled() ? &visitor : nullptr); !s) {
    return fail_in(a.in.path, rep, s);
  } else if (!rr.from_polygon) {
    return finish_rings2(a, pts, rep, rr, ropt, fmt, progress, t0, t1);
  }
  note_inferred(a, rr);
  if (is_skeleton(a)) rr.rings = {Ring2{RingRole::Shell, -1, r.boundary}};

  // reconstruct2 validated the polygon exactly (options.validate); an incomplete polygon is
  // checked again by the general sweep so that the report says whether it is at least simple.
  PolygonCheck chk = r.check;
  bool valid = r.validated && chk.reason.empty();
  double ms_validate = r.ms_validate;
  if (!r.complete) {
    progress.phase("validating");
    const auto tv = Clock::now();
    Status vs = validate_polygon(pts, r.boundary, &chk);
    valid = vs.is_ok();
    ms_validate += ms(tv, Clock::now());
  }
  const auto t3 = Clock::now();
  // A complete result must validate; anything else is a bug in the library.
  if (r.complete && !valid)
    return fail({StatusCode::Internal, "the reconstructed polygon failed validation (please report): " + chk.reason});

  progress.phase("writing");
  PolygonSvgLayers layers;
  GammaFaces dt_edges;
  if (fmt == PolygonFormat::Svg) {
    if (Status s = svg_layers(a, pts, r.method, dt_edges, layers); !s) return fail(s);
    layers.highlight_points = r.stuck_points;
    layers.highlight_edges = r.fallback_edges;
  }
  if (Status s = write_polygon_rows(a.out, pts, rep, r.boundary, fmt, &layers); !s) return fail(s);
  if (int rc = a.render.empty() ? 0 : render_reconstruction2(a.render, pts, r)) return rc;
  const auto t4 = Clock::now();

  const std::size_t n = pts.size(), nb = r.boundary.size();
  if (!a.report.empty()) {
    nlohmann::json j = nlohmann::json::parse(to_json(rr, ropt));
    add_common_json(a, rep, 2, n, nb, j);
    j["valid"] = valid && r.complete;
    j["validation"].update({{"simple", chk.simple}, {"counter_clockwise", chk.ccw}, {"all_points_once", chk.all_points},
                            {"reason", chk.reason}});
    add_method_json(a, skel, j);
    if (is_skeleton(a)) j["fallback"] = nullptr;
    j["timings_ms"].update({{"read", ms(t0, t1)}, {"validate", ms_validate}, {"write", ms(t3, t4)}, {"total", ms(t0, Clock::now())}});
    report_rows(rep, j);
    if (Status s = write_report(a.report, j); !s) return fail(s);
  }
  if (!r.complete) {
    const char* why = incomplete_why(a, r.method);
    return fail({StatusCode::Incomplete, std::string(why) + ": " + std::to_string(n - nb) + " of " + std::to_string(n) +
                                             " points left inside; the polygon in " + a.out +
                                             " passes through " + std::to_string(nb) + " points"});
  }
  if (!a.quiet) {
    std::printf("polygon through %zu/%zu points: valid (simple, counter-clockwise, every point once); method %s",
                nb, n, r.method.c_str());
    if (a.method != "gamma" && !is_skeleton(a)) std::printf(" (criterion %s)", a.method.c_str());
    if (r.locked_at_gamma0) std::printf(" (gamma locked with %zu inside)", r.stuck_points.size());
    std::printf(" -> %s (%.0f ms)\n", a.out.c_str(), ms(t0, Clock::now()));
  }
  return 0;
}

// --topology auto in 3D: the surfaces, their roles, nesting and genus, and what decided (issue 16).
void add_surfaces_json(const Surfaces3Result& sr, nlohmann::json& j) {
  nlohmann::json list = nlohmann::json::array();
  for (const Surface3& s : sr.surfaces) {
    nlohmann::json x = {{"faces", s.triangles.size()}, {"points", s.points.size()}, {"genus", s.genus},
                        {"role", to_string(s.role)}, {"parent", s.parent}};
    x["gap_spacings"] = std::isfinite(s.gap_spacings) ? nlohmann::json(s.gap_spacings) : nlohmann::json(nullptr);
    x["nearest_surface"] = s.nearest_surface;
    list.push_back(x);
  }
  j["surfaces"] = list;
  if (!j.contains("handles")) j["handles"] = nlohmann::json::array();  // (to_json lists them when any)
  // The handle stage's kept changes by what they did to F = 2N - 4c + 4g (a region may close
  // several loops at once; a change that lowers F sealed surfaces off, whether it added or removed
  // tetrahedra); the tetrahedra they added and removed apart.
  long long closed = 0, opened = 0, sealed = 0;
  for (const Handle3Change& c : sr.mesh.handle_changes) {
    if (c.delta_faces < 0) sealed -= c.delta_faces / 4;
    else if (c.kind == Handle3Change::Kind::OpenTunnel) opened += c.delta_faces / 4;
    else closed += c.delta_faces / 4;
  }
  j["topology"] = {{"mode", to_string(sr.topology)},
                   {"decision", to_string(sr.decision)},
                   {"parts", sr.parts},
                   {"part_sizes", sr.part_sizes},
                   {"small_parts_merged", sr.small_parts_merged},
                   {"patches_joined", sr.patches_joined},
                   {"parts_split_by_labels", sr.parts_split_by_labels},
                   {"repaired_tetrahedra", sr.repaired_tetrahedra},
                   {"repair_capped", sr.repair_capped},
                   {"gap_threshold", sr.gap_threshold},
                   {"min_gap_spacings",
                    std::isfinite(sr.min_gap_spacings) ? nlohmann::json(sr.min_gap_spacings) : nlohmann::json(nullptr)},
                   {"handles_closed", closed},
                   {"handles_opened", opened},
                   {"cavities_sealed", sealed},
                   {"handle_tetrahedra_added", sr.mesh.handle_added},
                   {"handle_tetrahedra_removed", sr.mesh.handle_removed},
                   {"ms_infer", sr.ms_infer},
                   {"ms_assemble", sr.ms_assemble}};
}

// --topology auto in 3D (validate: the library's own check; the CLI validates and reports it).
Status run_surfaces3(const ReconstructArgs& a, const PointSet& pts, const Constrict3Options& opt, bool validate,
                     Surfaces3Result& sr) {
  Surfaces3Options so;
  so.topology = Topology3::Auto;
  so.topology_gap = a.topology_gap;
  so.surface = opt;
  so.validate = validate;
  return reconstruct_surfaces3(pts, so, sr);
}

// Single mode: what auto gives, for the note on stderr and the report (small inputs only).
void note_surfaces3(const ReconstructArgs& a, const PointSet& pts, const Constrict3Options& opt, Surfaces3Result& inferred) {
  if (!run_surfaces3(a, pts, opt, true, inferred).is_ok()) inferred = Surfaces3Result{};
  if (!a.quiet && inferred.valid() && (inferred.surfaces.size() > 1 || inferred.genus > 0))
    std::fprintf(stderr, "note: the points show %zu surface%s of total genus %d; try --topology auto\n",
                 inferred.surfaces.size(), inferred.surfaces.size() == 1 ? "" : "s", inferred.genus);
}

class ProgressVisitor3 final : public Constrict3Visitor {
 public:
  ProgressVisitor3(Progress& p, std::size_t n) : progress_(p), n_(n) {}
  void on_event(const Constrict3Event& e) override {
    if (e.kind == Constrict3Event::Kind::RemoveTet) {
      if (!started_) {
        started_ = true;
        progress_.phase("constricting, tetrahedra removed");
      }
      if ((++removed_ & 4095u) == 0) progress_.count(removed_, 6 * n_);
    } else if (e.kind == Constrict3Event::Kind::Lock) {
      progress_.phase("lock: fallback");
    } else if (e.kind == Constrict3Event::Kind::StageBegin && e.stage == Stage3::Grow) {
      progress_.phase("growing the body from the inside (labels)");
    } else if (e.kind == Constrict3Event::Kind::StageBegin && e.stage == Stage3::Fill) {
      progress_.phase("filling the pockets of the grown body");
    } else if (e.kind == Constrict3Event::Kind::StageBegin && e.stage == Stage3::Candidates) {
      // The variant runs are parallel and report no events (docs/reconstruction-3d.md §4.5).
      progress_.phase("constricting: variant runs in parallel, then the smallest-area surface");
    }
  }

 private:
  Progress& progress_;
  std::size_t n_;
  std::size_t removed_ = 0;
  bool started_ = false;
};

int run_reconstruct3(const ReconstructArgs& a, const PointSet& pts, const ReadReport& rep, Progress& progress,
                     Clock::time_point t0, Clock::time_point t1) {
  const std::string ext = lower_ext(a.out);
  if (!is_mesh_ext(ext))
    return fail({StatusCode::InvalidArgument, a.out + ": unknown output extension for a 3D surface (use .off, .ply, .obj or .stl)"});
  if (!a.body.empty() && lower_ext(a.body) != "vtk")
    return fail({StatusCode::InvalidArgument, a.body + ": the body is written as VTK legacy (.vtk)"});
  // --refine none: the paper's algorithm (Constrict3Options::paper()); --fast: one variant run.
  Constrict3Options opt;
  (void)Constrict3Options::from_preset(a.refine == "none" ? "paper" : a.fast ? "fast" : "default", opt);
  (void)fallback3_from_name(a.fallback, opt.fallback);
  opt.stop_after = a.stop_after;
  if (a.no_grow) opt.grow = false;
  opt.validate = false;  // the surface is validated below (validate_mesh3) and reported
  (void)criterion_from_name(a.method, opt.criterion);
  progress.phase(is_skeleton(a) ? "voronoi skeleton growth" : "delaunay tetrahedralization, labels");
  ProgressVisitor3 visitor(progress, pts.size());
  Mesh3Result r;
  Surfaces3Result sr;
  VoronoiSkeletonStats skel;
  if (is_skeleton(a)) {
    VoronoiSkeletonOptions vo;
    vo.seed_limit = a.seed_limit;
    vo.validate = false;
    VoronoiSkeleton3Result v;
    if (Status s = voronoi_skeleton3(pts, vo, v); !s) return fail_in(a.in.path, rep, s);
    skel = v.stats;
    r = as_reconstruction(std::move(v));
  } else if (a.topology == "auto") {
    if (Status s = run_surfaces3(a, pts, opt, false, sr); !s) return fail_in(a.in.path, rep, s);
    r = sr.mesh;
  } else if (Status s = reconstruct3(pts, opt, r, progress.enabled() ? &visitor : nullptr); !s) {
    return fail_in(a.in.path, rep, s);
  }
  const bool surfaces = a.topology == "auto" && !is_skeleton(a);
  // Single mode, small inputs: what auto would give, for the note and the report.
  Surfaces3Result inferred;
  const bool infer =
      !surfaces && !is_skeleton(a) && pts.size() <= kNoteMaxPoints3 && r.delaunay_tets <= kNoteMaxTets3 && r.complete;
  const auto tn = Clock::now();
  if (infer) note_surfaces3(a, pts, opt, inferred);
  const double ms_note = ms(tn, Clock::now());  // (the auto run behind the note: a second engine run)

  progress.phase("validating");
  const auto tv = Clock::now();
  // The files are written beside the validation (mostly the kernel's copy into the page cache);
  // a complete result that fails validation takes them back below.
  Clock::time_point tw0, tw1;
  std::future<Status> written = std::async(std::launch::async, [&] {
    tw0 = Clock::now();
    Status ws = write_surface_rows(a, pts, rep, r);
    tw1 = Clock::now();
    return ws;
  });
  MeshCheck chk;
  MeshCheckOptions copt;
  copt.require_all_points = true;
  copt.any_topology = surfaces;
  // Auto: the body check beside the mesh check (two independent exact checks, one thread each).
  std::future<Status> body_check;
  if (surfaces && r.complete)
    body_check = std::async(std::launch::async, [&] { return validate_body3(pts, r.mesh, r.tets); });
  bool valid = validate_mesh3(pts, r.mesh, &chk, copt).is_ok();
  // The check's volume is exact where the double sum is badly conditioned (a body much thinner
  // than it is long).
  if (chk.volume_exact) r.volume = chk.volume;
  std::string body_reason;
  if (body_check.valid()) {
    const Status bs = body_check.get();
    if (valid && !bs) body_reason = bs.message();
    valid = valid && bs.is_ok();
  }
  // An incomplete skeleton must still be a closed genus-0 surface over the points it reaches.
  bool part_valid = true;
  MeshCheck part;
  if (is_skeleton(a) && !r.complete) {
    copt.require_all_points = false;
    part_valid = validate_mesh3(pts, r.mesh, &part, copt).is_ok();
  }
  const double ms_validate = ms(tv, Clock::now());
  progress.phase("writing");
  const Status write_status = written.get();
  if ((r.complete && !valid) || !part_valid) {
    (void)std::remove(a.out.c_str());
    if (!a.body.empty()) (void)std::remove(a.body.c_str());
    if (!part_valid)
      return fail(
          {StatusCode::Internal, "the voronoi skeleton surface failed validation (please report): " + part.reason});
    return fail({StatusCode::Internal, "the reconstructed surface failed validation (please report): " + chk.reason +
                                           body_reason});
  }
  if (!write_status) return fail(write_status);
  const auto tr = Clock::now();
  if (int rc = a.render.empty() ? 0 : render_reconstruction3(a.render, pts, r.mesh)) return rc;
  const double ms_write = ms(tw0, tw1) + ms(tr, Clock::now());

  const std::size_t n = pts.size(), nb = n - r.unplaced_points.size();
  if (!a.report.empty()) {
    nlohmann::json j = nlohmann::json::parse(to_json(r, opt));
    add_common_json(a, rep, 3, n, nb, j);
    if (!a.body.empty()) j["body"] = a.body;
    j["valid"] = valid && r.complete;
    // The surface's shape: of the points it reaches when incomplete (the check that requires
    // every point stops before it counts components and genus).
    const MeshCheck& shape = is_skeleton(a) && !r.complete ? part : chk;
    j["closed"] = shape.closed;
    j["manifold"] = shape.edge_manifold && shape.vertex_manifold;
    j["oriented"] = shape.oriented && shape.outward;
    j["genus"] = shape.genus;
    j["components"] = shape.components;
    j["validation"] = {{"reason", chk.reason}, {"euler", chk.euler}, {"face_count_ok", chk.face_count_ok}};
    if (surfaces) add_surfaces_json(sr, j);
    if (infer && inferred.valid())
      j["topology"] = {{"mode", "single"},
                       {"inferred", {{"surfaces", inferred.surfaces.size()}, {"genus", inferred.genus},
                                     {"parts", inferred.parts}, {"decision", to_string(inferred.decision)}}}};
    add_method_json(a, skel, j);
    j["timings_ms"].update({{"read", ms(t0, t1)}, {"validate", ms_validate}, {"write", ms_write}, {"total", ms(t0, Clock::now())}});
    if (infer) j["timings_ms"]["topology_note"] = ms_note;
    report_rows(rep, j);
    if (Status s = write_report(a.report, j); !s) return fail(s);
  }
  if (!r.complete) {
    const char* why = is_skeleton(a) ? incomplete_why(a, to_string(r.method))
                      : r.method == Method3::Stopped ? "stopped early (--stop-after)" : "constriction locked";
    return fail({StatusCode::Incomplete, std::string(why) + ": " + std::to_string(n - nb) + " of " + std::to_string(n) +
                                             " points left inside; the surface in " + a.out + " passes through " +
                                             std::to_string(nb) + " points"});
  }
  if (!a.quiet && surfaces) {
    std::printf("%zu surface%s through %zu/%zu points: valid (closed, manifold, outward, total genus %d, %zu triangles; %zu part%s, %s)",
                sr.surfaces.size(), sr.surfaces.size() == 1 ? "" : "s", nb, n, chk.genus, r.mesh.triangles.size(), sr.parts,
                sr.parts == 1 ? "" : "s", to_string(sr.decision));
    std::printf(" -> %s (%.0f ms)\n", a.out.c_str(), ms(t0, Clock::now()));
  } else if (!a.quiet) {
    std::printf("surface through %zu/%zu points: valid (closed, manifold, outward, genus %d, %zu triangles); method %s",
                nb, n, chk.genus, r.mesh.triangles.size(), to_string(r.method));
    if (a.method != "gamma" && !is_skeleton(a)) std::printf(" (criterion %s)", a.method.c_str());
    if (r.locked) std::printf(" (gamma locked with %zu inside)", r.stuck_points.size());
    std::printf(" -> %s (%.0f ms)\n", a.out.c_str(), ms(t0, Clock::now()));
  }
  return 0;
}

// Options that contradict each other, or outputs that would overwrite each other, named before
// the input is read.
Status check_option_conflicts(const ReconstructArgs& a) {
  if (a.seed_limit > 0 && !is_skeleton(a))
    return {StatusCode::InvalidArgument, "--seed-limit applies to --method voronoi-skeleton only: drop it, or add that method"};
  // The skeleton has no constriction to stop, no lock fallback, no post-pass and no growth: these
  // were accepted and changed nothing (cli.md: they do not apply).
  if (is_skeleton(a)) {
    const char* unused = a.stop_after != SIZE_MAX ? "--stop-after" : a.fallback != "auto" ? "--fallback" : a.refine != "auto" ? "--refine"
                         : a.fast ? "--fast" : a.no_grow ? "--no-grow" : nullptr;
    if (unused)
      return {StatusCode::InvalidArgument, std::string(unused) +
                                               " applies to the constriction; --method voronoi-skeleton has none of its stages: drop " + unused};
  }
  // (In 3D the skeleton ran and --topology was ignored.)
  if (is_skeleton(a) && a.topology != "single")
    return {StatusCode::InvalidArgument,
            "--topology auto needs the constriction (--method voronoi-skeleton gives one polygon or surface)"};
  if (a.topology == "single" && a.topology_gap != kDefaultTopologyGap)
    return {StatusCode::InvalidArgument, "--topology-gap applies to --topology auto: drop it, or add --topology auto"};
  if (a.topology == "auto" && a.stop_after != SIZE_MAX)
    return {StatusCode::InvalidArgument,
            "--stop-after stops the one constriction of --topology single; --topology auto reconstructs every part to the end (drop one of them)"};
  std::error_code ec;
  if (std::filesystem::is_directory(a.out, ec))
    return {StatusCode::InvalidArgument, a.out + " is a directory; give -o a file name (for example " +
                                             (std::filesystem::path(a.out) / "result").string() + ".off or .idx)"};
  return check_distinct_files({{"INPUT", &a.in.path}}, {{"-o", &a.out}, {"--report", &a.report}, {"--body", &a.body}, {"--render", &a.render}});
}

int run_reconstruct(const ReconstructArgs& a) {
  const auto t0 = Clock::now();
  if (Status s = check_option_conflicts(a); !s) return fail(s);
  Progress progress(!a.quiet);
  progress.phase("reading");
  PointSet pts;
  ReadReport rep;
  // Every engine checks its points (reconstruct_rings2, reconstruct3 and the surfaces find
  // duplicates in their canonical order or triangulation; the skeletons call check_points), with
  // the same statuses and messages as the reader's check.
  if (Status s = read_input(a.in, pts, rep, /*check=*/false); !s) return fail(s);
  const auto t1 = Clock::now();
  if (Status s = check_dimension_options(a, pts.dim); !s) return fail(s);
  if (pts.dim == 2) return run_reconstruct2(a, pts, rep, progress, t0, t1);
  return run_reconstruct3(a, pts, rep, progress, t0, t1);
}

}  // namespace

Command add_reconstruct_command(CLI::App& app) {
  auto a = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand(
      "reconstruct",
      "reconstruct a simple polygon (2D) / closed genus-0 surface (3D) through all points by gamma-constriction");
  add_input_options(cmd, a->in);
  cmd->add_option("-o,--output", a->out, "output: 2D .idx .csv .geojson .wkt .svg; 3D .off .ply .obj .stl")->required()->check(non_empty_path());
  cmd->add_option("--body", a->body, "3D: also write the tetrahedral body (VTK legacy .vtk)")->check(non_empty_path());
  cmd->add_flag("--ascii", a->ascii, "3D: ASCII PLY instead of binary");
  cmd->add_option("--report", a->report, "write a JSON report (method, counts, area, timings)")->check(non_empty_path());
  cmd->add_option("--fallback", a->fallback, "on a lock: auto (default) | gamma0 | degree4 (2D) | none")
      ->check(CLI::IsMember({"auto", "gamma0", "degree4", "none"}));
  cmd->add_option("--refine", a->refine,
                  "post-pass on the complete result: auto (default: 2D local search, 3D carve + flip passes) | none (the paper's algorithm)")
      ->check(CLI::IsMember({"auto", "none"}));
  cmd->add_flag("--fast", a->fast, "3D: one constriction run (size bias and labels) instead of two variants, when the growth does not reach every point");
  cmd->add_flag("--no-grow", a->no_grow, "3D: no growth from the inside; constrict from the convex hull (docs/reconstruction-3d.md §4.7)");
  cmd->add_option("--render", a->render, "also draw the result: .png (2D, 3D) or .svg (2D)")->check(non_empty_path());
  cmd->add_option("--stop-after", a->stop_after, "stop the constriction after K removals (result incomplete; --topology single)")
      ->check(non_negative_integer());
  cmd->add_option("--method", a->method, "gamma (default) | min-area-change | boissonnat | voronoi-skeleton (docs/comparison-methods.md)")
      ->check(CLI::IsMember({"gamma", "min-area-change", "boissonnat", "voronoi-skeleton"}));
  cmd->add_option("--seed-limit", a->seed_limit, "voronoi-skeleton: try at most N seeds (0 = all)")->check(non_negative_integer());
  cmd->add_option("--topology", a->topology,
                  "single (default: one polygon / one genus-0 surface) | auto (what the data show: 2D shells, holes, parts; 3D parts, inner shells, handles; docs/topology.md)")
      ->check(CLI::IsMember({"single", "auto"}));
  cmd->add_option("--topology-gap", a->topology_gap,
                  "auto: separate rings (2D) or surfaces (3D) only where parts are at least T local spacings apart (default 2); 2D holes that the nearest-neighbour walk traces, at least T/2")
      ->check(non_negative_number());
  cmd->add_flag("-q,--quiet", a->quiet, "no summary line, no progress");
  return {cmd, [a] { return run_reconstruct(*a); }};
}

}  // namespace constrict::cli
