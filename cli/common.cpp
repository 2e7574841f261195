// SPDX-License-Identifier: GPL-3.0-or-later
#include "common.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace constrict::cli {

int fail(const Status& s) {
  std::fprintf(stderr, "constrict: error [%s]: %s\n", to_string(s.code()), s.message().c_str());
  return exit_code(s.code());
}

int fail_in(const std::string& input, const Status& s) {
  if (s.message().rfind(input + ":", 0) == 0) return fail(s);
  return fail(Status(s.code(), input + ": " + s.message()));
}

int fail_in(const std::string& input, const ReadReport& rep, const Status& s) {
  if (s.code() != StatusCode::Collinear && s.code() != StatusCode::Coplanar) return fail_in(input, s);
  return fail_in(input, Status(s.code(), degenerate_message_for(rep.format, s.message())));
}

void add_input_options(CLI::App* cmd, InputArgs& in, bool columns) {
  cmd->add_option("INPUT", in.path, "input points (.xyz .xy .csv .txt .ply .off .obj .stl .geojson)")
      ->required()
      ->check(non_empty_path());
  cmd->add_option("--dim", in.dim, "force the dimension (default: from the data)")
      ->check(non_empty())
      ->check(CLI::IsMember({2, 3}));
  cmd->add_flag("--merge-duplicates", in.merge_duplicates,
                "keep the first of identical points (default: duplicates are an error); output indices stay file rows");
  cmd->add_option("--format", in.format, "input format, overrides the extension: text | ply | off | obj | stl | geojson")
      ->check(CLI::IsMember({"auto", "text", "ply", "off", "obj", "stl", "geojson"}));
  if (columns)
    cmd->add_option("--columns", in.columns,
                    "text input: the x,y[,z] columns, 1-based numbers (2,3,4) or header names (x,y,z)")
        ->check(non_empty());
}

// Warnings (e.g. merged duplicates) are printed even with --quiet: dropping data is never silent.
Status read_input(const InputArgs& in, PointSet& pts, ReadReport& rep, bool check) {
  ReadOptions opt;
  opt.dim = in.dim;
  opt.check = check;
  opt.merge_duplicates = in.merge_duplicates;
  if (Status s = point_format_from_name(in.format, opt.format); !s) return s;
  if (!in.columns.empty())
    if (Status s = parse_columns(in.columns, opt.columns); !s) return s;
  Status s = read_points(in.path, opt, pts, &rep);
  if (s)
    for (const auto& w : rep.warnings) std::fprintf(stderr, "constrict: warning: %s\n", w.c_str());
  return s;
}

nlohmann::json merged_json(const ReadReport& rep) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& p : rep.merged) pairs.push_back({p[0], p[1]});
  return pairs;
}

Status wrong_dimension(const std::string& option, int dim, const std::string& input) {
  const int other = dim == 2 ? 3 : 2;
  return {StatusCode::InvalidArgument, option + " is a " + std::to_string(other) + "D option, but " + input +
                                           " is " + std::to_string(dim) + "D; leave it out (or check --dim)"};
}

