// SPDX-License-Identifier: GPL-3.0-or-later
// `constrict render INPUT_OR_RESULT -o PICTURE.{svg,png}`: pictures of a point set's
// reconstruction (with --stop-after, a stage sheet or a 2D animation), of a 2D polygon result
// (--points) or of a 3D mesh; and the pictures of `reconstruct --render`. Drawing is done by the
// library (render.hpp, write_polygon2).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "constrict/constrict.hpp"
#include "constrict/constrict3.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/io.hpp"
#include "constrict/mesh.hpp"
#include "constrict/render.hpp"
#include "constrict/topology.hpp"

namespace constrict::cli {
namespace {

constexpr int kMaxViews = 1024;  // 32 x 32 panels of 512 pixels: the largest picture (16384 pixels)

struct RenderArgs {
  InputArgs in;
  std::string out, points, size, view, stages, animate, up = "z";
  int views = 0, columns = 0;
  bool wireframe = false, no_graph = false, quiet = false;
  std::size_t stop_after = SIZE_MAX;
};

// Picture geometry from the options: size (default: 1024² for one panel, 512² per sheet cell).
// RenderOptions2 and RenderOptions3 share these fields.
template <class RenderOptions>
Status layout(const RenderArgs& a, std::size_t panels, RenderOptions& o) {
  o.columns = a.columns;
  const int cols = a.columns > 0 ? std::min<int>(a.columns, static_cast<int>(panels))
                                 : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(panels))));
  const int rows = static_cast<int>((panels + static_cast<std::size_t>(cols) - 1) / static_cast<std::size_t>(cols));
  if (a.size.empty()) {
    if (cols > 32 || rows > 32)
      return {StatusCode::InvalidArgument, "a sheet of " + std::to_string(panels) + " panels (" + std::to_string(cols) + " x " +
                                               std::to_string(rows) + " of 512 pixels) exceeds 16384 pixels: ask for fewer "
                                               "panels (--stages, --views), or set --size WxH"};
    o.width = panels == 1 ? 1024 : 512 * cols;
    o.height = panels == 1 ? 1024 : 512 * rows;
    return Status::ok();
  }
  // (Digits only, each number range-checked as a whole: sscanf's %d wrapped 4294967297 to 1.)
  int w = 0, h = 0;
  const char* const b = a.size.data();
  const char* const e = b + a.size.size();
  const auto rw = std::from_chars(b, e, w);
  const bool by = rw.ec == std::errc() && rw.ptr != b && rw.ptr < e && (*rw.ptr == 'x' || *rw.ptr == 'X');
  const auto rh = by ? std::from_chars(rw.ptr + 1, e, h) : std::from_chars_result{e, std::errc::invalid_argument};
  if (!by || rh.ec != std::errc() || rh.ptr != e || rh.ptr == rw.ptr + 1 || w < 1 || h < 1 || w > 16384 || h > 16384)
    return {StatusCode::InvalidArgument, "--size: expected WxH with 1 <= W, H <= 16384, e.g. 2048x2048"};
  o.width = w;
  o.height = h;
  return Status::ok();
}

Status views_of(const RenderArgs& a, std::vector<View>& views) {
  views.clear();
  View base;
  if (!a.view.empty()) {
    std::vector<double> v;
    if (!parse_list(a.view, 2, v) || !std::isfinite(v[0]) || !std::isfinite(v[1]))
      return {StatusCode::InvalidArgument, "--view: expected two numbers AZIMUTH,ELEVATION in degrees"};
    base.azimuth = v[0];
    base.elevation = v[1];
  }
  const int n = std::max(1, a.views);
  for (int i = 0; i < n; ++i) views.push_back({base.azimuth + 360.0 * i / n, base.elevation});
  return Status::ok();
}

