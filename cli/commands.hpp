// SPDX-License-Identifier: GPL-3.0-or-later
// Registration of the subcommands. Each returns the subcommand and the function that runs it
// (the argument storage lives inside the function object).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace constrict::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command add_graph_command(CLI::App& app);
Command add_reconstruct_command(CLI::App& app);
Command add_compare_command(CLI::App& app);

}  // namespace constrict::cli
