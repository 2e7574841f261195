// SPDX-License-Identifier: GPL-3.0-or-later
// Property tests of the γ-neighborhood graph against independent oracles (spec
// ../shared/spec/gamma-graph.md §1.3-§1.5, §2.2, §4.1; STYLE.md "Tests" 3-5, 6):
//   (1) delaunay_gamma2/3 = γ([-1,1],[0,1]) decided exactly (pencil-of-spheres argmin with
//       in-circle/in-sphere), side values = brute force;
//   (2) build_gamma_graph = brute force filtered with in_graph, for fixed and interval graphs;
//   (3) in_graph = the paper's literal two-ball rule (both mirror placements);
//   (4) presets reproduce hull, Delaunay, Gabriel, β-skeletons, complete, void;
//   (5) permutation / rotation / translation / scaling invariance;
//   (6) bit-identical repeated runs.
// Every random input is derived from a printed seed (SCOPED_TRACE) and is reproducible.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "constrict/delaunay.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/points.hpp"
#include "constrict/predicates.hpp"

namespace constrict {
namespace {

using Key = std::array<int, 3>;  // face ids ascending; the third is -1 in 2D

constexpr double kValueTol = 1e-9;  // side values of the same face from two code paths
constexpr double kMargin = 1e-9;    // distance to a threshold below which a decision is skipped
constexpr int kShownPerKind = 2;    // failures printed per test and kind; the rest is counted

// ---- reporting ---------------------------------------------------------------------------------

// Caps the failures a test prints per kind (the kind names the function and the graph), so one
// broken function does not hide the others or flood the log; the counts are reported at the end.
class Budget {
 public:
  Budget() = default;
  Budget(const Budget&) = delete;
  Budget& operator=(const Budget&) = delete;
  ~Budget() {
    for (const auto& [kind, c] : counts_)
      if (c.total > kShownPerKind)
        ADD_FAILURE() << "[" << kind << "] failed on " << c.total << " inputs in all (" << c.total - kShownPerKind
                      << " not printed)";
  }
  void fail(const std::string& kind, const std::string& msg) {
    if (++counts_[kind].total <= kShownPerKind) ADD_FAILURE() << "[" << kind << "]\n  " << msg;
  }

 private:
  struct Count {
    int total = 0;
  };
  std::map<std::string, Count> counts_;
};

// Collects the mismatching faces of one check and emits one failure with a few examples.
class Mismatches {
 public:
  explicit Mismatches(std::string what) : what_(std::move(what)) {}
  void add(const std::string& example) {
    ++count_;
    if (examples_.size() < 4) examples_.push_back(example);
  }
  // @p tag is appended to the kind (e.g. the graph).
  void flush(Budget& budget, const std::string& context, const std::string& tag = "") {
    if (count_ == 0) return;
    std::ostringstream o;
    o << context << "\n  " << count_ << " faces, e.g.";
    for (const std::string& e : examples_) o << "\n    " << e;
    budget.fail(what_ + tag, o.str());
    count_ = 0;
    examples_.clear();
  }
  std::size_t count() const { return count_; }

 private:
  std::string what_;
  std::size_t count_ = 0;
  std::vector<std::string> examples_;
};

std::string num(double v) {
  std::ostringstream o;
  o.precision(17);
  o << v;
  return o.str();
}

Key face_key(const GammaFaces& g, std::size_t f) {
  Key k{-1, -1, -1};
  for (int j = 0; j < g.dim; ++j) k[static_cast<std::size_t>(j)] = g.vertex(f, j);
  return k;
}

std::string key_str(const Key& k) {
  std::string s = "(" + std::to_string(k[0]) + "," + std::to_string(k[1]);
  if (k[2] >= 0) s += "," + std::to_string(k[2]);
  return s + ")";
}

std::string face_str(const GammaFaces& g, std::size_t f) {
  return key_str(face_key(g, f)) + " ga=" + num(g.gamma_a[f]) + " gb=" + num(g.gamma_b[f]) +
         " delta=" + num(g.delta[f]) + " flags=" + std::to_string(g.flags[f]);
}

std::string points_str(const PointSet& p) {
  std::ostringstream o;
  o.precision(17);
  o << "dim " << p.dim << " [";
  for (std::size_t i = 0; i < p.size(); ++i) {
    o << (i ? ", (" : "(");
    for (int j = 0; j < p.dim; ++j) o << (j ? "," : "") << p[i][j];
    o << ")";
  }
  return o.str() + "]";
}

bool values_close(double x, double y) {
  return std::fabs(x - y) <= kValueTol * (1.0 + std::max(std::fabs(x), std::fabs(y)));
}

int sign_of(double v) { return (v > 0) - (v < 0); }

std::string lens_note(const GraphSpec& spec) {
  return spec.delaunay_subgraph() ? std::string()
                                  : std::string(" [non-Delaunay graph: built by detail::lens_faces]");
}

std::map<Key, std::size_t> index_faces(const GammaFaces& g) {
  std::map<Key, std::size_t> m;
  for (std::size_t f = 0; f < g.size(); ++f) m.emplace(face_key(g, f), f);
  return m;
}

// ---- reproducible random inputs ----------------------------------------------------------------

// mt19937_64 raw output is fully specified by the standard; the conversions below are ours, so the
// inputs are the same with every standard library.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : eng_(seed * 0x9E3779B97F4A7C15ull + 0x5DEECE66Dull) {}
  double uniform01() { return static_cast<double>(eng_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  int integer(int lo, int hi) {
    return lo + static_cast<int>(eng_() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  double normal() {
    const double u = 1.0 - uniform01(), v = uniform01();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
  }
  template <class T>
  void shuffle(std::vector<T>& v) {
    for (std::size_t i = v.size(); i > 1; --i)
      std::swap(v[i - 1], v[static_cast<std::size_t>(integer(0, static_cast<int>(i) - 1))]);
  }

 private:
  std::mt19937_64 eng_;
};

// Coordinates on a 2^-24 grid: general position in practice, and translations by +-1024 and
// scalings by powers of two stay exact.
double quantize(double x) { return std::ldexp(std::round(std::ldexp(x, 24)), -24); }

enum class Dist { Uniform = 0, Grid = 1, Sphere = 2, Cluster = 3 };

const char* dist_name(Dist d) {
  switch (d) {
    case Dist::Uniform: return "uniform";
    case Dist::Grid: return "integer-grid";
    case Dist::Sphere: return "lattice-circle/sphere";
    case Dist::Cluster: return "clustered";
  }
  return "?";
}

// Keeps the first occurrence of every point, in input order.
PointSet dedupe(const PointSet& p) {
  PointSet out;
  out.dim = p.dim;
  std::set<std::vector<double>> seen;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::vector<double> c(p[i], p[i] + p.dim);
    if (seen.insert(c).second) out.coords.insert(out.coords.end(), c.begin(), c.end());
  }
  return out;
}

// Not all collinear (2D) / not all coplanar (3D), exact.
bool full_dimensional(const PointSet& p) {
  const std::size_t n = p.size();
  if (n < static_cast<std::size_t>(p.dim) + 1) return false;
  if (p.dim == 2) {
    for (std::size_t k = 2; k < n; ++k)
      if (orient2(p[0], p[1], p[k]) != 0) return true;
    return false;
  }
  std::size_t c = 2;
  while (c < n && collinear3(p[0], p[1], p[c])) ++c;
  if (c == n) return false;
  for (std::size_t k = 2; k < n; ++k)
    if (orient3(p[0], p[1], p[c], p[k]) != 0) return true;
  return false;
}

// Integer points with |x|^2 = r2 (exactly co-circular / co-spherical).
std::vector<std::array<int, 3>> lattice_sphere(int dim, int r2) {
  std::vector<std::array<int, 3>> out;
  const int r = static_cast<int>(std::lround(std::sqrt(static_cast<double>(r2))));
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y) {
      if (dim == 2) {
        if (x * x + y * y == r2) out.push_back({x, y, 0});
        continue;
      }
      for (int z = -r; z <= r; ++z)
        if (x * x + y * y + z * z == r2) out.push_back({x, y, z});
    }
  return out;
}

struct Input {
  PointSet points;
  Dist dist = Dist::Uniform;
  std::string trace;   // seed, distribution, size (SCOPED_TRACE)
  std::string detail;  // trace plus the coordinates (failure messages)
  bool usable = false;  // enough points, full-dimensional
  bool general = false; // drawn from a continuous distribution (general position w.p. 1)
};

// The input of seed @p seed: distribution seed % 4, N uniform in [n_min, n_max] before duplicate
// removal.
Input make_input(int dim, std::uint64_t seed, int n_min, int n_max) {
  Rng rng(seed * 4 + static_cast<std::uint64_t>(dim));
  Input in;
  in.dist = static_cast<Dist>(seed % 4);
  in.general = in.dist == Dist::Uniform || in.dist == Dist::Cluster;
  const int n = rng.integer(n_min, n_max);
  PointSet p;
  p.dim = dim;
  auto push = [&](const double* c) { p.coords.insert(p.coords.end(), c, c + dim); };
  switch (in.dist) {
    case Dist::Uniform:
      for (int i = 0; i < n; ++i) {
        double c[3];
        for (int j = 0; j < dim; ++j) c[j] = quantize(rng.uniform(-1, 1));
        push(c);
      }
      break;
    case Dist::Grid: {
      // Small grids: many collinear, co-circular and (3D) coplanar / co-spherical subsets.
      const int g = dim == 2 ? rng.integer(2, 8) : rng.integer(1, 3);
      for (int i = 0; i < n; ++i) {
        double c[3];
        for (int j = 0; j < dim; ++j) c[j] = rng.integer(0, g);
        push(c);
      }
      break;
    }
    case Dist::Sphere: {
      static const int r2_2d[] = {25, 625, 4225};
      static const int r2_3d[] = {9, 25, 50, 81};
      const int r2 = dim == 2 ? r2_2d[rng.integer(0, 2)] : r2_3d[rng.integer(0, 3)];
      std::vector<std::array<int, 3>> s = lattice_sphere(dim, r2);
      rng.shuffle(s);
      const std::size_t take = std::min(s.size(), static_cast<std::size_t>(n));
      for (std::size_t i = 0; i < take; ++i) {
        const double c[3] = {static_cast<double>(s[i][0]), static_cast<double>(s[i][1]), static_cast<double>(s[i][2])};
        push(c);
      }
      if (rng.integer(0, 1) == 1) {  // a few points off the circle/sphere
        const int r = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(r2))));
        const int extra = rng.integer(1, 3);
        for (int i = 0; i < extra; ++i) {
          double c[3];
          for (int j = 0; j < dim; ++j) c[j] = rng.integer(-r - 1, r + 1);
          push(c);
        }
      }
      break;
    }
    case Dist::Cluster: {
      const int k = rng.integer(1, 4);
      std::vector<std::array<double, 3>> centres(static_cast<std::size_t>(k));
      for (auto& c : centres)
        for (int j = 0; j < dim; ++j) c[static_cast<std::size_t>(j)] = rng.uniform(-1, 1);
      for (int i = 0; i < n; ++i) {
        const auto& c = centres[static_cast<std::size_t>(rng.integer(0, k - 1))];
        double x[3];
        for (int j = 0; j < dim; ++j) x[j] = quantize(c[static_cast<std::size_t>(j)] + 0.03 * rng.normal());
        push(x);
      }
      break;
    }
  }
  in.points = dedupe(p);
  in.usable = full_dimensional(in.points);
  in.trace = "seed " + std::to_string(seed) + " dim " + std::to_string(dim) + " dist " + dist_name(in.dist) +
             " n " + std::to_string(in.points.size());
  in.detail = in.trace + " points " + points_str(in.points);
  return in;
}