std::string lower_ext(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string e = path.substr(dot + 1);
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

bool is_mesh_ext(const std::string& ext) { return ext == "off" || ext == "ply" || ext == "obj" || ext == "stl"; }

namespace {
bool same_file(const std::string& a, const std::string& b) {
  if (a == b) return true;
  std::error_code ec1, ec2;
  if (std::filesystem::equivalent(a, b, ec1)) return true;  // both exist: hard links, symlinks
  const auto p = std::filesystem::weakly_canonical(a, ec1), q = std::filesystem::weakly_canonical(b, ec2);
  return !ec1 && !ec2 && !p.empty() && p == q;
}
}  // namespace

Status check_distinct_files(std::initializer_list<NamedPath> inputs, std::initializer_list<NamedPath> outputs) {
  const std::vector<NamedPath> out(outputs), in(inputs);
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i].second->empty()) continue;
    // ("-" would be a file of that name: standard output carries the summary line.)
    if (*out[i].second == "-")
      return {StatusCode::InvalidArgument,
              std::string(out[i].first) + " -: results are written to files, not to standard output; give a file name"};
    // (Before the input is read: a graph of a minute's work then failed to write into a directory.)
    std::error_code ec;
    if (std::filesystem::is_directory(*out[i].second, ec))
      return {StatusCode::InvalidArgument, std::string(out[i].first) + " names a directory (" + *out[i].second +
                                               "): give a file name in it"};
    for (const NamedPath& x : in)
      if (!x.second->empty() && same_file(*out[i].second, *x.second))
        return {StatusCode::InvalidArgument, std::string(out[i].first) + " names the input " + x.first + " (" + *x.second +
                                                 "): it would be overwritten; give the output another name"};
    for (std::size_t j = i + 1; j < out.size(); ++j)
      if (!out[j].second->empty() && same_file(*out[i].second, *out[j].second))
        return {StatusCode::InvalidArgument, std::string(out[i].first) + " and " + out[j].first + " name the same file (" +
                                                 *out[i].second + "); give each its own"};
  }
  return Status::ok();
}

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
  if (!f) return {StatusCode::WriteFailed, path + ": cannot open report for writing (" + std::strerror(errno) + ")"};
  // (Paths and names are the user's bytes: any that are not UTF-8 become U+FFFD in the report,
  // instead of JSON's type error.)
  f << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
  f.close();  // (a small report fails only when its buffer is flushed: /dev/full)
  if (!f) return {StatusCode::WriteFailed, path + ": writing the report failed"};
  return Status::ok();
}

Progress::Progress(bool enabled) : enabled_(enabled), start_(Clock::now()) {
  if (enabled_) thread_ = std::thread([this] { run(); });
}

Progress::~Progress() {
  if (!enabled_) return;
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void Progress::phase(const std::string& name) {
  if (!enabled_) return;
  {
    std::lock_guard<std::mutex> lock(m_);
    phase_ = name;
  }
  done_.store(0);
  total_.store(0);
}

void Progress::count(std::size_t done, std::size_t total) {
  total_.store(total);
  done_.store(done);
}

void Progress::run() {
  std::unique_lock<std::mutex> lock(m_);
  auto next = start_ + std::chrono::seconds(1);
  while (!cv_.wait_until(lock, next, [this] { return stop_; })) {
    const double s = ms(start_, Clock::now()) / 1000.0;
    const std::size_t total = total_.load(), done = done_.load();
    if (total > 0)
      std::fprintf(stderr, "constrict: %6.1f s  %s %zu/%zu\n", s, phase_.c_str(), done, total);
    else
      std::fprintf(stderr, "constrict: %6.1f s  %s\n", s, phase_.c_str());
    next += std::chrono::seconds(1);
  }
}

namespace {
// A number as CLI11 reads it (strtod: also "inf", "1e400" -> inf), or false.
bool option_number(const std::string& text, double& v) {
  if (text.empty()) return false;
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}
}  // namespace

CLI::Validator non_empty_path() {
  return CLI::Validator([](std::string& text) -> std::string { return text.empty() ? "an empty file name" : ""; }, "");
}

CLI::Validator non_empty() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "an empty value (leave the option out for its default)" : "";
      },
      "");
}

CLI::Validator non_negative_integer() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
          return "'" + text + "' is not a non-negative integer (0, 1, 2, ...)";
        if (text.size() > 19) return "'" + text + "' is too large (at most 19 digits)";
        return {};
      },
      "INT >= 0");
}

namespace {
// A finite number above 0 (strict) or at least 0.
CLI::Validator finite_number_from_zero(bool strict) {
  const std::string what = strict ? "a finite number > 0" : "a finite number >= 0";
  return CLI::Validator(
      [strict, what](std::string& text) -> std::string {
        double v = 0;
        if (!option_number(text, v) || !std::isfinite(v) || v < 0 || (strict && v == 0)) return "'" + text + "' is not " + what;
        return {};
      },
      strict ? "NUMBER > 0" : "NUMBER >= 0");
}
}  // namespace

CLI::Validator non_negative_number() { return finite_number_from_zero(false); }
CLI::Validator positive_number() { return finite_number_from_zero(true); }

}  // namespace constrict::cli
