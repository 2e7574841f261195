// SPDX-License-Identifier: GPL-3.0-or-later
// Distances between a reconstruction and a reference (compare.hpp): deterministic grid sampling of
// one side, point-to-primitive distances to the other side through CGAL's AABB tree (in doubles),
// both directions; triangle recovery by exact vertex positions. All of compare.hpp is here, inside
// the CGAL fence (src/cgal/), because the sampling loops query the AABB trees directly. Sampling
// and its accuracy: docs/evaluation.md.
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "constrict/compare.hpp"
#include "core/detail/check_points.hpp"

namespace constrict {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;  // (the exact degeneracy test)
// The distance search in plain doubles: it measures, it decides nothing. With Epick's exact
// fallback, comparisons of nearly equal distances (a mesh 10^15 from the origin, the other at
// it) ran in rational arithmetic at every node: minutes for 300 triangles.
using KD = CGAL::Simple_cartesian<double>;
using P3 = KD::Point_3;
using Tri3 = KD::Triangle_3;
using Seg3 = KD::Segment_3;
using TriTree = CGAL::AABB_tree<CGAL::AABB_traits<KD, CGAL::AABB_triangle_primitive<KD, std::vector<Tri3>::const_iterator>>>;
using SegTree = CGAL::AABB_tree<CGAL::AABB_traits<KD, CGAL::AABB_segment_primitive<KD, std::vector<Seg3>::const_iterator>>>;

// Fixed block size: the per-element results do not depend on the thread count, and they are
// reduced serially, so the output is bit-identical on any machine with the same double arithmetic.
constexpr std::size_t kGrain = 256;
// A triangle (segment) is cut into at most kMaxGrid pieces per side, whatever the spacing.
constexpr double kMaxGrid = 1e6;
// choose_spacing() widens the spacing by kSpacingGrowth until the samples fit the budget, or the
// spacing exceeds the bounding-box diagonal (every element then has its fewest samples: more
// elements than the budget). (It stopped after 200 steps, 1.25^200 ~ 1e19, and a relative spacing
// below about 1e-19 then sampled 10^12 points per triangle: a hang.)
constexpr double kSpacingGrowth = 1.25;
// A query farther from the other side's bounding box than kFarQuery times its diagonal is measured
// to the box: within a relative 1/kFarQuery of the distance to the mesh. From far off every node of
// the search tree is at nearly the same distance, so none was pruned (a vertex 10^17 off made
// each of its samples visit every triangle).
constexpr double kFarQuery = 1048576.0;
// Triangles (segments) shorter, or (triangles) lower, than 2^-kTinyExponent of the coordinates'
// magnitude are left out of the search trees: the projections onto them underflow (a mesh 10^-100
// across beside one at 1, a sliver 10^-320 high: NaN distances). Both sides' samples still reach
// the other side; a sliver's samples are measured to its neighbours.
constexpr int kTinyExponent = 200;
// FNV-1a over the coordinates' bit patterns, plus a final mix of the high bits.
constexpr std::uint64_t kFnvOffset = 1469598103934665603ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;
constexpr int kHashMixShift = 29;

struct Side {
  double hmax = 0;   // max over samples
  long worst = -1;   // the first element (triangle, segment) where it is reached
  double mean = 0;   // measure-weighted mean
  std::size_t samples = 0;
};

// The serial reduction of the per-element results (element order, whatever the thread count):
// element maxima, integrals, measures (area or length) and sample counts.
Side reduce(const std::vector<double>& emax, const std::vector<double>& eint, const std::vector<double>& emeasure,
            const std::vector<std::size_t>& ecount) {
  Side s;
  double total = 0, integral = 0;
  for (std::size_t i = 0; i < emax.size(); ++i) {
    if (s.worst < 0 || emax[i] > s.hmax) s.worst = static_cast<long>(i);
    s.hmax = std::max(s.hmax, emax[i]);
    integral += eint[i];
    total += emeasure[i];
    s.samples += ecount[i];
  }
  s.mean = total > 0 ? integral / total : 0;
  return s;
}

// MeshDistance and CurveDistance2 report the two one-sided samplings under the same field names.
template <class Distance>
void put_sides(const Side& ab, const Side& ba, Distance& d) {
  d.hausdorff_result_to_reference = ab.hmax;
  d.hausdorff_reference_to_result = ba.hmax;
  d.hausdorff = std::max(ab.hmax, ba.hmax);
  d.worst_result_element = ab.worst;
  d.worst_reference_element = ba.worst;
  d.mean_result_to_reference = ab.mean;
  d.mean_reference_to_result = ba.mean;
  d.mean = 0.5 * (ab.mean + ba.mean);
  d.samples_result = ab.samples;
  d.samples_reference = ba.samples;
  if (d.bbox_diagonal > 0) {
    d.relative_hausdorff = d.hausdorff / d.bbox_diagonal;
    d.relative_mean = d.mean / d.bbox_diagonal;
  }
}

// The lengths of a MeshDistance or CurveDistance2 measured on coordinates times 2^-e, back to the
// input's scale (the relative values stay as measured). Near 1e308 they can pass the largest
// double: refused rather than reported as inf (a report would hold null).
template <class D>
Status scale_back(D& d, int e) {
  if (e != 0)
    for (double* x : {&d.hausdorff, &d.hausdorff_result_to_reference, &d.hausdorff_reference_to_result,
                      &d.mean_result_to_reference, &d.mean_reference_to_result, &d.mean, &d.bbox_diagonal,
                      &d.spacing_result, &d.spacing_reference})
      *x = std::ldexp(*x, e);
  for (double x : {d.hausdorff, d.mean, d.bbox_diagonal})
    if (!std::isfinite(x))
      return {StatusCode::NonFinite, "the distances exceed the largest double (coordinates near 1e308): scale both sides down"};
  return Status::ok();
}

// Built before the parallel sampling: CGAL builds the tree and the distance search structure
// lazily on the first query, which is not safe from several threads at once.
template <class Tree>
void prepare(Tree& tree) {
  tree.build();
  tree.accelerate_distance_queries();
}

bool ok_options(const DistanceOptions& o) {
  return std::isfinite(o.relative_spacing) && o.relative_spacing > 0 && o.max_samples > 0;
}

std::size_t uk(int k) { return static_cast<std::size_t>(k); }

double dist3(const double* a, const double* b) {
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return std::sqrt(x * x + y * y + z * z);
}

// ---- 3D ------------------------------------------------------------------------------------
struct Mesh {
  const PointSet& pts;
  const TriMesh3& m;
  const double* p(int i) const { return pts[static_cast<std::size_t>(i)]; }
  double longest(std::size_t t) const {
    const auto& f = m.triangles[t];
    return std::max({dist3(p(f[0]), p(f[1])), dist3(p(f[1]), p(f[2])), dist3(p(f[2]), p(f[0]))});
  }
};

std::size_t grid_k(double longest, double h) {
  if (!(longest > 0)) return 1;
  const double k = std::ceil(longest / h);
  if (!(k >= 1)) return 1;  // (NaN too: a cast of NaN to an integer is undefined)
  return static_cast<std::size_t>(std::min(k, kMaxGrid));
}

// The binary exponent of the largest magnitude added (|x| < 2^e), 0 when none is non-zero: what
// max_coordinate_exponent gives for a point set.
struct MaxExponent {
  double m = 0;
  void add(double x) { m = std::max(m, std::fabs(x)); }
  int get() const {
    int e = 0;
    if (m > 0) std::frexp(m, &e);
    return e;
  }
};

// Far from 1 in magnitude (beyond 2^±kRescaleExponent) squared lengths and cross products
// overflow or underflow: the distances are measured on both sides' coordinates times 2^-e (e the
// larger exponent of the two) and scaled back. Vertices are matched on the coordinates as given.
// 0 when no scaling is needed.
int common_exponent(const PointSet& a, const PointSet& b) {
  return rescale_exponent(std::max(max_coordinate_exponent(a), max_coordinate_exponent(b)));
}

// Spacing that honours both the wanted relative spacing and the sample budget. `longest`: the
// sampled side's longest element, at which every element has its fewest samples (the reference's
// diagonal alone is no bound: a result 10^10 times the reference's size, or with one vertex far
// off, was sampled at the reference's scale, 10^12 samples per triangle: a hang).
template <class CountAt>
double choose_spacing(double h, double diagonal, double longest, std::size_t budget, CountAt&& count_at) {
  const double bound = std::max(diagonal, longest);
  // Below longest / kMaxGrid a spacing changes nothing (the grid's cap); a spacing that rounded to
  // 0 (--spacing 5e-324) skipped this loop and sampled 5e11 points per triangle.
  h = std::max(h, longest / kMaxGrid);
  // (Among subnormals h * 1.25 can round back to h: then the next double up.)
  while (h > 0 && std::isfinite(h) && h <= bound && count_at(h) > budget)
    h = std::max(h * kSpacingGrowth, std::nextafter(h, std::numeric_limits<double>::infinity()));
  return h;
}

// The area, with the edge vectors scaled to their largest coordinate first: the cross product's
// squares underflow for triangles near 1e-100 and overflow near 1e100 (a triangle 1e-100 across
// measured 0 and was taken for a degenerate one).
double area3(const double* a, const double* b, const double* c) {
  double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double m = std::max({std::fabs(ux), std::fabs(uy), std::fabs(uz), std::fabs(vx), std::fabs(vy), std::fabs(vz)});
  if (!(m > 0) || !std::isfinite(m)) return 0;
  ux /= m, uy /= m, uz /= m, vx /= m, vy /= m, vz /= m;
  const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  return 0.5 * m * (m * std::sqrt(nx * nx + ny * ny + nz * nz));
}

// Not on one line (exactly): a triangle with an area, at any scale.
bool proper3(const double* a, const double* b, const double* c) {
  return !CGAL::collinear(K::Point_3(a[0], a[1], a[2]), K::Point_3(b[0], b[1], b[2]), K::Point_3(c[0], c[1], c[2]));
}

// The distance from q to the tree's primitives, or to their bounding box when q is far from it
// (kFarQuery).
struct Distance {
  template <class Tree>
  explicit Distance(const Tree& tree) {
    const auto box = tree.bbox();
    lo = {box.xmin(), box.ymin(), box.zmin()};
    hi = {box.xmax(), box.ymax(), box.zmax()};
    far = kFarQuery * dist3(lo.data(), hi.data());
  }
  template <class Tree>
  double operator()(const Tree& tree, const P3& q) const {
    double d2 = 0;
    const double c[3] = {q.x(), q.y(), q.z()};
    for (int k = 0; k < 3; ++k) {
      const double o = c[k] < lo[uk(k)] ? lo[uk(k)] - c[k] : c[k] > hi[uk(k)] ? c[k] - hi[uk(k)] : 0.0;
      d2 += o * o;
    }
    const double box = std::sqrt(d2);
    return box > far ? box : std::sqrt(tree.squared_distance(q));
  }
  std::array<double, 3> lo{}, hi{};
  double far = 0;
};

// Samples every triangle of `a` on a k×k grid and measures the distance to `tree`. The mean is the
// exact integral of the piecewise-linear interpolant of the node distances (node weight =
// incident sub-triangles / 3k² of the triangle's area), divided by the total area.
// Triangles flagged in `exact` are also triangles of the other mesh: their samples are at distance
// 0 (no query; exactly 0 for identical meshes instead of rounding noise).
Side sample_to_tree(const Mesh& a, const TriTree& tree, double h, const std::vector<char>& exact) {
  const std::size_t F = a.m.triangles.size();
  std::vector<double> tmax(F, 0.0), tint(F, 0.0), tarea(F, 0.0);
  std::vector<std::size_t> tcount(F, 0);
  const Distance distance(tree);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, F, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const auto& f = a.m.triangles[t];
      const double *A = a.p(f[0]), *B = a.p(f[1]), *C = a.p(f[2]);
      const double area = area3(A, B, C);
      const std::size_t k = proper3(A, B, C) ? grid_k(a.longest(t), h) : 1;
      double mx = 0, integral = 0;
      for (std::size_t i = 0; i <= k; ++i)
        for (std::size_t j = 0; i + j <= k; ++j) {
          const double s = static_cast<double>(i) / static_cast<double>(k);
          const double u = static_cast<double>(j) / static_cast<double>(k);
          const P3 q(A[0] + s * (B[0] - A[0]) + u * (C[0] - A[0]), A[1] + s * (B[1] - A[1]) + u * (C[1] - A[1]),
                     A[2] + s * (B[2] - A[2]) + u * (C[2] - A[2]));
          const double d = exact[t] ? 0.0 : distance(tree, q);
          mx = std::max(mx, d);
          // incident sub-triangles: corner 1, edge node 3, interior 6
          const bool on_i = i == 0, on_j = j == 0, on_d = i + j == k;
          const int edges = int(on_i) + int(on_j) + int(on_d);
          const int incident = edges >= 2 ? 1 : (edges == 1 ? 3 : 6);
          integral += incident * d;
        }
      tmax[t] = mx;
      tint[t] = integral * area / (3.0 * static_cast<double>(k * k));
      tarea[t] = area;
      tcount[t] = (k + 1) * (k + 2) / 2;
    }
  });
  return reduce(tmax, tint, tarea, tcount);
}