// ---- exact oracle for γ([-1,1],[0,1]) ------------------------------------------------------------

const double* pt(const PointSet& p, int i) { return p[static_cast<std::size_t>(i)]; }

// Collinear x strictly inside the segment ab (exact: coordinate comparisons only).
bool in_open_segment(const double* a, const double* b, const double* x, int dim) {
  for (int j = 0; j < dim; ++j)
    if (x[j] < std::min(a[j], b[j]) || x[j] > std::max(a[j], b[j])) return false;
  return !std::equal(x, x + dim, a) && !std::equal(x, x + dim, b);
}

int side_of(const PointSet& p, const int* ids, int x) {
  return p.dim == 2 ? orient2(pt(p, ids[0]), pt(p, ids[1]), pt(p, x))
                    : orient3(pt(p, ids[0]), pt(p, ids[1]), pt(p, ids[2]), pt(p, x));
}

// Points on one side of the face ordered by t (spec §1.1): q comes first iff q lies strictly
// inside the sphere through the face and `through`.
bool before_in_pencil(const PointSet& p, const int* ids, int through, int q) {
  if (p.dim == 2) return in_circle(pt(p, ids[0]), pt(p, ids[1]), pt(p, through), pt(p, q)) > 0;
  return in_sphere(pt(p, ids[0]), pt(p, ids[1]), pt(p, ids[2]), pt(p, through), pt(p, q)) > 0;
}

struct ExactFace {
  bool blocked = false;
  bool member = false;  // σ ∈ γ([-1,1],[0,1]): some empty open ball has σ on its boundary
};

// Spec §2.2: member ⇔ not blocked and T+ + T− >= 0 ⇔ the first point q* of the negative side is
// not strictly inside the sphere through σ and the first point p* of the positive side.
ExactFace exact_delaunay_face(const PointSet& p, const int* ids) {
  ExactFace r;
  int first[2] = {-1, -1};
  const int n = static_cast<int>(p.size());
  for (int x = 0; x < n; ++x) {
    if (std::find(ids, ids + p.dim, x) != ids + p.dim) continue;
    const int o = side_of(p, ids, x);
    if (o == 0) {
      const bool in_d = p.dim == 2 ? in_open_segment(pt(p, ids[0]), pt(p, ids[1]), pt(p, x), 2)
                                   : in_circle_coplanar3(pt(p, ids[0]), pt(p, ids[1]), pt(p, ids[2]), pt(p, x)) > 0;
      r.blocked = r.blocked || in_d;
      continue;
    }
    int& f = first[o > 0 ? 0 : 1];
    if (f < 0 || before_in_pencil(p, ids, f, x)) f = x;
  }
  if (r.blocked) return r;
  r.member = first[0] < 0 || first[1] < 0 || !before_in_pencil(p, ids, first[0], first[1]);
  return r;
}

// ---- membership robust to tiny value differences -------------------------------------------------

double nudge(double v, double d, bool keep_sign) {
  if (v == 1.0) return v;  // an empty side is exact
  if (!keep_sign) return std::clamp(v + d, -1.0, std::nextafter(1.0, 0.0));
  if (v == 0.0) return v;  // signs come from exact predicates
  const double m = std::clamp(std::fabs(v) + d, 1e-300, std::nextafter(1.0, 0.0));
  return v > 0 ? m : -m;
}

// Membership of a face with side values (ga, gb); @p decided is false when moving the values by
// kMargin (keeping their exact signs if @p keep_sign) changes the answer.
bool robust_member(const GraphSpec& spec, double ga, double gb, bool blocked, bool keep_sign, bool& decided) {
  const bool m = in_graph(spec, ga, gb, blocked);
  decided = true;
  for (const double da : {-kMargin, kMargin})
    for (const double db : {-kMargin, 0.0, kMargin})
      if (in_graph(spec, nudge(ga, da, keep_sign), nudge(gb, db, keep_sign), blocked) != m) decided = false;
  for (const double db : {-kMargin, kMargin})
    if (in_graph(spec, ga, nudge(gb, db, keep_sign), blocked) != m) decided = false;
  return m;
}

// The graphs of check (2): fixed pairs incl. 0, ±1, equal, opposite and mixed signs, and intervals.
std::vector<GraphSpec> oracle_specs() {
  std::vector<GraphSpec> s;
  const double pairs[][2] = {{0, 0},     {0.3, 0.3},   {-0.3, -0.3}, {0.5, -0.5}, {-0.5, 0.5},   {-1, 1},
                             {1, -1},    {1, 1},       {-1, -1},     {0, 0.6},    {0.6, 0},      {-0.2, 0.7},
                             {0.7, -0.2}, {-0.05, -0.05}, {0.2, -0.1}, {-0.7, -0.1}};
  for (const auto& g : pairs) s.push_back(GraphSpec::fixed(g[0], g[1]));
  const double iv[][4] = {{-1, 1, 0, 1},  {-1, 1, 0.3, 1},  {0, 1, 0, 1},          {-1, 0, 0, 1},
                          {-1, 1, -0.2, 1}, {-1, 1, -1, 0}, {-0.5, 0.5, -0.6, 0.9}};
  for (const auto& v : iv) s.push_back(GraphSpec::interval(v[0], v[1], v[2], v[3]));
  return s;
}

GammaFaces brute(const PointSet& p) {
  GammaFaces bf;
  const Status s = brute_force_gamma_faces(p, bf);
  EXPECT_TRUE(s.is_ok()) << s.message();
  return bf;
}

// ---- (1) delaunay_gamma2/3 against the exact oracle and the brute force -----------------------------

// Which findings of check_delaunay_faces() a test reports.
enum Part : unsigned {
  kCore = 1,         // face set, values, signs, Δ, blocked flags
  kHullFlag = 2,     // kFaceHull of delaunay_gamma = "one side empty"
  kBruteDelta = 4,   // the brute force's Δ decides γ([-1,1],[0,1]) exactly
};