// Removal counts of a stage sheet: "auto" = 0, N/4, N/2, 3N/4 of the N removals of the full run.
Status stage_targets(const std::string& spec, std::size_t total, std::vector<std::size_t>& out) {
  out.clear();
  if (spec == "auto") {
    for (std::size_t k = 0; k < 4; ++k) out.push_back(total * k / 4);
    return Status::ok();
  }
  std::size_t pos = 0;
  while (pos <= spec.size()) {
    const std::size_t comma = spec.find(',', pos);
    const std::string item = spec.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    try {
      std::size_t used = 0;
      const long long v = std::stoll(item, &used);
      if (used != item.size() || v < 0) throw std::invalid_argument(item);
      out.push_back(static_cast<std::size_t>(v));
    } catch (...) {
      return {StatusCode::InvalidArgument, "--stages: expected 'auto' or removal counts K1,K2,... (>= 0)"};
    }
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  std::sort(out.begin(), out.end());
  return Status::ok();
}

Status delaunay_layer(const PointSet& pts, GammaFaces& g) {
  GraphSpec spec;
  (void)GraphSpec::from_preset("delaunay", spec);
  return build_gamma_graph(pts, spec, g);
}

// Stage pictures need the number of removals of the whole run before the snapshots are placed.
template <class Constrictor, class Options>
Status count_removals(const PointSet& pts, const Options& opt, std::size_t& total) {
  total = 0;
  Constrictor c;
  if (Status s = c.init(pts, opt); !s) return s;
  while (c.step()) ++total;
  return Status::ok();
}

// Replays the run, appends snap(c) after each target count of removals (ascending; the run's own
// state when it ends earlier), then finishes it into r.
template <class Constrictor, class Options, class Snap, class Shot, class Result>
Status replay(const PointSet& pts, const Options& opt, const std::vector<std::size_t>& targets, Snap snap,
              std::vector<Shot>& shots, Result& r) {
  Constrictor c;
  if (Status s = c.init(pts, opt); !s) return s;
  std::size_t done = 0;
  bool more = true;
  for (std::size_t t : targets) {
    while (more && done < t) {
      more = c.step();
      if (more) ++done;
    }
    shots.push_back(snap(c));
  }
  while (more && c.step()) ++done;
  return c.finish(r);
}

void print_stages(std::size_t total, const std::vector<std::size_t>& targets, const std::string& method,
                  const std::string& out) {
  std::printf("stages (removals of %zu):", total);
  for (std::size_t t : targets) std::printf(" %zu", t);
  std::printf(" final(%s) -> %s\n", method.c_str(), out.c_str());
}

// ---- 2D ------------------------------------------------------------------------------------
Status write_picture2(const RenderArgs& a, const PointSet& pts, const std::vector<Panel2>& panels, const std::string& path) {
  if (lower_ext(path) == "svg") {
    if (panels.size() != 1)
      return {StatusCode::InvalidArgument, path + ": a sheet of several panels is written as PNG"};
    return write_polygon2(path, pts, panels[0].boundary, PolygonFormat::Svg, panels[0].layers);
  }
  RenderOptions2 o;
  if (Status s = layout(a, panels.size(), o); !s) return s;
  Image img;
  if (Status s = render_sheet2(pts, panels, o, img); !s) return s;
  return write_png(path, img);
}

// Several rings in one picture: PNG fills them even-odd; SVG is write_rings2()'s (holes dashed).
Status write_rings_picture2(const RenderArgs& a, const PointSet& pts, const std::vector<Ring2>& rings,
                            const PolygonSvgLayers& layers, const std::string& path) {
  if (lower_ext(path) == "svg") return write_rings2(path, pts, rings, PolygonFormat::Svg, &layers);
  Panel2 p{rings[0].indices, &layers};
  for (std::size_t k = 1; k < rings.size(); ++k) p.rings.push_back(rings[k].indices);
  return write_picture2(a, pts, {p}, path);
}

// Rings read from a file, their roles for the drawing style only: clockwise = hole.
std::vector<Ring2> rings_by_orientation(const PointSet& pts, const std::vector<std::vector<int>>& rings) {
  std::vector<Ring2> rs(rings.size());
  for (std::size_t k = 0; k < rings.size(); ++k) {
    double area2 = 0;
    const std::vector<int>& r = rings[k];
    for (std::size_t i = 0; i < r.size(); ++i) {
      const auto p = static_cast<std::size_t>(r[i]), q = static_cast<std::size_t>(r[(i + 1) % r.size()]);
      area2 += pts[p][0] * pts[q][1] - pts[q][0] * pts[p][1];
    }
    rs[k].role = area2 < 0 ? RingRole::Hole : RingRole::Shell;
    rs[k].indices = r;
  }
  return rs;
}

int render_points2(const RenderArgs& a, const PointSet& pts) {
  GammaFaces dt;
  if (!a.no_graph)
    if (Status s = delaunay_layer(pts, dt); !s) return fail(s);
  Constrict2Options opt;
  const bool staged = !a.stages.empty() || !a.animate.empty();
  if (!staged) {  // one picture: the result (or the state after --stop-after removals)
    opt.stop_after = a.stop_after;
    Polygon2Result r;
    if (Status s = reconstruct2(pts, opt, r); !s) return fail(s);
    PolygonSvgLayers layers;
    layers.graph = a.no_graph ? nullptr : &dt;
    layers.highlight_points = r.stuck_points;
    layers.highlight_edges = r.fallback_edges;
    layers.title = "constrict: " + a.in.path + " (" + r.method + ")";
    if (Status s = write_picture2(a, pts, {Panel2{r.boundary, &layers}}, a.out); !s) return fail(s);
    if (!a.quiet) std::printf("polygon through %zu/%zu points (%s) -> %s\n", r.boundary.size(), pts.size(), r.method.c_str(), a.out.c_str());
    return 0;
  }
  // Count the removals of the whole Delaunay constriction, then replay it and take snapshots.
  std::size_t total = 0;
  if (Status s = count_removals<Constrictor2>(pts, opt, total); !s) return fail(s);
  std::vector<std::size_t> targets;
  if (!a.stages.empty()) {
    if (Status s = stage_targets(a.stages, total, targets); !s) return fail(s);
  } else {  // animation: at most 60 frames plus the final one
    const std::size_t stride = std::max<std::size_t>(1, (total + 59) / 60);
    for (std::size_t k = 0; k < total; k += stride) targets.push_back(k);
  }
  std::vector<std::vector<int>> shots;
  Polygon2Result r;
  if (Status s = replay<Constrictor2>(pts, opt, targets, [](const Constrictor2& c) { return c.boundary(); }, shots, r); !s)
    return fail(s);
  shots.push_back(r.boundary);
  PolygonSvgLayers plain, last;
  plain.graph = last.graph = a.no_graph ? nullptr : &dt;
  last.highlight_points = r.stuck_points;
  last.highlight_edges = r.fallback_edges;
  std::vector<Panel2> panels;
  for (std::size_t i = 0; i < shots.size(); ++i) panels.push_back({shots[i], i + 1 == shots.size() ? &last : &plain});
  if (!a.animate.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(a.animate, ec);
    const std::string ext = lower_ext(a.out) == "svg" ? "svg" : "png";
    for (std::size_t i = 0; i < panels.size(); ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "/frame_%04zu.", i);
      if (Status s = write_picture2(a, pts, {panels[i]}, a.animate + name + ext); !s) return fail(s);
    }
    if (!a.quiet) std::printf("animation: %zu frames (every %zu removals, then the final polygon) -> %s/frame_*.%s\n",
                              panels.size(), targets.size() > 1 ? targets[1] - targets[0] : total, a.animate.c_str(), ext.c_str());
    if (a.stages.empty()) {  // -o gets the final picture
      if (Status s = write_picture2(a, pts, {panels.back()}, a.out); !s) return fail(s);
      return 0;
    }
  }
  if (Status s = write_picture2(a, pts, panels, a.out); !s) return fail(s);
  if (!a.quiet) print_stages(total, targets, r.method, a.out);
  return 0;
}