// The binary exponent of the coordinates the triangles use (MaxExponent).
int used_exponent(const Mesh& a) {
  MaxExponent e;
  for (const auto& f : a.m.triangles)
    for (int v : f)
      for (int k = 0; k < 3; ++k) e.add(a.p(v)[k]);
  return e.get();
}

double longest3(const Mesh& a) {
  double m = 0;
  for (std::size_t t = 0; t < a.m.triangles.size(); ++t) m = std::max(m, a.longest(t));
  return m;
}

std::size_t count3(const Mesh& a, double h) {
  std::size_t n = 0;
  for (std::size_t t = 0; t < a.m.triangles.size(); ++t) {
    const std::size_t k = grid_k(a.longest(t), h);
    n += (k + 1) * (k + 2) / 2;
  }
  return n;
}

Status check_mesh(const PointSet& pts, const TriMesh3& m, const char* what) {
  if (pts.dim != 3) return {StatusCode::InvalidArgument, std::string(what) + ": mesh comparison needs 3D points"};
  if (Status f = detail::check_finite(pts, what); !f) return f;
  for (const auto& t : m.triangles)
    for (int v : t)
      if (v < 0 || static_cast<std::size_t>(v) >= pts.size())
        return {StatusCode::InvalidArgument, std::string(what) + ": vertex index " + std::to_string(v) + " out of range"};
  return Status::ok();
}