void check_delaunay_faces(const Input& in, unsigned parts, Budget& budget) {
  const PointSet& p = in.points;
  const GammaFaces bf = brute(p);
  GammaFaces dt;
  Status s;
  if (p.dim == 2) {
    DelaunayGamma2 dg;
    s = delaunay_gamma2(p, dg);
    dt = std::move(dg.faces);
  } else {
    DelaunayGamma3 dg;
    s = delaunay_gamma3(p, dg);
    dt = std::move(dg.faces);
  }
  if (!s.is_ok()) {
    budget.fail("delaunay_gamma failed", in.detail + ": " + s.message());
    return;
  }
  const std::map<Key, std::size_t> dt_index = index_faces(dt);
  Mismatches dup("delaunay_gamma: duplicate faces");
  if (dt_index.size() != dt.size()) dup.add(std::to_string(dt.size() - dt_index.size()) + " duplicates");
  Mismatches missing("face of γ([-1,1],[0,1]) (exact oracle) missing from delaunay_gamma");
  Mismatches extra("face in delaunay_gamma that is not in γ([-1,1],[0,1]) (exact oracle)");
  Mismatches values("side values of delaunay_gamma differ from the brute force by more than 1e-9");
  Mismatches signs("signs of side values differ between delaunay_gamma and the brute force");
  Mismatches delta("delaunay_gamma: delta != filtration_value(ga, gb)");
  Mismatches hull(
      "delaunay_gamma: kFaceHull flag != (one side empty), unlike brute_force_gamma_faces and the header "
      "('convex hull facet (one side empty)'); co-spherical completion faces on a coplanar hull facet get "
      "only kFaceCospherical");
  Mismatches bf_blocked("brute_force_gamma_faces: blocked flag differs from the exact test");
  Mismatches bf_member(
      "brute_force_gamma_faces: {not blocked, Δ >= 0} differs from γ([-1,1],[0,1]) decided exactly "
      "(Δ picks the wrong side value when |γ+| = |γ−| only up to rounding, i.e. co-circular/co-spherical apexes)");
  std::size_t matched = 0;
  for (std::size_t f = 0; f < bf.size(); ++f) {
    const Key k = face_key(bf, f);
    const ExactFace ex = exact_delaunay_face(p, k.data());
    const bool blocked = (bf.flags[f] & kFaceBlocked) != 0;
    if (blocked != ex.blocked) bf_blocked.add(face_str(bf, f) + " exact blocked=" + std::to_string(ex.blocked));
    if ((!blocked && bf.delta[f] >= 0) != ex.member)
      bf_member.add(face_str(bf, f) + " exact member=" + std::to_string(ex.member));
    const auto it = dt_index.find(k);
    const bool in_dt = it != dt_index.end();
    if (in_dt != ex.member) (in_dt ? extra : missing).add("brute force " + face_str(bf, f) + (in_dt ? " dt " + face_str(dt, it->second) : ""));
    if (!in_dt) continue;
    ++matched;
    const std::size_t d = it->second;
    if (!values_close(dt.gamma_a[d], bf.gamma_a[f]) || !values_close(dt.gamma_b[d], bf.gamma_b[f]))
      values.add("dt " + face_str(dt, d) + " | brute force " + face_str(bf, f));
    if (sign_of(dt.gamma_a[d]) != sign_of(bf.gamma_a[f]) || sign_of(dt.gamma_b[d]) != sign_of(bf.gamma_b[f]))
      signs.add("dt " + face_str(dt, d) + " | brute force " + face_str(bf, f));
    if (dt.delta[d] != filtration_value(dt.gamma_a[d], dt.gamma_b[d])) delta.add(face_str(dt, d));
    if (((dt.flags[d] & kFaceHull) != 0) != (bf.gamma_a[f] == 1.0 || bf.gamma_b[f] == 1.0))
      hull.add("dt " + face_str(dt, d) + " | brute force " + face_str(bf, f));
  }
  if (matched != dt.size()) {
    const std::map<Key, std::size_t> bf_index = index_faces(bf);
    for (std::size_t d = 0; d < dt.size(); ++d)
      if (!bf_index.count(face_key(dt, d))) extra.add("not a brute-force face (collinear?): " + face_str(dt, d));
  }
  if (parts & kCore)
    for (Mismatches* m : {&dup, &missing, &extra, &values, &signs, &delta, &bf_blocked}) m->flush(budget, in.detail);
  if (parts & kHullFlag) hull.flush(budget, in.detail);
  if (parts & kBruteDelta) bf_member.flush(budget, in.detail);
}

void run_delaunay_checks(int dim, unsigned parts) {
  Budget budget;
  int used = 0;
  const std::uint64_t seeds = dim == 2 ? 200 : 100;
  for (std::uint64_t seed = 0; seed < seeds; ++seed) {
    const Input in = dim == 2 ? make_input(2, seed, 3, 60) : make_input(3, seed, 4, 25);
    if (!in.usable) continue;
    ++used;
    SCOPED_TRACE(in.trace);
    check_delaunay_faces(in, parts, budget);
  }
  EXPECT_GE(used, static_cast<int>(seeds * 85 / 100)) << "too many inputs were collinear/coplanar";
}

TEST(GammaOracle2D, DelaunayGammaEqualsExactOracle) { run_delaunay_checks(2, kCore); }
TEST(GammaOracle3D, DelaunayGammaEqualsExactOracle) { run_delaunay_checks(3, kCore); }

// The hull flag of delaunay_gamma agrees with the brute force (and with the header: "convex hull
// facet (one side empty)"), also for faces added by the co-spherical completion.
TEST(GammaOracle2D, DelaunayGammaHullFlagMeansOneSideEmpty) { run_delaunay_checks(2, kHullFlag); }
TEST(GammaOracle3D, DelaunayGammaHullFlagMeansOneSideEmpty) { run_delaunay_checks(3, kHullFlag); }

// brute_force_gamma_faces is the reference oracle: its Δ must decide γ([-1,1],[0,1]) = {Δ >= 0}
// exactly (header), including co-circular / co-spherical ties |γ+| = |γ−|.
TEST(GammaOracle2D, BruteForceDeltaDecidesDelaunayGraphExactly) { run_delaunay_checks(2, kBruteDelta); }
TEST(GammaOracle3D, BruteForceDeltaDecidesDelaunayGraphExactly) { run_delaunay_checks(3, kBruteDelta); }

// ---- (2) build_gamma_graph against the brute force filtered with in_graph ------------------------

void check_graph_specs(const Input& in, Budget& budget, std::size_t& decided_faces) {
  const PointSet& p = in.points;
  const GammaFaces bf = brute(p);
  const std::vector<GraphSpec> specs = oracle_specs();
  for (const GraphSpec& spec : specs) {
    const std::string ctx = in.detail + "\n  spec " + spec.describe() + lens_note(spec);
    GammaFaces out;
    const Status s = build_gamma_graph(p, spec, out);
    if (!s.is_ok()) {
      budget.fail("build_gamma_graph failed | " + spec.describe() + lens_note(spec), ctx + ": " + s.message());
      continue;
    }
    Mismatches order("output not strictly sorted by vertex ids (unsorted or duplicate faces)");
    Mismatches missing("member (brute force + in_graph) missing from build_gamma_graph");
    Mismatches extra("face in build_gamma_graph that is not a member (brute force + in_graph)");
    Mismatches values("side values differ from the brute force by more than 1e-9");
    Mismatches signs("signs of side values differ from the brute force");
    Mismatches delta("delta != filtration_value(ga, gb)");
    if (out.dim != p.dim) order.add("dim " + std::to_string(out.dim));
    for (std::size_t f = 1; f < out.size(); ++f)
      if (!(face_key(out, f - 1) < face_key(out, f))) order.add(face_str(out, f - 1) + " before " + face_str(out, f));
    const std::map<Key, std::size_t> out_index = index_faces(out);
    std::size_t matched = 0;
    for (std::size_t f = 0; f < bf.size(); ++f) {
      bool decided = true;
      const bool member =
          robust_member(spec, bf.gamma_a[f], bf.gamma_b[f], (bf.flags[f] & kFaceBlocked) != 0, true, decided);
      const auto it = out_index.find(face_key(bf, f));
      const bool in_out = it != out_index.end();
      if (decided) ++decided_faces;
      if (decided && member != in_out)
        (in_out ? extra : missing).add("brute force " + face_str(bf, f) + (in_out ? " out " + face_str(out, it->second) : ""));
      if (!in_out) continue;
      ++matched;
      const std::size_t d = it->second;
      if (!values_close(out.gamma_a[d], bf.gamma_a[f]) || !values_close(out.gamma_b[d], bf.gamma_b[f]))
        values.add("out " + face_str(out, d) + " | brute force " + face_str(bf, f));
      if (sign_of(out.gamma_a[d]) != sign_of(bf.gamma_a[f]) || sign_of(out.gamma_b[d]) != sign_of(bf.gamma_b[f]))
        signs.add("out " + face_str(out, d) + " | brute force " + face_str(bf, f));
      if (out.delta[d] != filtration_value(out.gamma_a[d], out.gamma_b[d])) delta.add(face_str(out, d));
    }
    if (matched != out_index.size()) {
      const std::map<Key, std::size_t> bf_index = index_faces(bf);
      for (std::size_t d = 0; d < out.size(); ++d)
        if (!bf_index.count(face_key(out, d))) extra.add("not a brute-force face: " + face_str(out, d));
    }
    for (Mismatches* m : {&order, &missing, &extra, &values, &signs, &delta})
      m->flush(budget, ctx, " | " + spec.describe() + lens_note(spec));

    // γ(g0,g1) = γ(g1,g0) (cap form, both mirror images, spec §1.3).
    if (spec.kind == GraphSpec::Kind::Fixed && spec.g0 != spec.g1) {
      GammaFaces swapped;
      const GraphSpec sw = GraphSpec::fixed(spec.g1, spec.g0);
      if (build_gamma_graph(p, sw, swapped).is_ok() && swapped.vertices != out.vertices)
        budget.fail("γ(g0,g1) != γ(g1,g0) | " + spec.describe() + lens_note(spec),
                    ctx + ": " + std::to_string(out.size()) + " vs " + std::to_string(swapped.size()) + " faces");
    }
  }
}