// ---- 3D ------------------------------------------------------------------------------------
Status write_picture3(const RenderArgs& a, const PointSet& pts, const std::vector<Panel3>& panels) {
  if (lower_ext(a.out) != "png") return {StatusCode::InvalidArgument, a.out + ": 3D pictures are PNG"};
  RenderOptions3 o;
  if (Status s = layout(a, panels.size(), o); !s) return s;
  o.wireframe = a.wireframe;
  o.up_axis = a.up == "x" ? 0 : a.up == "y" ? 1 : 2;
  Image img;
  if (Status s = render_sheet3(pts, panels, o, img); !s) return s;
  return write_png(a.out, img);
}

int render_mesh_file(const RenderArgs& a, const PointSet& pts, const TriMesh3& mesh) {
  std::vector<View> views;
  if (Status s = views_of(a, views); !s) return fail(s);
  std::vector<Panel3> panels;
  for (const View& v : views) panels.push_back({&mesh, v});
  const auto t0 = Clock::now();
  if (Status s = write_picture3(a, pts, panels); !s) return fail(s);
  if (!a.quiet) std::printf("%zu triangles, %zu view(s) -> %s (%.0f ms)\n", mesh.n_faces(), views.size(), a.out.c_str(), ms(t0, Clock::now()));
  return 0;
}