// The tree's triangles. CGAL's distance acceleration keeps one reference point per triangle, its
// first vertex; many equal ones (a polygon face read as a fan: 50 000 triangles from one vertex)
// make its Kd-tree split once per point, a recursion that overflowed the stack. Each triangle
// therefore starts at its vertex of the fewest triangles (the first such). A triangle repeated
// (the same three positions: 300 000 copies of one face overflowed the stack the same way) is in
// the tree once; it adds nothing to a distance.
std::vector<Tri3> triangles_of(const Mesh& a, double tiny, bool& any_proper) {
  any_proper = false;
  std::vector<std::uint32_t> valence(a.pts.size(), 0);
  for (const auto& f : a.m.triangles)
    for (int v : f) ++valence[static_cast<std::size_t>(v)];
  // Each triangle's corners, sorted: equal keys are the same triangle.
  using Key = std::array<double, 9>;
  std::vector<std::pair<Key, std::size_t>> keys;
  keys.reserve(a.m.triangles.size());
  for (std::size_t i = 0; i < a.m.triangles.size(); ++i) {
    std::array<std::array<double, 3>, 3> c{};
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t j = 0; j < 3; ++j) c[k][j] = a.p(a.m.triangles[i][k])[j] + 0.0;
    std::sort(c.begin(), c.end());
    Key key{};
    for (std::size_t j = 0; j < 9; ++j) key[j] = c[j / 3][j % 3];
    keys.emplace_back(key, i);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<char> repeat(a.m.triangles.size(), 0);
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i].first == keys[i - 1].first) repeat[keys[i].second] = 1;  // (the first in file order stays)
  std::vector<std::pair<Key, std::size_t>>().swap(keys);
  std::vector<Tri3> out;
  out.reserve(a.m.triangles.size());
  for (std::size_t i = 0; i < a.m.triangles.size(); ++i) {
    if (repeat[i]) continue;
    const auto& f = a.m.triangles[i];
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (valence[static_cast<std::size_t>(f[uk(k)])] < valence[static_cast<std::size_t>(f[uk(first)])]) first = k;
    const double *A = a.p(f[uk(first)]), *B = a.p(f[uk((first + 1) % 3)]), *C = a.p(f[uk((first + 2) % 3)]);
    if (!proper3(A, B, C)) continue;
    any_proper = true;
    const double longest = a.longest(i);
    if (longest >= tiny && 2 * area3(A, B, C) >= tiny * longest)  // (neither small nor thin: a height too)
      out.emplace_back(P3(A[0], A[1], A[2]), P3(B[0], B[1], B[2]), P3(C[0], C[1], C[2]));
  }
  return out;
}