TEST(GammaOracle2D, BuildGammaGraphEqualsBruteForceFilter) {
  Budget budget;
  std::size_t decided = 0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const Input in = make_input(2, seed, 3, 60);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_graph_specs(in, budget, decided);
  }
  RecordProperty("faces_compared", std::to_string(decided));
  EXPECT_GT(decided, 1000000u) << "too few faces compared (most were too close to a threshold)";
}

TEST(GammaOracle3D, BuildGammaGraphEqualsBruteForceFilter) {
  Budget budget;
  std::size_t decided = 0;
  for (std::uint64_t seed = 0; seed < 100; ++seed) {
    const Input in = make_input(3, seed, 4, 25);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_graph_specs(in, budget, decided);
  }
  RecordProperty("faces_compared", std::to_string(decided));
  EXPECT_GT(decided, 500000u) << "too few faces compared (most were too close to a threshold)";
}

// Larger inputs, so that the spatial pruning of the non-Delaunay path (k-d tree, direction bins)
// works on more than a handful of points: a few inputs per distribution, including a noisy circle /
// sphere surface and a large integer grid, every graph of oracle_specs().
Input make_large_input(int dim, std::uint64_t seed) {
  Rng rng(seed + 4242);
  Input in;
  const int kind = static_cast<int>(seed % 5);
  const int n = dim == 2 ? rng.integer(150, 260) : rng.integer(40, 60);
  PointSet p;
  p.dim = dim;
  const char* name = "";
  for (int i = 0; i < n; ++i) {
    double x[3] = {0, 0, 0};
    switch (kind) {
      case 0:
        name = "uniform";
        for (int j = 0; j < dim; ++j) x[j] = quantize(rng.uniform(-1, 1));
        break;
      case 1:  // integer grid, about half the nodes occupied
        name = "integer-grid";
        for (int j = 0; j < dim; ++j) x[j] = rng.integer(0, dim == 2 ? 20 : 4);
        break;
      case 2: {  // noisy circle / sphere (a "surface sample")
        name = "noisy-surface";
        double len = 0;
        for (int j = 0; j < dim; ++j) {
          x[j] = rng.normal();
          len += x[j] * x[j];
        }
        len = std::sqrt(len);
        for (int j = 0; j < dim; ++j) x[j] = quantize(x[j] / len * (1 + 0.01 * rng.normal()));
        break;
      }
      case 3:  // clustered
        name = "clustered";
        for (int j = 0; j < dim; ++j) x[j] = quantize((i % 3) * 0.7 + 0.05 * rng.normal());
        break;
      default:  // lattice points on a circle/sphere plus interior points
        name = "lattice-circle/sphere+interior";
        if (i < n / 2) {
          static const std::vector<std::array<int, 3>> s2 = lattice_sphere(2, 4225);
          static const std::vector<std::array<int, 3>> s3 = lattice_sphere(3, 81);
          const auto& s = dim == 2 ? s2 : s3;
          const auto& q = s[static_cast<std::size_t>(rng.integer(0, static_cast<int>(s.size()) - 1))];
          for (int j = 0; j < dim; ++j) x[j] = q[static_cast<std::size_t>(j)];
        } else {
          const int r = dim == 2 ? 45 : 6;
          for (int j = 0; j < dim; ++j) x[j] = rng.integer(-r, r);
        }
        break;
    }
    p.coords.insert(p.coords.end(), x, x + dim);
  }
  in.points = dedupe(p);
  in.usable = full_dimensional(in.points);
  in.general = kind == 0 || kind == 2 || kind == 3;
  in.trace = "large seed " + std::to_string(seed) + " dim " + std::to_string(dim) + " dist " + name + " n " +
             std::to_string(in.points.size());
  in.detail = in.trace + " points " + points_str(in.points);
  return in;
}

TEST(GammaOracle2D, BuildGammaGraphEqualsBruteForceFilterOnLargerInputs) {
  Budget budget;
  std::size_t decided = 0;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    const Input in = make_large_input(2, seed);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_graph_specs(in, budget, decided);
  }
  RecordProperty("faces_compared", std::to_string(decided));
  EXPECT_GT(decided, 1000000u);
}

TEST(GammaOracle3D, BuildGammaGraphEqualsBruteForceFilterOnLargerInputs) {
  Budget budget;
  std::size_t decided = 0;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    const Input in = make_large_input(3, seed);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_graph_specs(in, budget, decided);
  }
  RecordProperty("faces_compared", std::to_string(decided));
  EXPECT_GT(decided, 1000000u);
}

// ---- (3) the paper's literal two-ball rule ---------------------------------------------------------

// Smallest sphere of the face (centre c, radius r) and the unit normal n of its positive side
// (orient > 0), computed in double.
struct Frame {
  std::array<double, 3> c{}, n{};
  double r = 0;
};

Frame frame_of(const PointSet& p, const int* ids) {
  Frame fr;
  const double* a = pt(p, ids[0]);
  const double* b = pt(p, ids[1]);
  if (p.dim == 2) {
    const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
    fr.c = {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, 0};
    fr.r = len / 2;
    fr.n = {-dy / len, dx / len, 0};  // left of a->b: orient2(a, b, x) > 0
    return fr;
  }
  const double* c = pt(p, ids[2]);
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double nn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double n2 = nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2];
  const double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
  const double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  const double w[3] = {l1 * e2[0] - l2 * e1[0], l1 * e2[1] - l2 * e1[1], l1 * e2[2] - l2 * e1[2]};
  const double o[3] = {(w[1] * nn[2] - w[2] * nn[1]) / (2 * n2), (w[2] * nn[0] - w[0] * nn[2]) / (2 * n2),
                       (w[0] * nn[1] - w[1] * nn[0]) / (2 * n2)};
  const double len = std::sqrt(n2);
  for (std::size_t j = 0; j < 3; ++j) {
    fr.c[j] = a[j] + o[j];
    fr.n[j] = nn[j] / len;  // orient3(a, b, c, x) > 0 side
  }
  fr.r = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
  return fr;
}

// Three-valued logic: 1 inside, 0 outside, -1 within kMargin of the boundary.
int in_ball(const Frame& fr, int dim, double mag, int centre_side, const double* x) {
  double h = 0;
  for (int j = 0; j < dim; ++j) h += (x[j] - fr.c[static_cast<std::size_t>(j)]) * fr.n[static_cast<std::size_t>(j)];
  if (mag >= 1) {  // infinite radius: the open half-space on the centre side (plus D, spec §1.4)
    if (std::fabs(h) <= kMargin) return -1;
    return centre_side * h > 0 ? 1 : 0;
  }
  const double big_r = fr.r / (1 - mag);
  const double tau = centre_side * fr.r * std::sqrt(1 / ((1 - mag) * (1 - mag)) - 1);
  double d2 = 0;
  for (int j = 0; j < dim; ++j) {
    const double cj = fr.c[static_cast<std::size_t>(j)] + tau * fr.n[static_cast<std::size_t>(j)];
    d2 += (x[j] - cj) * (x[j] - cj);
  }
  const double dist = std::sqrt(d2);
  if (std::fabs(dist - big_r) <= kMargin) return -1;
  return dist < big_r ? 1 : 0;
}

