// SPDX-License-Identifier: GPL-3.0-or-later
// `constrict graph`: one graph of the γ-neighborhood family.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/io.hpp"

namespace constrict::cli {
namespace {

struct GraphArgs {
  InputArgs in;
  std::string out, report, gamma, interval, preset;
  bool quiet = false;
};

int run_graph(const GraphArgs& a) {
  const auto t0 = Clock::now();
  if (Status s = check_distinct_files({{"INPUT", &a.in.path}}, {{"-o", &a.out}, {"--report", &a.report}}); !s) return fail(s);
  PointSet pts;
  ReadReport rep;
  if (Status s = read_input(a.in, pts, rep); !s) return fail(s);
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
  if (Status s = check_graph_format(a.out, pts.dim, fmt); !s) return fail(s);

  GammaFaces faces;
  GraphStats stats;
  if (Status s = build_gamma_graph(pts, spec, faces, &stats); !s) return fail(s);
  const auto t2 = Clock::now();
  // Indices written are the file's rows, also after --merge-duplicates (docs/cli.md); the map is
  // increasing, so the faces stay sorted.
  if (!rep.merged.empty())
    for (int& id : faces.vertices) id = file_row(rep, id);
  PointSet merged_rows;
  if (!rep.merged.empty()) merged_rows = file_row_points(pts, rep);
  const PointSet& rows = rep.merged.empty() ? pts : merged_rows;
  if (Status s = write_graph(a.out, rows, faces, spec.describe(), fmt); !s) return fail(s);
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
    j["merged"] = merged_json(rep);
    j["warnings"] = rep.warnings;
    if (Status s = write_report(a.report, j); !s) return fail(s);
  }
  return 0;
}

}  // namespace

Command add_graph_command(CLI::App& app) {
  auto a = std::make_shared<GraphArgs>();
  CLI::App* cmd = app.add_subcommand("graph", "build a gamma-neighborhood graph (2D edges / 3D triangles)");
  add_input_options(cmd, a->in);
  cmd->add_option("-o,--output", a->out, "output file: .csv .json .svg .off .ply .obj")->required()->check(non_empty_path());
  auto* og =
      cmd->add_option("--gamma", a->gamma, "fixed parameters G0,G1 in [-1,1], e.g. 0,0 (Gabriel)")->check(non_empty());
  auto* oi = cmd->add_option("--interval", a->interval, "interval graph A0,A1,B0,B1, e.g. -1,1,0,1 (Delaunay)")
                 ->check(non_empty());
  auto* op = cmd->add_option("--preset", a->preset,
                             "hull | delaunay (default) | gabriel | beta-circle=B | beta-lune=B | complete | void")
                 ->check(non_empty());
  og->excludes(oi)->excludes(op);
  oi->excludes(op);
  cmd->add_option("--report", a->report, "write a JSON report (counts, timings)")->check(non_empty_path());
  cmd->add_flag("-q,--quiet", a->quiet, "no summary line on stdout");

  return {cmd, [a] { return run_graph(*a); }};
}

}  // namespace constrict::cli