// Exact position keys (-0 and +0 are the same point).
struct PosKey {
  std::array<double, 3> c;
  bool operator==(const PosKey& o) const { return c == o.c; }
};
struct PosHash {
  std::size_t operator()(const PosKey& k) const noexcept {
    std::uint64_t h = kFnvOffset;
    for (double v : k.c) {
      std::uint64_t b;
      std::memcpy(&b, &v, sizeof b);
      h = (h ^ b) * kFnvPrime;
      h ^= h >> kHashMixShift;
    }
    return static_cast<std::size_t>(h);
  }
};
PosKey key_of(const double* p) { return {{p[0] + 0.0, p[1] + 0.0, p[2] + 0.0}}; }

// The nearest float where one is finite (else the double itself): STL's 32-bit vertices.
double to_single(double x) {
  const float f = static_cast<float>(x);
  return std::isfinite(f) ? static_cast<double>(f) + 0.0 : x + 0.0;
}
PosKey single_key_of(const double* p) { return {{to_single(p[0]), to_single(p[1]), to_single(p[2])}}; }

std::array<int, 3> sorted(std::array<int, 3> t) {
  std::sort(t.begin(), t.end());
  return t;
}

}  // namespace

Status compare_meshes3(const PointSet& result_points, const TriMesh3& result, const PointSet& reference_points,
                       const TriMesh3& reference, MeshDistance& out, const DistanceOptions& options) {
  if (!ok_options(options)) return {StatusCode::InvalidArgument, "distance options: spacing must be > 0 and finite, max_samples > 0"};
  if (Status s = check_mesh(result_points, result, "result"); !s) return s;
  if (Status s = check_mesh(reference_points, reference, "reference"); !s) return s;
  const int e = common_exponent(result_points, reference_points);
  PointSet result_scaled, reference_scaled;
  if (e != 0) {
    result_scaled = scaled_by_power_of_two(result_points, -e);
    reference_scaled = scaled_by_power_of_two(reference_points, -e);
  }
  // A, B: the geometry (scaled if far from 1); A0: the coordinates as given, for the matching.
  const Mesh A{e != 0 ? result_scaled : result_points, result}, B{e != 0 ? reference_scaled : reference_points, reference};
  const Mesh A0{result_points, result};
  // (Over the vertices the triangles use: an unused vertex far off made every triangle "tiny".)
  const double tiny = std::ldexp(1.0, std::max(used_exponent(A), used_exponent(B)) - kTinyExponent);
  bool proper_a = false, proper_b = false;
  const std::vector<Tri3> ta = triangles_of(A, tiny, proper_a), tb = triangles_of(B, tiny, proper_b);
  for (const auto& [tris, proper, what] : {std::tuple{&ta, proper_a, "result"}, std::tuple{&tb, proper_b, "reference"}}) {
    if (!tris->empty()) continue;
    if (!proper) return {StatusCode::InvalidArgument, std::string(what) + ": no triangle with a positive area"};
    return {StatusCode::InvalidArgument, std::string(what) + ": every triangle is smaller or thinner than 2^-" +
                                             std::to_string(kTinyExponent) +
                                             " of the coordinates' magnitude: the two meshes are not at comparable scales (check their units)"};
  }

  MeshDistance d;
  // Reference bounding box over the used vertices.
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<double>::max(), hi[k] = -lo[k];
  for (const auto& f : reference.triangles)
    for (int v : f)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], B.p(v)[k]);
        hi[k] = std::max(hi[k], B.p(v)[k]);
      }
  d.bbox_diagonal = dist3(lo, hi);

  // Matching by exact vertex positions (or their float rounding).
  const auto key = [&options](const double* p) {
    return options.match_single_precision ? single_key_of(p) : key_of(p);
  };
  std::unordered_map<PosKey, int, PosHash> ids;
  ids.reserve(result_points.size());
  for (std::size_t i = 0; i < result_points.size(); ++i) ids.emplace(key(result_points[i]), static_cast<int>(i));
  std::vector<int> map(reference_points.size(), -1);
  std::vector<char> used(reference_points.size(), 0);
  for (const auto& f : reference.triangles)
    for (int v : f) used[static_cast<std::size_t>(v)] = 1;
  for (std::size_t i = 0; i < reference_points.size(); ++i) {
    const auto it = ids.find(key(reference_points[i]));
    if (it != ids.end()) map[i] = it->second;
    if (used[i] && it != ids.end()) ++d.matched_vertices;
  }
  // Result triangles expressed in canonical result ids (the first vertex with a position).
  std::vector<std::array<int, 3>> rt, bt;
  std::vector<std::array<int, 3>> canon_a, canon_b;
  canon_a.reserve(result.triangles.size());
  for (const auto& f : result.triangles)
    canon_a.push_back(sorted({{ids.at(key(A0.p(f[0]))), ids.at(key(A0.p(f[1]))), ids.at(key(A0.p(f[2])))}}));
  rt = canon_a;
  std::sort(rt.begin(), rt.end());
  rt.erase(std::unique(rt.begin(), rt.end()), rt.end());
  std::size_t unmatched = 0;
  for (const auto& f : reference.triangles) {
    const std::array<int, 3> m{{map[static_cast<std::size_t>(f[0])], map[static_cast<std::size_t>(f[1])],
                                map[static_cast<std::size_t>(f[2])]}};
    if (m[0] < 0 || m[1] < 0 || m[2] < 0) {
      ++unmatched;
      canon_b.push_back({{-1, -1, -1}});
      continue;
    }
    canon_b.push_back(sorted(m));
    bt.push_back(canon_b.back());
  }
  std::sort(bt.begin(), bt.end());
  bt.erase(std::unique(bt.begin(), bt.end()), bt.end());
  std::size_t common = 0;
  for (const auto& t : bt)
    if (std::binary_search(rt.begin(), rt.end(), t)) ++common;
  std::vector<char> exact_a(result.triangles.size(), 0), exact_b(reference.triangles.size(), 0);
  // Shared triangles are measured at distance 0 only when shared exactly: matched by rounding,
  // they are apart by the rounding, and that is measured.
  if (!options.match_single_precision) {
    for (std::size_t i = 0; i < result.triangles.size(); ++i)
      exact_a[i] = std::binary_search(bt.begin(), bt.end(), canon_a[i]);
    for (std::size_t i = 0; i < reference.triangles.size(); ++i)
      exact_b[i] = canon_b[i][0] >= 0 && std::binary_search(rt.begin(), rt.end(), canon_b[i]);
  } else {
    // Matched by their float rounding, a shared triangle whose vertices are also the same doubles on
    // both sides is shared exactly (an STL against itself measured 4.4e-16, not 0): the triangles
    // of each side whose every vertex is bit for bit its canonical (result) vertex.
    const auto same_a = [&](int v) { return key_of(A0.p(v)) == key_of(result_points[static_cast<std::size_t>(ids.at(key(A0.p(v))))]); };
    const auto same_b = [&](int v) {
      const int m = map[static_cast<std::size_t>(v)];
      return m >= 0 && key_of(reference_points[static_cast<std::size_t>(v)]) == key_of(result_points[static_cast<std::size_t>(m)]);
    };
    std::vector<char> own_a(result.triangles.size(), 0), own_b(reference.triangles.size(), 0);
    std::vector<std::array<int, 3>> rt_exact, bt_exact;
    for (std::size_t i = 0; i < result.triangles.size(); ++i) {
      const auto& f = result.triangles[i];
      if ((own_a[i] = same_a(f[0]) && same_a(f[1]) && same_a(f[2]))) rt_exact.push_back(canon_a[i]);
    }
    for (std::size_t i = 0; i < reference.triangles.size(); ++i) {
      const auto& f = reference.triangles[i];
      if ((own_b[i] = canon_b[i][0] >= 0 && same_b(f[0]) && same_b(f[1]) && same_b(f[2]))) bt_exact.push_back(canon_b[i]);
    }
    for (auto* v : {&rt_exact, &bt_exact}) {
      std::sort(v->begin(), v->end());
      v->erase(std::unique(v->begin(), v->end()), v->end());
    }
    for (std::size_t i = 0; i < result.triangles.size(); ++i)
      exact_a[i] = own_a[i] && std::binary_search(bt_exact.begin(), bt_exact.end(), canon_a[i]);
    for (std::size_t i = 0; i < reference.triangles.size(); ++i)
      exact_b[i] = own_b[i] && std::binary_search(rt_exact.begin(), rt_exact.end(), canon_b[i]);
  }
  d.reference_triangles = reference.triangles.size();
  d.result_triangles = result.triangles.size();
  d.recovered_triangles = common;
  d.triangle_recovery = static_cast<double>(common) / static_cast<double>(d.reference_triangles);
  d.triangle_precision = static_cast<double>(common) / static_cast<double>(d.result_triangles);
  // The same triangles as multisets: a face repeated on one side only (a precision of 4/5) is a
  // difference, though each side's distinct triangles are the other's.
  d.identical = unmatched == 0 && common == rt.size() && common == bt.size() && canon_a.size() == canon_b.size();
  if (d.identical) {
    std::vector<std::array<int, 3>> sa = canon_a, sb = canon_b;
    std::sort(sa.begin(), sa.end());
    std::sort(sb.begin(), sb.end());
    d.identical = sa == sb;
  }

  // Distances.
  TriTree tree_a(ta.begin(), ta.end()), tree_b(tb.begin(), tb.end());
  prepare(tree_a);
  prepare(tree_b);
  const double h0 = options.relative_spacing * d.bbox_diagonal;
  d.spacing_result = choose_spacing(h0, d.bbox_diagonal, longest3(A), options.max_samples, [&](double h) { return count3(A, h); });
  d.spacing_reference = choose_spacing(h0, d.bbox_diagonal, longest3(B), options.max_samples, [&](double h) { return count3(B, h); });
  const Side ab = sample_to_tree(A, tree_b, d.spacing_result, exact_a);
  const Side ba = sample_to_tree(B, tree_a, d.spacing_reference, exact_b);
  put_sides(ab, ba, d);
  if (Status f = scale_back(d, e); !f) return f;
  out = d;
  return Status::ok();
}