int or3(int x, int y) { return (x == 1 || y == 1) ? 1 : (x == 0 && y == 0 ? 0 : -1); }
int and3(int x, int y) { return (x == 0 || y == 0) ? 0 : (x == 1 && y == 1 ? 1 : -1); }

// The paper's neighborhood for |g0| <= |g1| (spec §1.3): balls of radii r/(1-|g0|), r/(1-|g1|);
// ball 1 centred on side s; ball 0 on the same side if g0*g1 < 0, on the other if > 0, on H if
// g0 = 0; union if g1 >= 0, intersection if g1 <= 0. Returns whether a point of P\σ lies in it
// (1 yes, 0 no, -1 undecided).
int literal_occupied(const PointSet& p, const int* ids, const Frame& fr, double g0, double g1, int s) {
  const int side0 = g0 == 0 ? 0 : (g0 * g1 > 0 ? -s : s);
  int result = 0;
  const int n = static_cast<int>(p.size());
  for (int x = 0; x < n; ++x) {
    if (std::find(ids, ids + p.dim, x) != ids + p.dim) continue;
    const int i0 = in_ball(fr, p.dim, std::fabs(g0), side0, pt(p, x));
    const int i1 = in_ball(fr, p.dim, std::fabs(g1), s, pt(p, x));
    const int v = g1 >= 0 ? or3(i0, i1) : and3(i0, i1);
    if (v == 1) return 1;
    if (v == -1) result = -1;
  }
  return result;
}

void check_literal(const Input& in, const std::vector<std::array<double, 2>>& pairs, Budget& budget,
                   std::size_t& checked, std::size_t& skipped) {
  const PointSet& p = in.points;
  const GammaFaces bf = brute(p);
  for (const auto& pr : pairs) {
    const double g0 = pr[0], g1 = pr[1];
    // The literal rule needs |g0| <= |g1|; the cap form accepts either order (spec §1.3).
    const double lo = std::fabs(g0) <= std::fabs(g1) ? g0 : g1;
    const double hi = std::fabs(g0) <= std::fabs(g1) ? g1 : g0;
    Mismatches mm("in_graph(fixed(" + num(g0) + "," + num(g1) + ")) disagrees with the literal two-ball rule");
    Mismatches order("in_graph(fixed(g0,g1)) != in_graph(fixed(g1,g0))");
    for (std::size_t f = 0; f < bf.size(); ++f) {
      if (bf.flags[f] & kFaceBlocked) continue;
      const Key k = face_key(bf, f);
      const Frame fr = frame_of(p, k.data());
      const int plus = literal_occupied(p, k.data(), fr, lo, hi, +1);
      const int minus = literal_occupied(p, k.data(), fr, lo, hi, -1);
      const int literal = (plus == 0 || minus == 0) ? 1 : ((plus == 1 && minus == 1) ? 0 : -1);
      const bool cap = in_graph(GraphSpec::fixed(g0, g1), bf.gamma_a[f], bf.gamma_b[f], false);
      if (cap != in_graph(GraphSpec::fixed(g1, g0), bf.gamma_a[f], bf.gamma_b[f], false)) order.add(face_str(bf, f));
      if (literal < 0) {
        ++skipped;
        continue;
      }
      ++checked;
      if (cap != (literal == 1))
        mm.add(face_str(bf, f) + " literal member=" + std::to_string(literal) + " (placement +: occupied=" +
               std::to_string(plus) + ", -: " + std::to_string(minus) + ")");
    }
    mm.flush(budget, in.detail);
    order.flush(budget, in.detail);
  }
}

std::vector<std::array<double, 2>> literal_pairs(std::uint64_t seed) {
  std::vector<std::array<double, 2>> pairs = {
      {0, 0},     {0.3, 0.3},   {-0.3, -0.3}, {0.5, -0.5},    {-0.5, 0.5}, {-1, 1},      {1, -1},
      {1, 1},     {-1, -1},     {0, 0.6},     {0.6, 0},       {-0.2, 0.7}, {0.7, -0.2},  {-0.05, -0.05},
      {0.2, -0.1}, {-0.7, -0.1}, {0, -0.4},   {-0.4, 0},      {0, 1},      {0, -1},      {1, 0.4},
      {-1, 0.4},  {0.4, -1},    {-0.4, -1}};
  Rng rng(seed + 1000003);
  for (int i = 0; i < 6; ++i) pairs.push_back({rng.uniform(-1, 1), rng.uniform(-1, 1)});
  return pairs;
}

TEST(GammaOracle2D, InGraphMatchesLiteralTwoBallRule) {
  Budget budget;
  std::size_t checked = 0, skipped = 0;
  for (std::uint64_t seed = 0; seed < 150; ++seed) {
    // Small general-position sets: uniform or clustered, N in [4, 12].
    const Input in = make_input(2, (seed / 2) * 4 + (seed % 2 ? 3 : 0), 4, 12);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_literal(in, literal_pairs(seed), budget, checked, skipped);
  }
  RecordProperty("faces_checked", std::to_string(checked));
  RecordProperty("faces_skipped", std::to_string(skipped));
  EXPECT_GT(checked, 50000u);
  EXPECT_LT(skipped, checked / 100 + 10) << "too many faces undecided by the literal oracle";
}

TEST(GammaOracle3D, InGraphMatchesLiteralTwoBallRule) {
  Budget budget;
  std::size_t checked = 0, skipped = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const Input in = make_input(3, (seed / 2) * 4 + (seed % 2 ? 3 : 0), 5, 9);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_literal(in, literal_pairs(seed), budget, checked, skipped);
  }
  RecordProperty("faces_checked", std::to_string(checked));
  RecordProperty("faces_skipped", std::to_string(skipped));
  EXPECT_GT(checked, 20000u);
  EXPECT_LT(skipped, checked / 100 + 10) << "too many faces undecided by the literal oracle";
}

// The interval reading (magnitude-ordered pair, spec §2.2) tied to the fixed graphs, which the
// literal oracle above validates: CGTA Lemma 1 γ(γ0,γ1) = γ([γ0,1],[γ1,1]) for γ1 >= 0, Lemma 2
// γ(γ0,γ1) = γ([γ0,1],[γ1,1]) ∪ γ([γ1,1],[|γ0|,1]) for γ1 <= 0 (both with |γ0| <= |γ1|), and
// γ([-1,1],[β,1]) = {Δ >= β}. in_graph is a pure function of doubles, so the identities must hold
// exactly, boundaries included; values include 0, ±1 and ties |γ+| = |γ−|.
TEST(GammaOracleSemantics, IntervalGraphsSatisfyCgtaLemmas) {
  Budget budget;
  Rng rng(99);
  const double specials[] = {0.0, 1.0, -1.0, 0.3, -0.3, 0.5, -0.5, 0.25, -0.25};
  auto value = [&]() {
    if (rng.integer(0, 3) == 0) return specials[rng.integer(0, 8)];
    return std::ldexp(std::round(std::ldexp(rng.uniform(-1, 1), 6)), -6);  // coarse: many ties
  };
  std::size_t checked = 0;
  for (int it = 0; it < 200000; ++it) {
    double ga = value(), gb = value();
    if (ga == -1.0) ga = -0.75;  // side values lie in (-1, 1]
    if (gb == -1.0) gb = 0.75;
    if (rng.integer(0, 5) == 0) gb = rng.integer(0, 1) ? -ga : ga;  // exact magnitude ties
    double g0 = value(), g1 = value();
    if (std::fabs(g0) > std::fabs(g1)) std::swap(g0, g1);
    const bool fixed = in_graph(GraphSpec::fixed(g0, g1), ga, gb, false);
    bool lemma = false;
    if (g1 >= 0) {
      lemma = in_graph(GraphSpec::interval(g0, 1, g1, 1), ga, gb, false);
    } else {
      lemma = in_graph(GraphSpec::interval(g0, 1, g1, 1), ga, gb, false) ||
              in_graph(GraphSpec::interval(g1, 1, std::fabs(g0), 1), ga, gb, false);
    }
    ++checked;
    if (fixed != lemma)
      budget.fail(g1 >= 0 ? "CGTA Lemma 1" : "CGTA Lemma 2",
                  "ga=" + num(ga) + " gb=" + num(gb) + " (g0,g1)=(" + num(g0) + "," + num(g1) +
                      ") fixed=" + std::to_string(fixed) + " intervals=" + std::to_string(lemma));
    const double beta = value();
    const bool by_delta = filtration_value(ga, gb) >= beta;
    if (in_graph(GraphSpec::interval(-1, 1, beta, 1), ga, gb, false) != by_delta)
      budget.fail("γ([-1,1],[β,1]) != {Δ >= β}", "ga=" + num(ga) + " gb=" + num(gb) + " beta=" + num(beta));
    if (in_graph(GraphSpec::fixed(g0, g1), ga, gb, true) || in_graph(GraphSpec::interval(-1, 1, -1, 1), ga, gb, true))
      budget.fail("blocked face accepted", "ga=" + num(ga) + " gb=" + num(gb));
  }
  EXPECT_EQ(checked, 200000u);
}

