// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: build_gamma_graph() on small decoded point sets (2D or 3D) with a decoded
// GraphSpec -- a preset (GraphSpec::from_preset, bad names and values included), fixed(g0, g1)
// with either value < 0, or an interval -- (docs/fuzzing.md). Contract (gamma_graph.hpp): a bad
// spec is InvalidArgument, bad points give the check_points() status, a size cap Unsupported;
// an Ok graph lists distinct faces sorted by vertex ids, ids ascending and in range, each a
// member by its own side values. On small inputs on a coarse grid the graph is compared with the
// brute-force oracle, skipping faces whose membership a 1e-9 change of a side value would flip
// (the oracle computes the magnitudes another way).
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "constrict/gamma_graph.hpp"
#include "fuzz_engine.hpp"

namespace {

using namespace constrict;
using constrict_fuzz::require;

constexpr double kMargin = 1e-9;           // side-value change below which a decision is skipped
constexpr std::size_t kOracleMax2 = 24;    // oracle O(N^3) in 2D
constexpr std::size_t kOracleMax3 = 10;    // oracle O(N^4) in 3D
// 3D graphs with gamma0 < 0 (the lens scan) on more points are skipped: on near-degenerate input
// every side value falls back to exact arithmetic, O(N^4) of it for the complete graph (48 points
// near a line, some subnormal: 6.7 s in Release, over a minute under ASan; docs/fuzzing.md).
constexpr std::size_t kLensMax3 = 24;

// Side values: a few exact specials (0, ±1, out of range, NaN), else uniform in [-1, 1].
double decode_gamma(constrict_fuzz::Bytes& in) {
  const std::uint8_t b = in.u8();
  const double specials[] = {-1, 1, 0, -0.5, 0.5, -0.1, -0.05, -0.999, 0.999, -1.5, 2, std::nan("")};
  constexpr std::size_t kSpecials = sizeof specials / sizeof specials[0];
  if (b < 2 * kSpecials) return specials[b % kSpecials];
  return (static_cast<double>(b) - 139.5) / 115.5;  // (24 .. 255) -> [-1, 1]
}

GraphSpec decode_spec(constrict_fuzz::Bytes& in, std::string& described) {
  const std::uint8_t kind = in.u8();
  GraphSpec spec;
  switch (kind % 3) {
    case 0: {
      const char* const names[] = {"hull", "delaunay", "gabriel", "complete", "void",
                                   "beta-circle", "beta-lune", "delaunay=1", "nonsense"};
      std::string name = names[in.u8() % 9];
      if (name.rfind("beta", 0) == 0) name += "=" + std::to_string(static_cast<double>(in.u8()) / 64.0);
      described = "preset " + name;
      if (!GraphSpec::from_preset(name, spec).is_ok()) spec = GraphSpec::fixed(std::nan(""), 0);
      break;
    }
    case 1: {
      const double g0 = decode_gamma(in), g1 = decode_gamma(in);
      spec = GraphSpec::fixed(g0, g1);
      break;
    }
    default: {
      const double a0 = decode_gamma(in), a1 = decode_gamma(in), b0 = decode_gamma(in), b1 = decode_gamma(in);
      spec = GraphSpec::interval(a0, a1, b0, b1);
      break;
    }
  }
  if (described.empty()) described = spec.describe();
  return spec;
}

bool robust_member(const GraphSpec& spec, double ga, double gb, bool blocked, bool& decided) {
  auto nudge = [](double v, double d) {
    if (v == 1.0 || v == 0.0) return v;  // empty side and signs are exact
    const double m = std::clamp(std::fabs(v) + d, 1e-300, std::nextafter(1.0, 0.0));
    return v > 0 ? m : -m;
  };
  const bool m = in_graph(spec, ga, gb, blocked);
  decided = true;
  for (double da : {-kMargin, 0.0, kMargin})
    for (double db : {-kMargin, 0.0, kMargin})
      decided = decided && in_graph(spec, nudge(ga, da), nudge(gb, db), blocked) == m;
  return m;
}

using Key = std::vector<int>;

void check_graph(const PointSet& p, const GraphSpec& spec, const GammaFaces& g) {
  require(g.dim == p.dim, "graph dimension");
  const std::size_t d = static_cast<std::size_t>(g.dim);
  require(g.vertices.size() == d * g.size() && g.gamma_b.size() == g.size() && g.delta.size() == g.size() &&
              g.flags.size() == g.size(),
          "face arrays differ in length");
  Key prev;
  for (std::size_t f = 0; f < g.size(); ++f) {
    Key k(&g.vertices[f * d], &g.vertices[f * d] + d);
    for (std::size_t j = 0; j < d; ++j) {
      require(k[j] >= 0 && static_cast<std::size_t>(k[j]) < p.size(), "face id out of range");
      require(j == 0 || k[j - 1] < k[j], "face ids not ascending");
    }
    require(f == 0 || prev < k, "faces not sorted or repeated");
    prev = k;
    require(std::isfinite(g.gamma_a[f]) && std::isfinite(g.gamma_b[f]), "non-finite side value");
    require(in_graph(spec, g.gamma_a[f], g.gamma_b[f], (g.flags[f] & kFaceBlocked) != 0),
            "face not a member by its own side values");
  }
}

// Coordinates on a coarse grid relative to the largest (k / 2^kGridBits after the exact rescaling
// to [1/2, 1)): the oracle's double magnitudes are then accurate. On a near-degenerate face (a
// sliver a few ulps from collinear, fuzz finding of the first run) they are not -- the oracle gave
// γ = ±0.04 where the exact values are -1 and 1 -- while the graph decides signs exactly.
constexpr int kGridBits = 8;
bool on_coarse_grid(const PointSet& scaled) {
  for (double c : scaled.coords) {
    const double k = std::ldexp(c, kGridBits);
    if (k != std::floor(k)) return false;
  }
  return true;
}

// The oracle on the exactly rescaled copy (the side values are scale-free; the oracle's double
// arithmetic is not): every decided face is in the graph iff the oracle says so.
void check_oracle(const PointSet& p, const GraphSpec& spec, const GammaFaces& g) {
  if (p.size() > (p.dim == 2 ? kOracleMax2 : kOracleMax3)) return;
  PointSet scaled;
  int e = 0;
  if (!exact_power_of_two_scale(p, scaled, e).is_ok() || !on_coarse_grid(scaled)) return;
  GammaFaces all;
  if (!brute_force_gamma_faces(scaled, all).is_ok()) return;
  const std::size_t d = static_cast<std::size_t>(g.dim);
  std::set<Key> got;
  for (std::size_t f = 0; f < g.size(); ++f) got.insert(Key(&g.vertices[f * d], &g.vertices[f * d] + d));
  for (std::size_t f = 0; f < all.size(); ++f) {
    bool decided = false;
    const bool want = robust_member(spec, all.gamma_a[f], all.gamma_b[f], (all.flags[f] & kFaceBlocked) != 0, decided);
    if (!decided) continue;
    Key k(&all.vertices[f * d], &all.vertices[f * d] + d);
    std::string ids;
    for (int v : k) ids += std::to_string(v) + " ";
    require(want == (got.count(k) != 0), want ? "oracle face missing" : "face not in the oracle's graph",
            ids + "ga=" + std::to_string(all.gamma_a[f]) + " gb=" + std::to_string(all.gamma_b[f]) + " " +
                spec.describe());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  constrict_fuzz::Bytes in(data, size);
  const int dim = 2 + (in.u8() & 1);
  std::string described;
  const GraphSpec spec = decode_spec(in, described);
  const constrict_fuzz::Decoded d = constrict_fuzz::decode_points(in, dim);
  constrict_fuzz::print_points(d);
  const PointSet& p = d.points;
  if (dim == 3 && p.size() > kLensMax3 && spec.validate().is_ok() && !spec.delaunay_subgraph()) return 0;

  Status spec_ok, checked, st;
  GammaFaces g;
  constrict_fuzz::no_throw("build_gamma_graph", [&] {
    spec_ok = spec.validate();
    checked = check_points(p);
    st = build_gamma_graph(p, spec, g);
  });
  constrict_fuzz::require_one_line(st);
  if (!spec_ok) {
    require(st.code() == StatusCode::InvalidArgument, "bad spec not InvalidArgument", described);
    return 0;
  }
  if (!checked) {
    require(st.code() == checked.code(), "status differs from check_points()", st.message());
    return 0;
  }
  if (st.code() == StatusCode::Unsupported) return 0;  // a documented size cap
  require(st.is_ok(), "valid input refused", st.message());
  constrict_fuzz::no_throw("checks", [&] {
    check_graph(p, spec, g);
    check_oracle(p, spec, g);
  });
  return 0;
}