// ---- 2D ------------------------------------------------------------------------------------
namespace {

struct Seg2 {
  double a[2], b[2];
  double length() const { return std::hypot(b[0] - a[0], b[1] - a[1]); }
};

Status segments_of(const std::vector<Polyline2>& lines, const char* what, std::vector<Seg2>& out) {
  out.clear();
  for (const auto& l : lines) {
    if (l.xy.size() % 2 != 0) return {StatusCode::InvalidArgument, std::string(what) + ": odd coordinate count"};
    for (double v : l.xy)
      if (!std::isfinite(v)) return {StatusCode::NonFinite, std::string(what) + ": non-finite coordinate"};
    const std::size_t n = l.xy.size() / 2;
    const std::size_t m = l.closed && n > 2 ? n : (n > 0 ? n - 1 : 0);
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = (i + 1) % n;
      out.push_back({{l.xy[2 * i], l.xy[2 * i + 1]}, {l.xy[2 * j], l.xy[2 * j + 1]}});
    }
  }
  if (out.empty())
    return {StatusCode::InvalidArgument, std::string(what) + ": no segment to measure (every curve in it has fewer than two points)"};
  return Status::ok();
}

double longest2(const std::vector<Seg2>& s) {
  double m = 0;
  for (const auto& g : s) m = std::max(m, g.length());
  return m;
}