// ---- (4) presets reproduce the classical graphs (spec §1.5) ----------------------------------------

using EdgeSet = std::set<std::array<int, 2>>;

GraphSpec preset(const char* name) {
  GraphSpec s;
  const Status st = GraphSpec::from_preset(name, s);
  EXPECT_TRUE(st.is_ok()) << name << ": " << st.message();
  return s;
}

std::set<Key> face_set(const GammaFaces& g) {
  std::set<Key> s;
  for (std::size_t f = 0; f < g.size(); ++f) s.insert(face_key(g, f));
  return s;
}

std::set<Key> graph_faces(const PointSet& p, const GraphSpec& spec) {
  GammaFaces out;
  const Status s = build_gamma_graph(p, spec, out);
  EXPECT_TRUE(s.is_ok()) << spec.describe() << ": " << s.message();
  return face_set(out);
}

std::string diff_str(const std::set<Key>& got, const std::set<Key>& want) {
  std::ostringstream o;
  int shown = 0;
  for (const Key& k : got)
    if (!want.count(k) && shown++ < 6) o << " extra " << key_str(k);
  for (const Key& k : want)
    if (!got.count(k) && shown++ < 12) o << " missing " << key_str(k);
  return "got " + std::to_string(got.size()) + " faces, expected " + std::to_string(want.size()) + ":" + o.str();
}

void expect_faces(Budget& budget, const std::string& kind, const std::string& ctx, const std::set<Key>& got,
                  const std::set<Key>& want) {
  if (got != want) budget.fail(kind, ctx + ": " + diff_str(got, want));
}

// Hull edges by definition: all other points on one closed side and none in the open segment
// (collinear hull points are vertices, spec §1.5).
std::set<Key> hull_edges(const PointSet& p) {
  std::set<Key> s;
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      bool pos = false, neg = false, between = false;
      for (int x = 0; x < n; ++x) {
        if (x == i || x == j) continue;
        const int o = orient2(pt(p, i), pt(p, j), pt(p, x));
        pos = pos || o > 0;
        neg = neg || o < 0;
        between = between || (o == 0 && in_open_segment(pt(p, i), pt(p, j), pt(p, x), 2));
      }
      if (!(pos && neg) && !between) s.insert({i, j, -1});
    }
  return s;
}

TEST(GammaOracle2D, HullPresetIsConvexHullIncludingCollinearVertices) {
  Budget budget;
  const GraphSpec hull = preset("hull");
  for (std::uint64_t seed = 0; seed < 120; ++seed) {
    const Input in = make_input(2, seed, 3, 60);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    expect_faces(budget, "hull preset != convex hull edges", in.detail, graph_faces(in.points, hull),
                 hull_edges(in.points));
  }
  // A square with collinear points on every side: hull = the 8 consecutive boundary edges.
  PointSet sq;
  sq.dim = 2;
  sq.coords = {0, 0, 1, 0, 2, 0, 2, 1, 2, 2, 1, 2, 0, 2, 0, 1, 1, 1};
  const std::set<Key> want = {{0, 1, -1}, {1, 2, -1}, {2, 3, -1}, {3, 4, -1},
                              {4, 5, -1}, {5, 6, -1}, {6, 7, -1}, {0, 7, -1}};
  expect_faces(budget, "hull preset on a 3x3 grid", "3x3 grid", graph_faces(sq, hull), want);
}

TEST(GammaOracle2D, DelaunayPresetEqualsDelaunayTriangulation) {
  Budget budget;
  const GraphSpec del = preset("delaunay");
  for (std::uint64_t seed = 0; seed < 200; seed += 4) {  // uniform inputs only (non-degenerate)
    const Input in = make_input(2, seed, 3, 60);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    Delaunay2 dt;
    ASSERT_TRUE(build_delaunay2(in.points, dt).is_ok());
    std::set<Key> want;
    for (const auto& t : dt.triangles)
      for (std::size_t a = 0; a < 3; ++a) {
        const int u = t[a], v = t[(a + 1) % 3];
        want.insert({std::min(u, v), std::max(u, v), -1});
      }
    expect_faces(budget, "delaunay preset != build_delaunay2 edges", in.detail, graph_faces(in.points, del), want);
  }
}

std::set<Key> all_faces(int n, int dim) {
  std::set<Key> s;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (dim == 2) {
        s.insert({i, j, -1});
        continue;
      }
      for (int k = j + 1; k < n; ++k) s.insert({i, j, k});
    }
  return s;
}

PointSet points_from(int dim, const std::vector<double>& c) {
  PointSet p;
  p.dim = dim;
  p.coords = c;
  return p;
}

TEST(GammaOracle2D, DelaunayPresetConnectsAllCocircularPoints) {
  Budget budget;
  const GraphSpec del = preset("delaunay");
  // Square: both diagonals (spec §2.2).
  expect_faces(budget, "delaunay preset, square", "square", graph_faces(points_from(2, {0, 0, 1, 0, 1, 1, 0, 1}), del), all_faces(4, 2));
  // A hexagon inscribed in the circle of radius 5 (a regular hexagon has irrational coordinates
  // and is not exactly co-circular in doubles): all 15 pairs.
  expect_faces(budget, "delaunay preset, hexagon", "hexagon r=5",
               graph_faces(points_from(2, {5, 0, 3, 4, -3, 4, -5, 0, -3, -4, 3, -4}), del), all_faces(6, 2));
  // All 12 lattice points of the circle of radius 5: all 66 pairs; every pair has side values ±g.
  std::vector<double> c12;
  for (const auto& q : lattice_sphere(2, 25)) {
    c12.push_back(q[0]);
    c12.push_back(q[1]);
  }
  ASSERT_EQ(c12.size(), 24u);
  const PointSet p12 = points_from(2, c12);
  expect_faces(budget, "delaunay preset, 12 co-circular points", "12 points on a circle", graph_faces(p12, del), all_faces(12, 2));
  GammaFaces g;
  ASSERT_TRUE(build_gamma_graph(p12, del, g).is_ok());
  for (std::size_t f = 0; f < g.size(); ++f) {
    const bool hull_edge = g.gamma_a[f] == 1.0 || g.gamma_b[f] == 1.0;
    if (!hull_edge) {
      EXPECT_EQ(std::fabs(g.gamma_a[f]), std::fabs(g.gamma_b[f])) << face_str(g, f);
    }
    EXPECT_GE(g.delta[f], 0.0) << face_str(g, f);
  }
  // With the centre added only the spokes and the 12 rim edges remain.
  c12.push_back(0);
  c12.push_back(0);
  std::set<Key> fan;
  for (int i = 0; i < 12; ++i) fan.insert({i, 12, -1});
  for (const Key& k : hull_edges(points_from(2, c12))) fan.insert(k);
  expect_faces(budget, "delaunay preset, 12 co-circular points + centre", "12 points on a circle + centre", graph_faces(points_from(2, c12), del), fan);
}

TEST(GammaOracle2D, GabrielPresetMatchesAngleDefinition) {
  // Integer inputs, so (a-p).(b-p) is exact: edge ab iff no p with ∠apb > 90° (= 90° does not block).
  Budget budget;
  const GraphSpec gab = preset("gabriel");
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    if (seed % 4 != 1 && seed % 4 != 2) continue;  // grid and lattice-circle inputs
    const Input in = make_input(2, seed, 3, 60);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    const PointSet& p = in.points;
    const int n = static_cast<int>(p.size());
    std::set<Key> want;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        bool empty = true;
        for (int x = 0; x < n && empty; ++x) {
          if (x == i || x == j) continue;
          const auto ax = static_cast<long long>(pt(p, i)[0] - pt(p, x)[0]), ay = static_cast<long long>(pt(p, i)[1] - pt(p, x)[1]);
          const auto bx = static_cast<long long>(pt(p, j)[0] - pt(p, x)[0]), by = static_cast<long long>(pt(p, j)[1] - pt(p, x)[1]);
          empty = ax * bx + ay * by >= 0;
        }
        if (empty) want.insert({i, j, -1});
      }
    expect_faces(budget, "gabriel preset != angle definition", in.detail, graph_faces(p, gab), want);
  }
}

// Angle ∠apb in [0, π].
double apex_angle(const double* a, const double* b, const double* x) {
  const double ux = a[0] - x[0], uy = a[1] - x[1], vx = b[0] - x[0], vy = b[1] - x[1];
  return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy);
}

