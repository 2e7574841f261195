// SPDX-License-Identifier: GPL-3.0-or-later
// The constrict command line: parse arguments, call the library, write results. No geometry here.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "constrict/gamma_graph.hpp"
#include "constrict/io.hpp"
#include "constrict/version.hpp"

namespace {

using namespace constrict;
using Clock = std::chrono::steady_clock;

double ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

int fail(const Status& s) {
  std::fprintf(stderr, "constrict: error [%s]: %s\n", to_string(s.code()), s.message().c_str());
  return exit_code(s.code());
}

struct InputArgs {
  std::string path;
  int dim = 0;
  bool merge_duplicates = false;
};

void add_input_options(CLI::App* cmd, InputArgs& in) {
  cmd->add_option("INPUT", in.path, "input points (.xyz .xy .csv .txt .ply .off .obj)")->required();
  cmd->add_option("--dim", in.dim, "force the dimension (default: from the data)")->check(CLI::IsMember({2, 3}));
  cmd->add_flag("--merge-duplicates", in.merge_duplicates,
                "keep the first of identical points (default: duplicates are an error)");
}

Status read_input(const InputArgs& in, PointSet& pts, ReadReport& rep, bool quiet) {
  ReadOptions opt;
  opt.dim = in.dim;
  opt.merge_duplicates = in.merge_duplicates;
  Status s = read_points(in.path, opt, pts, &rep);
  if (s && !quiet)
    for (const auto& w : rep.warnings) std::fprintf(stderr, "constrict: warning: %s\n", w.c_str());
  return s;
}

// Splits "a,b,c" into doubles; returns false on a malformed list or the wrong count.
bool parse_list(const std::string& text, std::size_t count, std::vector<double>& out) {
  out.clear();
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = text.find(',', pos);
    const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size()) return false;
      out.push_back(v);
    } catch (...) {
      return false;
    }
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out.size() == count;
}

Status write_report(const std::string& path, const nlohmann::json& j) {
  std::ofstream f(path);
  if (!f) return {StatusCode::WriteFailed, path + ": cannot open report for writing"};
  f << j.dump(2) << '\n';
  if (!f) return {StatusCode::WriteFailed, path + ": writing the report failed"};
  return Status::ok();
}

struct GraphArgs {
  InputArgs in;
  std::string out, report, gamma, interval, preset;
  bool quiet = false;
};

int run_graph(const GraphArgs& a) {
  const auto t0 = Clock::now();
  PointSet pts;
  ReadReport rep;
  if (Status s = read_input(a.in, pts, rep, a.quiet); !s) return fail(s);
  const auto t1 = Clock::now();

  GraphSpec spec;
  std::vector<double> v;
  const int given = !a.gamma.empty() + !a.interval.empty() + !a.preset.empty();
  if (given > 1) return fail({StatusCode::InvalidArgument, "give only one of --gamma, --interval, --preset"});
  if (!a.gamma.empty()) {
    if (!parse_list(a.gamma, 2, v))
      return fail({StatusCode::InvalidArgument, "--gamma expects two numbers G0,G1 (e.g. --gamma 0,0), got '" + a.gamma + "'"});
    spec = GraphSpec::fixed(v[0], v[1]);
  } else if (!a.interval.empty()) {
    if (!parse_list(a.interval, 4, v))
      return fail({StatusCode::InvalidArgument, "--interval expects four numbers A0,A1,B0,B1 (e.g. --interval -1,1,0,1), got '" + a.interval + "'"});
    spec = GraphSpec::interval(v[0], v[1], v[2], v[3]);
  } else if (Status s = GraphSpec::from_preset(a.preset.empty() ? "delaunay" : a.preset, spec); !s) {
    return fail(s);
  }
  if (Status s = spec.validate(); !s) return fail(s);
  // Check the output format before the (possibly long) computation.
  const GraphFormat fmt = graph_format_from_path(a.out);
  if (fmt == GraphFormat::Auto)
    return fail({StatusCode::InvalidArgument, a.out + ": unknown output extension (use .csv, .json, .svg, .off, .ply or .obj)"});

  GammaFaces faces;
  GraphStats stats;
  if (Status s = build_gamma_graph(pts, spec, faces, &stats); !s) return fail(s);
  const auto t2 = Clock::now();
  if (Status s = write_graph(a.out, pts, faces, spec.describe(), fmt); !s) return fail(s);
  const auto t3 = Clock::now();

  const char* what = pts.dim == 2 ? "edges" : "triangles";
  if (!a.quiet)
    std::printf("%s on %zu points (%dD): %zu %s -> %s (%.0f ms)\n", spec.describe().c_str(), pts.size(), pts.dim,
                faces.size(), what, a.out.c_str(), ms(t0, t3));
  if (!a.report.empty()) {
    nlohmann::json j;
    j["command"] = "graph";
    j["input"] = a.in.path;
    j["dimension"] = pts.dim;
    j["points"] = pts.size();
    j["points_read"] = rep.points_read;
    j["merged_duplicates"] = rep.merged_duplicates;
    j["graph"] = spec.describe();
    j["faces"] = faces.size();
    j["delaunay_faces"] = stats.delaunay_faces;
    j["extra_candidates"] = stats.extra_candidates;
    j["output"] = a.out;
    j["timings_ms"] = {{"read", ms(t0, t1)}, {"delaunay_gamma", stats.ms_gamma}, {"extra", stats.ms_extra},
                       {"graph", ms(t1, t2)}, {"write", ms(t2, t3)}, {"total", ms(t0, t3)}};
    j["warnings"] = rep.warnings;
    if (Status s = write_report(a.report, j); !s) return fail(s);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"constrict " CONSTRICT_VERSION_STRING
               " - object reconstruction with the gamma-neighborhood graph (Veltkamp)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("constrict ") + CONSTRICT_VERSION_STRING);

  GraphArgs g;
  CLI::App* graph = app.add_subcommand("graph", "build a gamma-neighborhood graph (2D edges / 3D triangles)");
  add_input_options(graph, g.in);
  graph->add_option("-o,--output", g.out, "output file: .csv .json .svg .off .ply .obj")->required();
  auto* og = graph->add_option("--gamma", g.gamma, "fixed parameters G0,G1 in [-1,1], e.g. 0,0 (Gabriel)");
  auto* oi = graph->add_option("--interval", g.interval, "interval graph A0,A1,B0,B1, e.g. -1,1,0,1 (Delaunay)");
  auto* op = graph->add_option("--preset", g.preset,
                               "hull | delaunay (default) | gabriel | beta-circle=B | beta-lune=B | complete | void");
  og->excludes(oi)->excludes(op);
  oi->excludes(op);
  graph->add_option("--report", g.report, "write a JSON report (counts, timings)");
  graph->add_flag("-q,--quiet", g.quiet, "no summary line on stdout");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "constrict: error [InvalidArgument]: %s (see constrict --help)\n", e.what());
    return exit_code(StatusCode::InvalidArgument);
  }
  try {
    if (graph->parsed()) return run_graph(g);
  } catch (const InternalError& e) {
    std::fprintf(stderr, "constrict: internal error (please report): %s\n", e.what());
    return exit_code(StatusCode::Internal);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "constrict: error [Unsupported]: out of memory\n");
    return exit_code(StatusCode::Unsupported);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "constrict: internal error (please report): %s\n", e.what());
    return exit_code(StatusCode::Internal);
  }
  return 0;
}
