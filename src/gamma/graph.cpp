// SPDX-License-Identifier: GPL-3.0-or-later
// The γ-neighborhood graph family: parameters, membership (cap form, spec §1.3 and the
// magnitude-ordered interval reading, spec §2.2) and construction (spec §4.2, §4.3).
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <string>

#include "constrict/gamma_graph.hpp"
#include "gamma/detail/extra_faces.hpp"

namespace constrict {
namespace {

bool in_range(double v, double lo, double hi) { return lo <= v && v <= hi; }

std::string fmt(double v) {  // shortest decimal that round-trips
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// Parses a whole string as a finite double.
bool parse_double(std::string_view text, double& v) {
  if (text.empty()) return false;
  std::string s(text);
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(v);
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

GraphSpec GraphSpec::fixed(double g0_, double g1_) {
  GraphSpec s;
  s.kind = Kind::Fixed;
  s.g0 = g0_;
  s.g1 = g1_;
  return s;
}

GraphSpec GraphSpec::interval(double a0_, double a1_, double b0_, double b1_) {
  GraphSpec s;
  s.kind = Kind::Interval;
  s.a0 = a0_;
  s.a1 = a1_;
  s.b0 = b0_;
  s.b1 = b1_;
  return s;
}

Status GraphSpec::from_preset(std::string_view preset, GraphSpec& out) {
  const auto eq = preset.find('=');
  const std::string_view name = preset.substr(0, eq);
  const std::string_view arg = eq == std::string_view::npos ? std::string_view{} : preset.substr(eq + 1);
  const bool has_arg = eq != std::string_view::npos;
  auto no_arg = [&](GraphSpec s) -> Status {
    if (has_arg) return {StatusCode::InvalidArgument, "preset '" + std::string(name) + "' takes no value"};
    out = s;
    return Status::ok();
  };
  if (name == "hull") return no_arg(fixed(-1, 1));
  if (name == "delaunay") return no_arg(interval(-1, 1, 0, 1));
  if (name == "gabriel") return no_arg(fixed(0, 0));
  if (name == "complete") return no_arg(fixed(-1, -1));
  if (name == "void") return no_arg(fixed(1, 1));
  if (name == "beta-circle" || name == "beta-lune") {
    double beta = 0;
    if (!has_arg || !parse_double(arg, beta))
      return {StatusCode::InvalidArgument, "preset '" + std::string(name) + "' needs a number, e.g. " +
                                               std::string(name) + (name == "beta-circle" ? "=1.5" : "=0.8")};
    if (name == "beta-circle") {
      if (!(beta >= 1))
        return {StatusCode::InvalidArgument, "beta-circle needs beta >= 1 (got " + fmt(beta) + "); use beta-lune for beta <= 1"};
      const double g = 1.0 - 1.0 / beta;  // circle radius r/(1-g) = beta r (spec §1.5)
      out = fixed(g, g);
      return Status::ok();
    }
    if (!(beta > 0 && beta <= 1))
      return {StatusCode::InvalidArgument, "beta-lune needs 0 < beta <= 1 (got " + fmt(beta) + "); use beta-circle for beta >= 1"};
    const double g = beta - 1.0;  // lens of two circles of radius r/beta (spec §1.5)
    out = fixed(g, g);
    return Status::ok();
  }
  return {StatusCode::InvalidArgument,
          "unknown preset '" + std::string(preset) +
              "' (known: hull, delaunay, gabriel, beta-circle=B, beta-lune=B, complete, void)"};
}

Status GraphSpec::validate() const {
  auto bad = [](double v) { return !(std::isfinite(v) && v >= -1 && v <= 1); };
  if (kind == Kind::Fixed) {
    if (bad(g0) || bad(g1))
      return {StatusCode::InvalidArgument, "gamma parameters must lie in [-1,1], got (" + fmt(g0) + "," + fmt(g1) + ")"};
    return Status::ok();
  }
  if (bad(a0) || bad(a1) || bad(b0) || bad(b1))
    return {StatusCode::InvalidArgument, "interval bounds must lie in [-1,1], got [" + fmt(a0) + "," + fmt(a1) +
                                             "],[" + fmt(b0) + "," + fmt(b1) + "]"};
  if (a0 > a1 || b0 > b1)
    return {StatusCode::InvalidArgument, "empty interval: [" + fmt(a0) + "," + fmt(a1) + "],[" + fmt(b0) + "," +
                                             fmt(b1) + "] (lower bound above upper bound)"};
  return Status::ok();
}

std::string GraphSpec::describe() const {
  if (kind == Kind::Fixed) return "gamma(" + fmt(g0) + "," + fmt(g1) + ")";
  return "gamma([" + fmt(a0) + "," + fmt(a1) + "],[" + fmt(b0) + "," + fmt(b1) + "])";
}

bool GraphSpec::delaunay_subgraph() const noexcept {
  // Fixed: members satisfy γ_s >= g0, γ_-s >= g1, so γ+ + γ- >= g0 + g1 >= 0, i.e. Δ >= 0.
  // Interval: the larger-magnitude value b* >= b0 >= 0, so Δ >= 0.
  return kind == Kind::Fixed ? (g0 + g1 >= 0) : (b0 >= 0);
}

double GraphSpec::min_side_value() const noexcept {
  if (kind == Kind::Fixed) return g0 + g1 >= 0 ? 0.0 : std::min(g0, g1);
  return b0 >= 0 ? 0.0 : b0;
}

bool in_graph(const GraphSpec& spec, double ga, double gb, bool blocked) noexcept {
  if (blocked) return false;
  if (spec.kind == GraphSpec::Kind::Fixed)
    return (spec.g0 <= ga && spec.g1 <= gb) || (spec.g0 <= gb && spec.g1 <= ga);
  const double ma = std::fabs(ga), mb = std::fabs(gb);
  return (ma <= mb && in_range(ga, spec.a0, spec.a1) && in_range(gb, spec.b0, spec.b1)) ||
         (mb <= ma && in_range(gb, spec.a0, spec.a1) && in_range(ga, spec.b0, spec.b1));
}

namespace {

void append_members(const GammaFaces& from, const GraphSpec& spec, GammaFaces& to) {
  for (std::size_t f = 0; f < from.size(); ++f)
    if (in_graph(spec, from.gamma_a[f], from.gamma_b[f], (from.flags[f] & kFaceBlocked) != 0))
      to.push_back(&from.vertices[f * static_cast<std::size_t>(from.dim)], from.gamma_a[f], from.gamma_b[f], from.flags[f]);
}

void sort_faces(GammaFaces& g) {
  const std::size_t n = g.size(), d = static_cast<std::size_t>(g.dim);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return std::lexicographical_compare(&g.vertices[x * d], &g.vertices[x * d] + d, &g.vertices[y * d],
                                        &g.vertices[y * d] + d);
  });
  GammaFaces s;
  s.dim = g.dim;
  s.reserve(n);
  for (std::size_t i : order) s.push_back(&g.vertices[i * d], g.gamma_a[i], g.gamma_b[i], g.flags[i]);
  g = std::move(s);
}

}  // namespace

Status build_gamma_graph(const PointSet& points, const GraphSpec& spec, GammaFaces& out, GraphStats* stats) {
  if (Status s = spec.validate(); !s) return s;
  if (Status s = check_points(points); !s) return s;
  // Far from 1 in magnitude the γ magnitudes, balls and k-d tree radii under- or overflow: work
  // on an exact power-of-two rescaling when there is one (it changes no predicate, and every
  // double computed from it is the input's up to the power of two: the same faces and side
  // values). Otherwise the input's own coordinates; the lens search then copes (linear scans).
  PointSet scaled_copy;
  const PointSet* use = &points;
  bool far_from_one = false;  // far from 1 and no exact rescaling: only the Delaunay part is safe
  if (const int e = max_coordinate_exponent(points); e > kRescaleExponent || e < -kRescaleExponent) {
    int applied = 0;
    if (exact_power_of_two_scale(points, scaled_copy, applied).is_ok()) use = &scaled_copy;
    else far_from_one = true;
  }
  // The lens search (γ0 < 0) on such input falls back to exact scans whose numbers carry the whole
  // exponent span: seconds for a few dozen points (fuzz_gamma_graph, 34 points from 1e-317 to
  // 1e305: 3.5 s). Refused, as reconstruct3 refuses it (docs/gamma-lens-graphs.md).
  if (far_from_one && !spec.delaunay_subgraph())
    return {StatusCode::Unsupported,
            "graphs with gamma0 < 0: the coordinates span too many orders of magnitude for an exact "
            "power-of-two rescaling (some would underflow); rescale or split the input"};
  const PointSet& pts = *use;
  GraphStats st;
  const auto t0 = std::chrono::steady_clock::now();
  GammaFaces all;
  if (points.dim == 2) {
    DelaunayGamma2 dg;
    if (Status s = delaunay_gamma2(pts, dg); !s) return s;
    all = std::move(dg.faces);
  } else {
    DelaunayGamma3 dg;
    if (Status s = delaunay_gamma3(pts, dg); !s) return s;
    all = std::move(dg.faces);
  }
  st.ms_gamma = ms_since(t0);
  st.delaunay_faces = all.size();
  out.clear();
  out.dim = points.dim;
  append_members(all, spec, out);
  if (!spec.delaunay_subgraph()) {
    const auto t1 = std::chrono::steady_clock::now();
    GammaFaces extra;
    extra.dim = points.dim;
    if (Status s = detail::lens_faces(pts, spec.min_side_value(), all, extra, &st.extra_candidates); !s) return s;
    append_members(extra, spec, out);
    st.ms_extra = ms_since(t1);
  }
  sort_faces(out);
  st.faces = out.size();
  if (stats) *stats = st;
  return Status::ok();
}

}  // namespace constrict