TEST(GammaOracle2D, BetaPresetsMatchAngleThresholds) {
  // γ(g,g) blocks ab iff some p has ∠apb > θ(g): θ = arcsin(1/β) (circle, β >= 1),
  // θ = π − arcsin(β) (lune, β <= 1). Edges with an angle within 1e-9 of θ are skipped.
  Budget budget;
  struct Beta {
    const char* preset;
    double theta;
  };
  const double pi = std::acos(-1.0);
  const std::vector<Beta> betas = {
      {"beta-circle=1", pi / 2},        {"beta-circle=1.25", std::asin(0.8)}, {"beta-circle=1.5", std::asin(1 / 1.5)},
      {"beta-circle=2", std::asin(0.5)}, {"beta-circle=4", std::asin(0.25)}, {"beta-lune=1", pi / 2},
      {"beta-lune=0.95", pi - std::asin(0.95)}, {"beta-lune=0.8", pi - std::asin(0.8)},
      {"beta-lune=0.5", pi - std::asin(0.5)},   {"beta-lune=0.2", pi - std::asin(0.2)}};
  std::size_t compared = 0;
  for (std::uint64_t seed = 0; seed < 120; ++seed) {
    if (seed % 4 != 0 && seed % 4 != 3) continue;  // uniform and clustered
    const Input in = make_input(2, seed, 3, 60);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    const PointSet& p = in.points;
    const int n = static_cast<int>(p.size());
    std::map<Key, double> widest_angle;  // the widest angle under which a point sees the pair
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        double w = 0;
        for (int x = 0; x < n; ++x)
          if (x != i && x != j) w = std::max(w, apex_angle(pt(p, i), pt(p, j), pt(p, x)));
        widest_angle[{i, j, -1}] = w;
      }
    for (const Beta& b : betas) {
      const GraphSpec spec = preset(b.preset);
      const std::set<Key> got = graph_faces(p, spec);
      Mismatches mm(std::string(b.preset) + " differs from the angle definition");
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
          const double widest = widest_angle[{i, j, -1}];
          if (std::fabs(widest - b.theta) <= kMargin) continue;
          ++compared;
          const bool want = widest < b.theta;
          if (want != (got.count({i, j, -1}) != 0))
            mm.add(key_str({i, j, -1}) + " widest angle " + num(widest) + " theta " + num(b.theta) +
                   (want ? " missing" : " extra"));
        }
      mm.flush(budget, in.detail, lens_note(spec));
    }
  }
  RecordProperty("edges_compared", std::to_string(compared));
  EXPECT_GT(compared, 100000u);
}

TEST(GammaOracle2D, CompleteAndVoidPresets) {
  // complete = γ(−1,−1): every pair without a point in the open segment; void = γ(1,1): empty for
  // any input that is not collinear.
  Budget budget;
  const GraphSpec complete = preset("complete");
  const GraphSpec empty = preset("void");
  for (std::uint64_t seed = 0; seed < 80; ++seed) {
    const Input in = make_input(2, seed, 3, 40);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    const PointSet& p = in.points;
    const int n = static_cast<int>(p.size());
    std::set<Key> want;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        bool free = true;
        for (int x = 0; x < n && free; ++x)
          if (x != i && x != j && orient2(pt(p, i), pt(p, j), pt(p, x)) == 0 &&
              in_open_segment(pt(p, i), pt(p, j), pt(p, x), 2))
            free = false;
        if (free) want.insert({i, j, -1});
      }
    expect_faces(budget, "complete preset != pairs with an empty open segment" + lens_note(complete), in.detail,
                 graph_faces(p, complete), want);
    expect_faces(budget, "void preset not empty", in.detail, graph_faces(p, empty), {});
  }
}

TEST(GammaOracle3D, DelaunayPresetOnCospherical) {
  Budget budget;
  const GraphSpec del = preset("delaunay");
  // The cube's 8 vertices are co-spherical: all 56 triangles.
  const PointSet cube = points_from(3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1});
  expect_faces(budget, "delaunay preset, cube", "cube", graph_faces(cube, del), all_faces(8, 3));
  // Its hull (γ(−1,1)): the 4 triangles of each square face (all on the face circle).
  std::set<Key> hull;
  for (const Key& k : all_faces(8, 3)) {
    const double* a = cube[static_cast<std::size_t>(k[0])];
    const double* b = cube[static_cast<std::size_t>(k[1])];
    const double* c = cube[static_cast<std::size_t>(k[2])];
    for (int axis = 0; axis < 3; ++axis)
      if (a[axis] == b[axis] && b[axis] == c[axis]) hull.insert(k);
  }
  ASSERT_EQ(hull.size(), 24u);
  expect_faces(budget, "hull preset, cube", "cube", graph_faces(cube, preset("hull")), hull);
  // Octahedron: all 20 triples.
  const PointSet octa = points_from(3, {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1});
  expect_faces(budget, "delaunay preset, octahedron", "octahedron", graph_faces(octa, del), all_faces(6, 3));
}

TEST(GammaOracle3D, DelaunayAndHullPresetsOnGeneralPosition) {
  Budget budget;
  const GraphSpec del = preset("delaunay");
  const GraphSpec hull = preset("hull");
  const GraphSpec empty = preset("void");
  for (std::uint64_t seed = 0; seed < 100; seed += 4) {  // uniform inputs
    const Input in = make_input(3, seed, 4, 25);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    const PointSet& p = in.points;
    Delaunay3 dt;
    ASSERT_TRUE(build_delaunay3(p, dt).is_ok());
    std::set<Key> want;
    for (const auto& t : dt.tets)
      for (std::size_t skip = 0; skip < 4; ++skip) {
        Key k{};
        std::size_t m = 0;
        for (std::size_t l = 0; l < 4; ++l)
          if (l != skip) k[m++] = t[l];
        std::sort(k.begin(), k.end());
        want.insert(k);
      }
    expect_faces(budget, "delaunay preset != build_delaunay3 faces", in.detail, graph_faces(p, del), want);
    std::set<Key> hw;
    const int n = static_cast<int>(p.size());
    for (const Key& k : all_faces(n, 3)) {
      bool pos = false, neg = false;
      for (int x = 0; x < n; ++x) {
        if (x == k[0] || x == k[1] || x == k[2]) continue;
        const int o = side_of(p, k.data(), x);
        pos = pos || o > 0;
        neg = neg || o < 0;
      }
      if (!(pos && neg)) hw.insert(k);
    }
    expect_faces(budget, "hull preset != convex hull facets", in.detail, graph_faces(p, hull), hw);
    expect_faces(budget, "void preset not empty", in.detail, graph_faces(p, empty), {});
  }
}

// ---- (5) invariance ----------------------------------------------------------------------------------

struct Transform {
  std::string name;
  int orientation;  // +1 preserves orientation, -1 mirrors
  bool exact;       // exactly representable result
  std::function<void(const double*, double*)> apply;
};

std::vector<Transform> transforms(int dim) {
  std::vector<Transform> t;
  const double ca = std::cos(0.7), sa = std::sin(0.7);
  if (dim == 2) {
    t.push_back({"rotate 90", 1, true, [](const double* x, double* y) { y[0] = -x[1]; y[1] = x[0]; }});
    t.push_back({"mirror x", -1, true, [](const double* x, double* y) { y[0] = -x[0]; y[1] = x[1]; }});
    t.push_back({"translate (1024,-512)", 1, true, [](const double* x, double* y) { y[0] = x[0] + 1024; y[1] = x[1] - 512; }});
    t.push_back({"scale 2^-3", 1, true, [](const double* x, double* y) { y[0] = x[0] * 0.125; y[1] = x[1] * 0.125; }});
    t.push_back({"scale 2^5", 1, true, [](const double* x, double* y) { y[0] = x[0] * 32; y[1] = x[1] * 32; }});
    t.push_back({"rotate 0.7 rad", 1, false, [ca, sa](const double* x, double* y) {
                   y[0] = ca * x[0] - sa * x[1];
                   y[1] = sa * x[0] + ca * x[1];
                 }});
    t.push_back({"scale 3", 1, false, [](const double* x, double* y) { y[0] = 3 * x[0]; y[1] = 3 * x[1]; }});
    return t;
  }
  t.push_back({"rotate 90 about z", 1, true, [](const double* x, double* y) { y[0] = -x[1]; y[1] = x[0]; y[2] = x[2]; }});
  t.push_back({"cycle axes", 1, true, [](const double* x, double* y) { y[0] = x[1]; y[1] = x[2]; y[2] = x[0]; }});
  t.push_back({"mirror x", -1, true, [](const double* x, double* y) { y[0] = -x[0]; y[1] = x[1]; y[2] = x[2]; }});
  t.push_back({"translate (1024,-512,2048)", 1, true,
               [](const double* x, double* y) { y[0] = x[0] + 1024; y[1] = x[1] - 512; y[2] = x[2] + 2048; }});
  t.push_back({"scale 2^-3", 1, true, [](const double* x, double* y) { for (int j = 0; j < 3; ++j) y[j] = x[j] * 0.125; }});
  t.push_back({"rotate 0.7 rad about (1,2,2)/3", 1, false, [ca, sa](const double* x, double* y) {
                 const double u[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};
                 const double d = u[0] * x[0] + u[1] * x[1] + u[2] * x[2];
                 const double c[3] = {u[1] * x[2] - u[2] * x[1], u[2] * x[0] - u[0] * x[2], u[0] * x[1] - u[1] * x[0]};
                 for (int j = 0; j < 3; ++j) y[j] = x[j] * ca + c[j] * sa + u[j] * d * (1 - ca);
               }});
  t.push_back({"scale 3", 1, false, [](const double* x, double* y) { for (int j = 0; j < 3; ++j) y[j] = 3 * x[j]; }});
  return t;
}