int render_points3(const RenderArgs& a, const PointSet& pts) {
  std::vector<View> views;
  if (Status s = views_of(a, views); !s) return fail(s);
  Constrict3Options opt;
  if (!a.stages.empty() || a.stop_after != SIZE_MAX) {
    // Stages and partial states show the paper's process, the constriction from the convex hull
    // (not the default growth from the inside, docs/reconstruction-3d.md §4.7): they replay the
    // variant that reconstruct3() with --no-grow chooses (the step-able constrictor runs one
    // variant), so the last panel is the `reconstruct --no-grow` result.
    opt.grow = false;
    Mesh3Result best;
    if (Status s = reconstruct3(pts, opt, best); !s) return fail(s);
    opt.size_bias = best.size_bias;
    opt.label_weight = best.label_weight;
    opt.variants.clear();
  }
  if (a.stages.empty()) {
    opt.stop_after = a.stop_after;
    Mesh3Result r;
    if (Status s = reconstruct3(pts, opt, r); !s) return fail(s);
    return render_mesh_file(a, pts, r.mesh);
  }
  std::size_t total = 0;
  if (Status s = count_removals<Constrictor3>(pts, opt, total); !s) return fail(s);
  std::vector<std::size_t> targets;
  if (Status s = stage_targets(a.stages, total, targets); !s) return fail(s);
  std::vector<TriMesh3> shots;
  Mesh3Result r;
  if (Status s = replay<Constrictor3>(pts, opt, targets, [](const Constrictor3& c) { return c.surface(); }, shots, r); !s)
    return fail(s);
  shots.push_back(r.mesh);
  std::vector<Panel3> panels;
  for (const auto& m : shots) panels.push_back({&m, views[0]});
  if (Status s = write_picture3(a, pts, panels); !s) return fail(s);
  if (!a.quiet) print_stages(total, targets, to_string(r.method), a.out);
  return 0;
}

// render's --columns lays out sheets: the columns of a point file of more than 3 columns are
// chosen by a header line here, or (points to reconstruct) by reconstruct's --columns, whose
// --render draws the result.
Status columns_advice(const Status& s, bool reconstructs) {
  const std::string m = s.message();
  const std::size_t at = m.find(kChooseColumnsAdvice);
  if (at == std::string::npos) return s;
  return {s.code(), m.substr(0, at) +
                        "name the coordinate columns " + (reconstructs ? "x, y[, z]" : "x, y") +
                        " in a header line (render's --columns lays out sheets)" +
                        (reconstructs ? ", or draw it with constrict reconstruct FILE --columns 2,3,4 --render PICTURE" : "") +
                        m.substr(at + std::string(kChooseColumnsAdvice).size())};
}

// Options of one dimension given for an input of the other are refused, not ignored (issue 18).
// --up's default (z) cannot be told from an explicit `--up z`, which is let through.
Status check_dimension_options(const RenderArgs& a, int dim) {
  if (dim == 2) {
    if (!a.view.empty()) return wrong_dimension("--view", 2, a.in.path);
    if (a.views != 0) return wrong_dimension("--views", 2, a.in.path);
    if (a.wireframe) return wrong_dimension("--wireframe", 2, a.in.path);
    if (a.up != "z") return wrong_dimension("--up", 2, a.in.path);
  } else {
    if (a.no_graph) return wrong_dimension("--no-graph", 3, a.in.path);
    if (!a.animate.empty()) return wrong_dimension("--animate", 3, a.in.path);
  }
  return Status::ok();
}

