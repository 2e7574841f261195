// SPDX-License-Identifier: GPL-3.0-or-later
// The constrict command line: parse arguments, call the library, write results. No geometry here.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "commands.hpp"
#include "constrict/status.hpp"
#include "constrict/version.hpp"

int main(int argc, char** argv) {
  using namespace constrict;
  CLI::App app{"constrict " CONSTRICT_VERSION_STRING
               " - object reconstruction with the gamma-neighborhood graph (Veltkamp)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("constrict ") + CONSTRICT_VERSION_STRING);
  const std::vector<cli::Command> commands = {cli::add_reconstruct_command(app), cli::add_graph_command(app),
                                             cli::add_compare_command(app), cli::add_render_command(app)};

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
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
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