std::vector<GraphSpec> invariance_specs() {
  return {GraphSpec::interval(-1, 1, 0, 1), GraphSpec::fixed(0, 0),          GraphSpec::fixed(-1, 1),
          GraphSpec::fixed(0.3, 0.3),       GraphSpec::fixed(-0.5, 0.5),      GraphSpec::interval(-1, 1, 0.3, 1),
          GraphSpec::fixed(-0.3, -0.3),     GraphSpec::interval(-1, 1, -0.2, 1)};
}

// A face of a graph in original input indices with its side values oriented as in the original.
struct Mapped {
  double ga, gb;
};

// Maps the faces of @p g (computed on a transformed/permuted input whose point k is original point
// perm[k]) back to original ids; swaps the sides when the id order or the orientation flips.
std::map<Key, Mapped> map_back(const GammaFaces& g, const std::vector<int>& perm, int orientation) {
  std::map<Key, Mapped> m;
  for (std::size_t f = 0; f < g.size(); ++f) {
    Key k = face_key(g, f);
    int parity = 1;
    for (int j = 0; j < g.dim; ++j) k[static_cast<std::size_t>(j)] = perm[static_cast<std::size_t>(k[static_cast<std::size_t>(j)])];
    for (int a = 0; a < g.dim; ++a)  // bubble sort, counting transpositions
      for (int b = 0; b + 1 < g.dim - a; ++b)
        if (k[static_cast<std::size_t>(b)] > k[static_cast<std::size_t>(b + 1)]) {
          std::swap(k[static_cast<std::size_t>(b)], k[static_cast<std::size_t>(b + 1)]);
          parity = -parity;
        }
    const bool same = parity * orientation > 0;
    m[k] = same ? Mapped{g.gamma_a[f], g.gamma_b[f]} : Mapped{g.gamma_b[f], g.gamma_a[f]};
  }
  return m;
}

void compare_mapped(const PointSet& p, const GraphSpec& spec, const std::map<Key, Mapped>& base,
                    const std::map<Key, Mapped>& other, bool exact, const std::string& ctx, Budget& budget) {
  Mismatches faces(exact ? "face sets differ" : "face sets differ on faces far (> 1e-9) from every threshold");
  Mismatches values("side values differ (> 1e-9) or are not on the same side");
  auto decided = [&](const Key& k) {
    if (exact) return true;
    double ga = 0, gb = 0;
    bool blocked = false;
    side_values_scan(p, k.data(), ga, gb, blocked);
    bool d = true;
    robust_member(spec, ga, gb, blocked, false, d);
    return d;
  };
  for (const auto& [k, v] : base) {
    const auto it = other.find(k);
    if (it == other.end()) {
      if (decided(k)) faces.add("missing " + key_str(k) + " ga=" + num(v.ga) + " gb=" + num(v.gb));
      continue;
    }
    const double tol = exact ? kValueTol : 1e-7;
    if (std::fabs(v.ga - it->second.ga) > tol || std::fabs(v.gb - it->second.gb) > tol)
      values.add(key_str(k) + " (" + num(v.ga) + "," + num(v.gb) + ") vs (" + num(it->second.ga) + "," +
                 num(it->second.gb) + ")");
  }
  for (const auto& [k, v] : other)
    if (!base.count(k) && decided(k)) faces.add("extra " + key_str(k) + " ga=" + num(v.ga) + " gb=" + num(v.gb));
  const std::string tag = " | " + spec.describe() + lens_note(spec);
  faces.flush(budget, ctx, tag);
  values.flush(budget, ctx, tag);
}

void check_invariance(const Input& in, std::uint64_t seed, Budget& budget) {
  const PointSet& p = in.points;
  const std::size_t n = p.size();
  const int dim = p.dim;
  std::vector<int> identity(n);
  std::iota(identity.begin(), identity.end(), 0);
  std::vector<int> perm = identity;
  Rng rng(seed + 777);
  rng.shuffle(perm);
  PointSet permuted;
  permuted.dim = dim;
  for (std::size_t k = 0; k < n; ++k) {
    const double* x = p[static_cast<std::size_t>(perm[k])];
    permuted.coords.insert(permuted.coords.end(), x, x + dim);
  }
  const std::vector<Transform> ts = transforms(dim);
  for (const GraphSpec& spec : invariance_specs()) {
    GammaFaces base;
    const Status s = build_gamma_graph(p, spec, base);
    if (!s.is_ok()) {
      budget.fail("build_gamma_graph failed | " + spec.describe() + lens_note(spec), in.detail + ": " + s.message());
      continue;
    }
    const std::map<Key, Mapped> base_map = map_back(base, identity, 1);
    GammaFaces g;
    if (build_gamma_graph(permuted, spec, g).is_ok())
      compare_mapped(p, spec, base_map, map_back(g, perm, 1), true,
                     in.detail + "\n  " + spec.describe() + lens_note(spec) + " after a random permutation", budget);
    for (const Transform& t : ts) {
      if (!t.exact && !in.general) continue;  // generic transforms destroy exact degeneracies
      PointSet q;
      q.dim = dim;
      q.coords.resize(p.coords.size());
      for (std::size_t k = 0; k < n; ++k) t.apply(p[k], q[k]);
      if (!build_gamma_graph(q, spec, g).is_ok()) {
        budget.fail("build_gamma_graph failed | " + spec.describe() + lens_note(spec), in.detail + " after " + t.name);
        continue;
      }
      compare_mapped(p, spec, base_map, map_back(g, identity, t.orientation), t.exact,
                     in.detail + "\n  " + spec.describe() + lens_note(spec) + " after " + t.name, budget);
    }
  }
}

TEST(GammaOracle2D, InvariantUnderPermutationRotationTranslationScaling) {
  Budget budget;
  for (std::uint64_t seed = 0; seed < 80; ++seed) {
    const Input in = make_input(2, seed, 3, 60);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_invariance(in, seed, budget);
  }
}

TEST(GammaOracle3D, InvariantUnderPermutationRotationTranslationScaling) {
  Budget budget;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const Input in = make_input(3, seed, 4, 25);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_invariance(in, seed, budget);
  }
}

// ---- (6) determinism -------------------------------------------------------------------------------

template <class T>
bool same_bits(const std::vector<T>& x, const std::vector<T>& y) {
  return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(T)) == 0);
}

void check_determinism(const Input& in, Budget& budget) {
  for (const GraphSpec& spec : oracle_specs()) {
    GammaFaces first, second;
    const PointSet copy = in.points;  // fresh memory
    const Status s1 = build_gamma_graph(in.points, spec, first);
    const Status s2 = build_gamma_graph(copy, spec, second);
    if (!s1.is_ok() || !s2.is_ok()) {
      budget.fail("build_gamma_graph failed | " + spec.describe() + lens_note(spec),
                  in.detail + ": " + s1.message() + " / " + s2.message());
      continue;
    }
    if (first.dim != second.dim || !same_bits(first.vertices, second.vertices) ||
        !same_bits(first.gamma_a, second.gamma_a) || !same_bits(first.gamma_b, second.gamma_b) ||
        !same_bits(first.delta, second.delta) || !same_bits(first.flags, second.flags))
      budget.fail("two runs differ | " + spec.describe() + lens_note(spec), in.detail);
  }
}

TEST(GammaOracle2D, RepeatedRunsAreBitIdentical) {
  Budget budget;
  for (std::uint64_t seed = 0; seed < 24; ++seed) {
    const Input in = make_input(2, seed, 3, 60);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_determinism(in, budget);
  }
}

TEST(GammaOracle3D, RepeatedRunsAreBitIdentical) {
  Budget budget;
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    const Input in = make_input(3, seed, 4, 25);
    if (!in.usable) continue;
    SCOPED_TRACE(in.trace);
    check_determinism(in, budget);
  }
}

}  // namespace
}  // namespace constrict