int run_render(const RenderArgs& a) {
  if (Status s = check_distinct_files({{"INPUT", &a.in.path}, {"--points", &a.points}}, {{"-o", &a.out}}); !s) return fail(s);
  const std::string oe = lower_ext(a.out);
  if (oe != "png" && oe != "svg") return fail({StatusCode::InvalidArgument, a.out + ": the picture is .png or .svg"});
  if (!a.animate.empty()) {
    // -o among the frames would be overwritten by one (or overwrite it) without a word.
    std::error_code ec;
    const std::filesystem::path out(a.out);
    const auto dir = std::filesystem::weakly_canonical(a.animate, ec);
    const auto parent = std::filesystem::weakly_canonical(out.has_parent_path() ? out.parent_path() : ".", ec);
    if (dir == parent && out.filename().string().rfind("frame_", 0) == 0)
      return fail({StatusCode::InvalidArgument, a.out + ": -o is among the frames that --animate writes to " +
                                                    a.animate +
                                                    "/frame_*: name the picture otherwise or write it elsewhere"});
  }
  if (a.views < 0 || a.columns < 0) return fail({StatusCode::InvalidArgument, "--views and --columns must be >= 0"});
  // Options that another one overrides were dropped without a word (hostile-argument sweep,
  // 2026-12-07): refused, each naming what to do.
  if (oe == "svg" && !a.size.empty())
    return fail({StatusCode::InvalidArgument, "--size sets a PNG's pixels; an SVG has none to set: drop --size or write .png"});
  if (a.stop_after != SIZE_MAX && (!a.stages.empty() || !a.animate.empty()))
    return fail({StatusCode::InvalidArgument,
                 "--stop-after draws one state of the run, --stages and --animate several: give one of them"});
  if (!a.stages.empty() && a.views > 1)
    return fail({StatusCode::InvalidArgument, "--stages draws each stage from one view, --views one state from several: give one of them"});
  if (!a.points.empty()) {
    const char* ignored = !a.stages.empty() ? "--stages" : !a.animate.empty() ? "--animate" : a.stop_after != SIZE_MAX ? "--stop-after"
                          : a.in.dim != 0 ? "--dim" : a.in.merge_duplicates ? "--merge-duplicates"
                          : a.in.format != "auto" && !a.in.format.empty() ? "--format" : nullptr;
    if (ignored)
      return fail({StatusCode::InvalidArgument,
                   std::string(ignored) + " applies to a point set that render reconstructs; with --points, " + a.in.path +
                       " is a result (point indices) drawn as it is: drop " + ignored});
  }
  // Checked before any view is made: 2e9 views allocated 8 GB before the size check refused them.
  if (a.views > kMaxViews)
    return fail({StatusCode::InvalidArgument, "--views must be at most " + std::to_string(kMaxViews) +
                                                  " (a sheet of 32 x 32 panels of 512 pixels, the largest picture)"});
  if (!a.points.empty()) {  // a 2D polygon result over --points
    PointSet pts;
    ReadOptions ro;
    ro.check = false;
    if (Status s = read_points(a.points, ro, pts); !s) return fail(columns_advice(s, false));
    // (The dimension from the data: a forced 2 had cut 3D points to x, y without a word.)
    if (pts.dim != 2)
      return fail({StatusCode::InvalidArgument,
                   a.points + ": 3D points; the indices of a 2D result refer to 2D points (give the 2D input)"});
    std::vector<std::vector<int>> rings;
    if (Status s = read_rings_result(a.in.path, pts, rings); !s) return fail(s);
    if (Status s = check_dimension_options(a, 2); !s) return fail(s);
    GammaFaces dt;
    if (!a.no_graph)
      if (Status s = delaunay_layer(pts, dt); !s)  // (--merge-duplicates would renumber what the indices refer to)
        return fail({s.code(), "--points " + a.points + ": the Delaunay graph under the result cannot be drawn (" + s.message() +
                                   "); with --points, --merge-duplicates does not apply: draw the result alone with --no-graph"});
    PolygonSvgLayers layers;
    layers.graph = a.no_graph ? nullptr : &dt;
    layers.title = "constrict: " + a.in.path;
    std::size_t vertices = 0;
    for (const auto& r : rings) vertices += r.size();
    if (rings.size() == 1) {
      if (Status s = write_picture2(a, pts, {Panel2{rings[0], &layers}}, a.out); !s) return fail(s);
      if (!a.quiet) std::printf("polygon of %zu vertices -> %s\n", vertices, a.out.c_str());
    } else {
      if (Status s = write_rings_picture2(a, pts, rings_by_orientation(pts, rings), layers, a.out); !s) return fail(s);
      if (!a.quiet) std::printf("%zu rings of %zu vertices -> %s\n", rings.size(), vertices, a.out.c_str());
    }
    return 0;
  }
  const std::string ie = lower_ext(a.in.path);
  // (--format names a mesh format too, and "-" is standard input: a piped mesh was read as points.)
  const std::string& fmt = a.in.format;
  const std::string mesh_fmt = is_mesh_ext(fmt) ? fmt : fmt == "auto" || fmt.empty() ? ie : std::string();
  if (is_mesh_ext(mesh_fmt)) {  // a mesh, unless it has no faces (by --format too, and on standard input)
    PointSet pts;
    TriMesh3 mesh;
    const Status s = read_mesh(a.in.path, mesh_fmt, pts, mesh);
    if (s) {
      if (!a.stages.empty() || !a.animate.empty() || a.stop_after != SIZE_MAX)
        return fail({StatusCode::InvalidArgument, "--stages, --animate and --stop-after need a point set, not a mesh"});
      if (Status cs = check_dimension_options(a, 3); !cs) return fail(cs);
      return render_mesh_file(a, pts, mesh);
    }
    if (s.code() != StatusCode::EmptyInput) return fail(s);
  }
  // A polygon's indices or a rings file read as points failed with a field count error.
  if ((ie == "idx" || ie == "gt" || ie == "rings") && (a.in.format.empty() || a.in.format == "auto"))
    return fail({StatusCode::InvalidArgument,
                 a.in.path + " is a 2D result (point indices), not points: give its points with --points"});
  PointSet pts;
  ReadReport rep;
  if (Status s = read_input(a.in, pts, rep); !s) return fail(columns_advice(s, true));
  if (Status s = check_dimension_options(a, pts.dim); !s) return fail(s);
  return pts.dim == 2 ? render_points2(a, pts) : render_points3(a, pts);
}

}  // namespace

