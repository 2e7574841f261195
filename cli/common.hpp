// SPDX-License-Identifier: GPL-3.0-or-later
// Shared pieces of the constrict subcommands: error reporting, input options, JSON reports,
// progress on stderr. No geometry here.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <initializer_list>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "constrict/io.hpp"
#include "constrict/status.hpp"

namespace constrict::cli {

using Clock = std::chrono::steady_clock;

inline double ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

/// Prints `constrict: error [Code]: message` and returns the exit code of the status.
int fail(const Status& s);
/// fail() for an error of the engine about the input's points: the message names the input file.
int fail_in(const std::string& input, const Status& s);
// ... an engine's status on the points read with `rep` (its Collinear / Coplanar hint fits the
// input's format).
int fail_in(const std::string& input, const ReadReport& rep, const Status& s);

struct InputArgs {
  std::string path;
  int dim = 0;
  bool merge_duplicates = false;
  std::string format = "auto";  // --format, a PointFormat name
  std::string columns;          // --columns, "2,3,4" or "x,y,z" (parse_columns)
};

/// INPUT, --dim, --merge-duplicates, --format and (unless @p columns is false: `render` has its own
/// --columns, the sheet's) --columns.
void add_input_options(CLI::App* cmd, InputArgs& in, bool columns = true);
// check = false: the points as parsed (parse-level defects are still errors); for commands whose
// library call checks its input itself (duplicates, too few, collinear, coplanar), so the O(N log N)
// duplicate search does not run twice.
/// Option checks with short messages (CLI11's ranges print the whole double range).
/// Refuses an empty value (`--columns ''` silently meant the default).
CLI::Validator non_empty();
// An option naming a file: refuses an empty name ("-o ''").
CLI::Validator non_empty_path();
CLI::Validator non_negative_integer();
CLI::Validator non_negative_number();
CLI::Validator positive_number();

Status read_input(const InputArgs& in, PointSet& pts, ReadReport& rep, bool check = true);

/// Output indices are the file's rows (docs/cli.md "Duplicates"): result point @p i is file row
/// rep.original_index[i]; the identity when nothing was merged.
inline int file_row(const ReadReport& rep, int i) {
  return static_cast<int>(rep.original_index[static_cast<std::size_t>(i)]);
}
/// The report's "merged": [[kept_row, dropped_row], ...] (empty when nothing was merged).
nlohmann::json merged_json(const ReadReport& rep);
/// InvalidArgument for an option that does not apply to an input of dimension @p dim.
Status wrong_dimension(const std::string& option, int dim, const std::string& input);

/// Splits "a,b,c" into exactly @p count doubles; false on a malformed list or another count.
bool parse_list(const std::string& text, std::size_t count, std::vector<double>& out);

/// The extension of @p path in lower case, without the dot ("" when the last component has none).
std::string lower_ext(const std::string& path);
/// True for the mesh extensions the library reads and writes: off, ply, obj, stl (lower case).
bool is_mesh_ext(const std::string& ext);

/// A named file path of a command ("-o", "--report", "INPUT", ...).
using NamedPath = std::pair<const char*, const std::string*>;
/// InvalidArgument when two of @p outputs, or an output and one of @p inputs, name the same file
/// (the same path after resolving ".." and links, or the same existing file): a run must not
/// overwrite its own input or one output with another; or when an output names a directory or is
/// "-" (results go to files). Empty paths are skipped.
Status check_distinct_files(std::initializer_list<NamedPath> inputs, std::initializer_list<NamedPath> outputs);

Status write_report(const std::string& path, const nlohmann::json& j);

/// Progress lines on stderr for long runs: silent during the first second, then one line per
/// second with the current phase and an optional counter. Thread-safe setters; the printing
/// thread stops in the destructor.
class Progress {
 public:
  explicit Progress(bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void phase(const std::string& name);
  void count(std::size_t done, std::size_t total);
  /// False with -q: nothing is shown, so the engines need not report their steps.
  bool enabled() const { return enabled_; }

 private:
  void run();
  bool enabled_;
  Clock::time_point start_;
  std::string phase_ = "starting";  // guarded by m_
  std::atomic<std::size_t> done_{0}, total_{0};
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace constrict::cli
