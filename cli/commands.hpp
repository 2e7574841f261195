// SPDX-License-Identifier: GPL-3.0-or-later
// Registration of the subcommands. Each returns the subcommand and the function that runs it
// (the argument storage lives inside the function object).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace constrict {
struct PointSet;
struct Polygon2Result;
struct Ring2;
struct TriMesh3;
class Status;
}  // namespace constrict

namespace constrict::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command add_graph_command(CLI::App& app);
Command add_reconstruct_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_render_command(CLI::App& app);

/// A 2D polygon result as input indices: .gt (one closed curve), .idx (one index per line) or .csv
/// (x,y rows matched to @p pts by exact coordinates). (cmd_compare.cpp)
Status read_polygon_result(const std::string& path, const PointSet& pts, std::vector<int>& poly);
/// A 2D result of one or several closed rings: a .gt or .rings file (every `c` line a ring; open
/// polylines are refused) or any one-polygon result of read_polygon_result(). (cmd_compare.cpp)
Status read_rings_result(const std::string& path, const PointSet& pts, std::vector<std::vector<int>>& rings);
/// `reconstruct --render PIC`: the picture of a result (.svg/.png 2D, .png 3D); returns the exit
/// code (0 or the failure's). (cmd_render.cpp)
int render_reconstruction2(const std::string& path, const PointSet& pts, const Polygon2Result& r);
/// The picture of a ring set (`reconstruct --topology auto --render PIC`, .png or .svg).
int render_rings2(const std::string& path, const PointSet& pts, const std::vector<Ring2>& rings);
int render_reconstruction3(const std::string& path, const PointSet& pts, const TriMesh3& mesh);

}  // namespace constrict::cli