int render_reconstruction2(const std::string& path, const PointSet& pts, const Polygon2Result& r) {
  GammaFaces dt;
  if (Status s = delaunay_layer(pts, dt); !s) return fail(s);
  PolygonSvgLayers layers;
  layers.graph = &dt;
  layers.highlight_points = r.stuck_points;
  layers.highlight_edges = r.fallback_edges;
  RenderArgs a;
  a.out = path;
  if (lower_ext(path) != "png" && lower_ext(path) != "svg")
    return fail({StatusCode::InvalidArgument, path + ": the picture is .png or .svg"});
  if (Status s = write_picture2(a, pts, {Panel2{r.boundary, &layers}}, path); !s) return fail(s);
  return 0;
}

int render_rings2(const std::string& path, const PointSet& pts, const std::vector<Ring2>& rings) {
  if (lower_ext(path) != "png" && lower_ext(path) != "svg")
    return fail({StatusCode::InvalidArgument, path + ": the picture is .png or .svg"});
  if (rings.empty()) return fail({StatusCode::InvalidArgument, "render: no ring to draw"});
  GammaFaces dt;
  if (Status s = delaunay_layer(pts, dt); !s) return fail(s);
  PolygonSvgLayers layers;
  layers.graph = &dt;
  RenderArgs a;
  a.out = path;
  if (Status s = write_rings_picture2(a, pts, rings, layers, path); !s) return fail(s);
  return 0;
}

int render_reconstruction3(const std::string& path, const PointSet& pts, const TriMesh3& mesh) {
  RenderArgs a;
  a.out = path;
  a.quiet = true;
  return render_mesh_file(a, pts, mesh);
}

Command add_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render", "draw a reconstruction (from points), a 2D polygon result (--points) or a 3D mesh as PNG/SVG");
  add_input_options(cmd, a->in, false);  // --columns is the sheet's here
  cmd->add_option("-o,--output", a->out, "picture: .png (2D, 3D) or .svg (2D, one panel)")->required()->check(non_empty_path());
  cmd->add_option("--points", a->points,
                  "INPUT is a 2D result over these points: a polygon (.idx .csv) or rings (.gt .rings)")->check(non_empty_path());
  cmd->add_option("--size", a->size, "image size WxH (default 1024x1024; sheets 512 per cell)")->check(non_empty());
  cmd->add_option("--view", a->view, "3D: azimuth,elevation in degrees (default 35,25)")->check(non_empty());
  cmd->add_option("--views", a->views, "3D: a sheet of N views around the object (azimuth steps of 360/N)")->check(non_empty());
  cmd->add_option("--columns", a->columns, "sheet columns (default: about square)")->check(non_empty());
  cmd->add_flag("--wireframe", a->wireframe, "3D: draw the triangle edges");
  cmd->add_option("--up", a->up, "3D: model axis drawn upwards (default z)")->check(CLI::IsMember({"x", "y", "z"}));
  cmd->add_flag("--no-graph", a->no_graph, "2D: leave out the dashed Delaunay graph");
  cmd->add_option("--stop-after", a->stop_after, "draw the state after K removals of the constriction")->check(non_negative_integer());
  cmd->add_option("--stages", a->stages, "sheet of constriction stages: auto (hull, 1/4, 1/2, 3/4, final) or K1,K2,...")
      ->check(non_empty());
  cmd->add_option("--animate", a->animate, "2D: write frames of the whole constriction to DIR (frame_NNNN.svg/png)")->check(non_empty_path());
  cmd->add_flag("-q,--quiet", a->quiet, "no summary line");
  return {cmd, [a] { return run_render(*a); }};
}

}  // namespace constrict::cli
