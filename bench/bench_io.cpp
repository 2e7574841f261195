// SPDX-License-Identifier: GPL-3.0-or-later
// Reading speed of read_points(): text columns (2D and 3D, every coordinate printed with %.17g,
// the worst case for the number parser) and binary PLY (float32 and float64), 1e4 to 1e6 points.
// Each input file is written once to a private temporary directory (fixed seed) and removed at
// exit. The /check:1 variants include the full check_points() (duplicates, collinear/coplanar),
// which is what the CLI runs; /check:0 is parsing alone.
// Link with benchmark::benchmark_main (this file has no main()).
#include <benchmark/benchmark.h>
#include <stdlib.h>  // mkdtemp

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <tuple>

#include "constrict/io.hpp"

namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kSeed = 12345;

enum class Kind { Text, PlyFloat, PlyDouble };

// Owns the temporary directory and the files written into it.
class InputFiles {
 public:
  ~InputFiles() {
    if (!dir_.empty()) {
      std::error_code ec;
      fs::remove_all(dir_, ec);
    }
  }

  // Path of the file with n random points in [-1, 1]^dim, written on first use; empty on failure.
  const std::string& get(Kind kind, int dim, std::int64_t n) {
    const auto key = std::make_tuple(kind, dim, n);
    auto it = files_.find(key);
    if (it != files_.end()) return it->second;
    std::string& path = files_[key];
    if (dir_.empty()) {
      std::string tmpl = (fs::temp_directory_path() / "constrict_bench_io_XXXXXX").string();
      if (mkdtemp(&tmpl[0]) == nullptr) return path;
      dir_ = tmpl;
    }
    const char* ext = kind == Kind::Text ? ".xyz" : ".ply";
    const std::string name = (dir_ / ("points_" + std::to_string(static_cast<int>(kind)) + "_" +
                                      std::to_string(dim) + "d_" + std::to_string(n) + ext))
                                 .string();
    if (write(name, kind, dim, n)) path = name;
    return path;
  }

 private:
  static bool write(const std::string& name, Kind kind, int dim, std::int64_t n) {
    std::FILE* f = std::fopen(name.c_str(), "wb");
    if (f == nullptr) return false;
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> coord(-1.0, 1.0);
    if (kind == Kind::Text) {
      std::fprintf(f, "# %lld random points, seed %llu\n", static_cast<long long>(n),
                   static_cast<unsigned long long>(kSeed));
      for (std::int64_t i = 0; i < n; ++i) {
        for (int k = 0; k < dim; ++k)
          std::fprintf(f, k + 1 < dim ? "%.17g " : "%.17g\n", coord(rng));
      }
    } else {
      const bool as_float = kind == Kind::PlyFloat;
      const char* type = as_float ? "float" : "double";
      // Written in the host's byte order, declared in the header.
      const std::uint16_t one = 1;
      unsigned char first = 0;
      std::memcpy(&first, &one, 1);
      std::fprintf(f, "ply\nformat %s 1.0\nelement vertex %lld\n",
                   first == 1 ? "binary_little_endian" : "binary_big_endian",
                   static_cast<long long>(n));
      for (int k = 0; k < dim; ++k) std::fprintf(f, "property %s %c\n", type, "xyz"[k]);
      std::fprintf(f, "end_header\n");
      for (std::int64_t i = 0; i < n; ++i) {
        for (int k = 0; k < dim; ++k) {
          const double v = coord(rng);
          if (as_float) {
            const auto fv = static_cast<float>(v);
            std::fwrite(&fv, sizeof fv, 1, f);
          } else {
            std::fwrite(&v, sizeof v, 1, f);
          }
        }
      }
    }
    return std::fclose(f) == 0;
  }

  fs::path dir_;
  std::map<std::tuple<Kind, int, std::int64_t>, std::string> files_;
};

InputFiles& files() {
  static InputFiles instance;
  return instance;
}

void run(benchmark::State& state, Kind kind, int dim) {
  const std::int64_t n = state.range(0);
  const std::string& path = files().get(kind, dim, n);
  if (path.empty()) {
    state.SkipWithError("cannot write the input file");
    return;
  }
  constrict::ReadOptions options;
  options.check = state.range(1) != 0;
  for (auto _ : state) {
    constrict::PointSet points;
    const constrict::Status st = constrict::read_points(path, options, points);
    if (!st) {
      state.SkipWithError(st.message().c_str());
      return;
    }
    benchmark::DoNotOptimize(points.coords.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(fs::file_size(path)));
}

void BM_ReadText3D(benchmark::State& state) { run(state, Kind::Text, 3); }
void BM_ReadText2D(benchmark::State& state) { run(state, Kind::Text, 2); }
void BM_ReadPlyFloat3D(benchmark::State& state) { run(state, Kind::PlyFloat, 3); }
void BM_ReadPlyDouble3D(benchmark::State& state) { run(state, Kind::PlyDouble, 3); }

void sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"n", "check"});
  for (std::int64_t n : {10000, 100000, 1000000})
    for (std::int64_t check : {0, 1}) b->Args({n, check});
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_ReadText3D)->Apply(sizes);
BENCHMARK(BM_ReadText2D)->Apply(sizes);
BENCHMARK(BM_ReadPlyFloat3D)->Apply(sizes);
BENCHMARK(BM_ReadPlyDouble3D)->Apply(sizes);

}  // namespace