std::size_t count2(const std::vector<Seg2>& s, double h) {
  std::size_t n = 0;
  for (const auto& g : s) n += grid_k(g.length(), h) + 1;
  return n;
}

// Trapezoid rule on the k+1 nodes of each segment: the exact integral of the piecewise-linear
// interpolant of the node distances.
// Segments flagged in `exact` are also segments of the other side: distance 0 without a query.
Side sample2(const std::vector<Seg2>& s, const SegTree& tree, double h, const std::vector<char>& exact) {
  const std::size_t M = s.size();
  std::vector<double> smax(M, 0.0), sint(M, 0.0), slen(M, 0.0);
  std::vector<std::size_t> scount(M, 0);
  const Distance distance(tree);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, M, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Seg2& g = s[i];
      const double len = g.length();
      const std::size_t k = grid_k(len, h);
      double mx = 0, sum = 0;
      for (std::size_t j = 0; j <= k; ++j) {
        const double t = static_cast<double>(j) / static_cast<double>(k);
        const P3 q(g.a[0] + t * (g.b[0] - g.a[0]), g.a[1] + t * (g.b[1] - g.a[1]), 0.0);
        const double d = exact[i] ? 0.0 : distance(tree, q);
        mx = std::max(mx, d);
        sum += (j == 0 || j == k) ? 0.5 * d : d;
      }
      smax[i] = mx;
      sint[i] = sum / static_cast<double>(k) * len;
      slen[i] = len;
      scount[i] = k + 1;
    }
  });
  return reduce(smax, sint, slen, scount);
}

// Unordered endpoint coordinates, -0 folded into +0: equal keys are the same segment.
std::array<double, 4> seg_key(const Seg2& g) {
  std::array<double, 4> k{{g.a[0] + 0.0, g.a[1] + 0.0, g.b[0] + 0.0, g.b[1] + 0.0}};
  if (std::make_pair(k[2], k[3]) < std::make_pair(k[0], k[1])) k = {{k[2], k[3], k[0], k[1]}};
  return k;
}

std::vector<char> shared_segments(const std::vector<Seg2>& s, const std::vector<Seg2>& other) {
  std::vector<std::array<double, 4>> keys;
  keys.reserve(other.size());
  for (const auto& g : other) keys.push_back(seg_key(g));
  std::sort(keys.begin(), keys.end());
  std::vector<char> out(s.size(), 0);
  for (std::size_t i = 0; i < s.size(); ++i) out[i] = std::binary_search(keys.begin(), keys.end(), seg_key(s[i]));
  return out;
}

// The search tree's segments: those not shorter than `tiny` (> 0; kTinyExponent).
std::vector<Seg3> seg3_of(const std::vector<Seg2>& s, double tiny) {
  std::vector<Seg3> out;
  out.reserve(s.size());
  for (const auto& g : s)
    if (g.length() >= tiny) out.emplace_back(P3(g.a[0], g.a[1], 0.0), P3(g.b[0], g.b[1], 0.0));
  return out;
}

}  // namespace

Status compare_curves2(const std::vector<Polyline2>& result, const std::vector<Polyline2>& reference,
                       CurveDistance2& out, const DistanceOptions& options) {
  if (!ok_options(options)) return {StatusCode::InvalidArgument, "distance options: spacing must be > 0 and finite, max_samples > 0"};
  std::vector<Seg2> sa, sb;
  if (Status st = segments_of(result, "result", sa); !st) return st;
  if (Status st = segments_of(reference, "reference", sb); !st) return st;
  // Far from 1 in magnitude, as in 3D (common_exponent): measured on the coordinates times 2^-e
  // (exact: the shared segments stay equal) and scaled back. (Before, curves near 1e200 measured
  // a Hausdorff distance of 0 and a mean of NaN: the squared distances overflowed.)
  MaxExponent magnitude;
  for (const auto* segs : {&sa, &sb})
    for (const Seg2& g : *segs)
      for (double v : {g.a[0], g.a[1], g.b[0], g.b[1]}) magnitude.add(v);
  const int e = rescale_exponent(magnitude.get());
  if (e != 0)
    for (auto* segs : {&sa, &sb})
      for (Seg2& g : *segs)
        for (double* v : {&g.a[0], &g.a[1], &g.b[0], &g.b[1]}) *v = std::ldexp(*v, -e);
  const double tiny = std::ldexp(1.0, magnitude.get() - e - kTinyExponent);  // (of the scaled magnitude)
  const std::vector<Seg3> ga = seg3_of(sa, tiny), gb = seg3_of(sb, tiny);
  for (const auto& [segs, tree, what] : {std::tuple{&sa, &ga, "result"}, std::tuple{&sb, &gb, "reference"}}) {
    if (!tree->empty()) continue;
    const bool any = std::any_of(segs->begin(), segs->end(), [](const Seg2& g) { return g.length() > 0; });
    if (!any) return {StatusCode::InvalidArgument, std::string(what) + ": a curve has only zero-length segments"};
    return {StatusCode::InvalidArgument, std::string(what) + ": every segment is shorter than 2^-" + std::to_string(kTinyExponent) +
                                             " of the coordinates' magnitude: not comparable at this scale"};
  }
  CurveDistance2 d;
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()}, hi[2] = {-lo[0], -lo[1]};
  for (const auto& g : sb)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min({lo[k], g.a[k], g.b[k]});
      hi[k] = std::max({hi[k], g.a[k], g.b[k]});
    }
  d.bbox_diagonal = std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
  SegTree ta(ga.begin(), ga.end()), tb(gb.begin(), gb.end());
  prepare(ta);
  prepare(tb);
  const double h0 = options.relative_spacing * d.bbox_diagonal;
  d.spacing_result = choose_spacing(h0, d.bbox_diagonal, longest2(sa), options.max_samples, [&](double h) { return count2(sa, h); });
  d.spacing_reference = choose_spacing(h0, d.bbox_diagonal, longest2(sb), options.max_samples, [&](double h) { return count2(sb, h); });
  const Side ab = sample2(sa, tb, d.spacing_result, shared_segments(sa, sb));
  const Side ba = sample2(sb, ta, d.spacing_reference, shared_segments(sb, sa));
  put_sides(ab, ba, d);
  if (Status f = scale_back(d, e); !f) return f;
  out = d;
  return Status::ok();
}

std::vector<Polyline2> reference_polylines2(const PointSet& points, const Reference2& reference) {
  std::vector<Polyline2> out;
  const auto add = [&](const std::vector<int>& ids, bool closed) {
    Polyline2 l;
    l.closed = closed;
    for (int i : ids) {
      l.xy.push_back(points[static_cast<std::size_t>(i)][0]);
      l.xy.push_back(points[static_cast<std::size_t>(i)][1]);
    }
    out.push_back(std::move(l));
  };
  for (const auto& c : reference.closed) add(c, true);
  for (const auto& o : reference.open) add(o, false);
  return out;
}

Polyline2 polygon_polyline2(const PointSet& points, const std::vector<int>& polygon) {
  Polyline2 l;
  for (int i : polygon) {
    l.xy.push_back(points[static_cast<std::size_t>(i)][0]);
    l.xy.push_back(points[static_cast<std::size_t>(i)][1]);
  }
  return l;
}

}  // namespace constrict
