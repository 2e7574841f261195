// SPDX-License-Identifier: GPL-3.0-or-later
// Non-Delaunay faces of the γ-graphs with a negative threshold m (spec §1.2, §2.2, §4.3).
// docs/gamma-lens-graphs.md has the algorithm and the proofs; "Lemma n" below refers to it.
//
// Exactness contract. A face is rejected only (a) by a witness point whose apex value, computed
// by apex_gamma2/3 exactly as the oracle does, is < m, or which lies in the open segment/disc
// (exact predicates), or (b) by a geometric pruning rule that certifies such a witness with a
// margin: the rules are evaluated for the smaller lens L(m - kShrink) and with relative slack
// kRel on every floating comparison, so the witness' true apex value is below m - kShrink and
// its computed value (error ~1e-15) below m. Side values of the output are minima over point
// sets proven to contain every point whose computed apex value can be the minimum.
#include "gamma/detail/extra_faces.hpp"

#include <algorithm>
#include <cstdio>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include <nanoflann.hpp>

#include "constrict/predicates.hpp"

namespace constrict::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxFaces = 20000000;     // output cap (Unsupported beyond)
constexpr double kMaxSubsets = 2e7;             // m = -1: refuse above this many k-subsets
constexpr double kTriangleBudget = 4e8;         // 3D: candidate triangles examined at most
constexpr double kShrink = 1e-7;                // pruning uses L(m - kShrink) ⊂ L(m)
constexpr double kRel = 1e-9;                   // relative slack of float distance comparisons
constexpr double kBallRel = 1e-7;               // relative slack of ball queries
constexpr double kGammaSlack = 1e-9;            // > rounding error of apex_gamma2/3
constexpr double kAngleSlack = 1e-9;            // > rounding error of computed directions
constexpr double kTangentCut = 1e-4;            // shadows nearly tangent to a bin are skipped
constexpr double kSliverSin2 = 1e-12;           // sin^2 of the angle at a below which the
                                                // computed circumcentre is not trusted
constexpr int kMaxGrowRounds = 40;              // grow_side: 4^40 r, then a linear scan
// Point tests at most (linear scans, the points of each ball query, the pairs the 2D search
// visits): near m = -1 nearly every pair is a face and each costs a query, and 20 000 points at
// m = -0.95 ran for more than 15 minutes; at -0.9 they use about half of it (20 s).
constexpr double kScanBudget = 4e8;

// ---- k-d tree (nanoflann) ----------------------------------------------------------------------

struct Cloud {
  const double* xyz = nullptr;
  std::size_t n = 0;
  std::size_t dim = 2;
  std::size_t kdtree_get_point_count() const { return n; }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return xyz[i * dim + d]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

template <int D>
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>,
                                                   Cloud, D, std::uint32_t>;

template <int D>
struct Ctx {
  const PointSet* ps = nullptr;
  double m = 0;
  Cloud cloud;
  std::unique_ptr<KdTree<D>> tree;
  double tol = 0;            // absolute slack of ball queries (coordinate rounding)
  double lo[D], hi[D];       // bounding box of the points
  double far_radius = 0;     // beyond this a growing ball is replaced by a linear scan
  std::unordered_set<std::uint64_t> delaunay;
  std::vector<std::pair<std::uint32_t, double>> hits;
  std::size_t tested = 0;
  double scanned = 0;  // point tests: linear scans, ball queries, pairs visited (kScanBudget)
  bool over_budget() const { return scanned > kScanBudget; }
};

std::uint64_t face_key(const int* ids, int dim) {
  if (dim == 2)
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ids[0])) << 32) |
           static_cast<std::uint32_t>(ids[1]);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ids[0])) << 42) |
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ids[1])) << 21) |
         static_cast<std::uint32_t>(ids[2]);
}

template <int D>
void ball_query(Ctx<D>& ctx, const double* q, double radius) {
  ctx.hits.clear();
  const double r2 = radius * radius;
  ctx.tree->radiusSearch(q, r2, ctx.hits, nanoflann::SearchParams(32, 0.0F, false));
}

// ---- the sphere of a face and exact side values ------------------------------------------------

struct Sphere {
  double c[3] = {0, 0, 0};
  double n[3] = {0, 0, 0};  // unit normal towards side a
  double r = 0;
};

void sphere2(const double* a, const double* b, Sphere& s) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len = std::sqrt(dx * dx + dy * dy);
  s.c[0] = 0.5 * (a[0] + b[0]);
  s.c[1] = 0.5 * (a[1] + b[1]);
  s.r = 0.5 * len;
  s.n[0] = -dy / len;  // left of a->b: orient2(a, b, p) > 0
  s.n[1] = dx / len;
}

// Circumcentre as in apex_gamma3; returns |e1 x e2|^2 / (|e1|^2 |e2|^2) (sin^2 of the angle at a).
double sphere3(const double* a, const double* b, const double* c, Sphere& s) {
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  const double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
  const double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  const double w[3] = {l1 * e2[0] - l2 * e1[0], l1 * e2[1] - l2 * e1[1], l1 * e2[2] - l2 * e1[2]};
  const double o[3] = {(w[1] * n[2] - w[2] * n[1]) / (2 * nn),
                       (w[2] * n[0] - w[0] * n[2]) / (2 * nn),
                       (w[0] * n[1] - w[1] * n[0]) / (2 * nn)};
  const double nl = std::sqrt(nn);
  for (int d = 0; d < 3; ++d) {
    s.c[d] = a[d] + o[d];
    s.n[d] = n[d] / nl;  // orient3(a, b, c, p) > 0  <=>  (p - a).n > 0
  }
  s.r = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
  return nn / (l1 * l2);
}

template <int D>
const double* pt(const Ctx<D>& ctx, std::size_t i) {
  return (*ctx.ps)[i];
}

// Side of p (+1 side a, -1 side b, 0 on H) and, when on H, whether it blocks (Lemma 0).
template <int D>
int side_of(const Ctx<D>& ctx, const int* ids, const double* p, bool& blocks) {
  blocks = false;
  if constexpr (D == 2) {
    const double* a = pt(ctx, static_cast<std::size_t>(ids[0]));
    const double* b = pt(ctx, static_cast<std::size_t>(ids[1]));
    const int o = orient2(a, b, p);
    if (o == 0) blocks = diametral_side2(a, b, p) < 0;
    return o;
  } else {
    const double* a = pt(ctx, static_cast<std::size_t>(ids[0]));
    const double* b = pt(ctx, static_cast<std::size_t>(ids[1]));
    const double* c = pt(ctx, static_cast<std::size_t>(ids[2]));
    const int o = orient3(a, b, c, p);
    if (o == 0) blocks = in_circle_coplanar3(a, b, c, p) > 0;
    return o;
  }
}

template <int D>
double apex(const Ctx<D>& ctx, const int* ids, const double* p) {
  if constexpr (D == 2) {
    return apex_gamma2(pt(ctx, static_cast<std::size_t>(ids[0])),
                       pt(ctx, static_cast<std::size_t>(ids[1])), p);
  } else {
    return apex_gamma3(pt(ctx, static_cast<std::size_t>(ids[0])),
                       pt(ctx, static_cast<std::size_t>(ids[1])),
                       pt(ctx, static_cast<std::size_t>(ids[2])), p);
  }
}

template <int D>
bool is_vertex(const int* ids, std::uint32_t i) {
  for (int k = 0; k < D; ++k)
    if (static_cast<std::uint32_t>(ids[k]) == i) return true;
  return false;
}

// Minimum apex value on side `side` when no point of that side lies in the closed smallest ball
// (all values positive). The cap C_s(g) lies in the ball through σ of radius r/(1-g) centred at
// c + τ(g)·s·n (spec §1.1-1.2); a point outside it has apex value >= g (Lemma 5).
// The linear scans are exact (every point, the oracle's computation) and O(N): they are counted.
template <int D>
void count_scan(Ctx<D>& ctx) {
  ctx.scanned += static_cast<double>(ctx.ps->size());
}

template <int D>
void grow_side(Ctx<D>& ctx, const int* ids, const Sphere& s, int side, double& mn) {
  double tau = s.r;
  for (int round = 0;; ++round) {
    const double R = std::hypot(s.r, tau);
    // Beyond far_radius the cap is essentially the half-space; after kMaxGrowRounds (a radius
    // that underflowed to 0, or a box near the double range) the growth would not end.
    if (!(R <= ctx.far_radius) || round == kMaxGrowRounds) {
      // Scan every point (exact, O(N)).
      count_scan(ctx);
      const std::size_t n = ctx.ps->size();
      for (std::size_t i = 0; i < n; ++i) {
        if (is_vertex<D>(ids, static_cast<std::uint32_t>(i))) continue;
        bool blocks = false;
        const double* p = pt(ctx, i);
        if (side_of(ctx, ids, p, blocks) == side) mn = std::min(mn, apex(ctx, ids, p));
      }
      return;
    }
    double q[D];
    for (int d = 0; d < D; ++d) q[d] = s.c[d] + side * tau * s.n[d];
    ball_query(ctx, q, R * (1 + kBallRel) + ctx.tol);
    ctx.scanned += static_cast<double>(ctx.hits.size());  // (the ball's points are tested too)
    for (const auto& h : ctx.hits) {
      if (is_vertex<D>(ids, h.first)) continue;
      bool blocks = false;
      const double* p = pt(ctx, h.first);
      if (side_of(ctx, ids, p, blocks) == side) mn = std::min(mn, apex(ctx, ids, p));
    }
    const double g = 1.0 - s.r / R;
    if (mn < g - kGammaSlack) return;
    tau *= 4;
  }
}

// The exact test (Lemma 4, 5): false if a point blocks the face or has apex value < m;
// otherwise the exact side values.
// The same test by scanning every point, for a face whose smallest ball is not reliable in
// doubles (a radius or normal that is not finite or zero, a sliver whose computed circumcentre
// has no correct digits): a near-collinear triple made the ball NaN, the ball query empty and
// grow_side endless.
template <int D>
bool scan_face(Ctx<D>& ctx, const int* ids, double& ga, double& gb) {
  count_scan(ctx);
  double mins[2] = {1.0, 1.0};
  const std::size_t n = ctx.ps->size();
  for (std::size_t i = 0; i < n; ++i) {
    if (is_vertex<D>(ids, static_cast<std::uint32_t>(i))) continue;
    const double* p = pt(ctx, i);
    bool blocks = false;
    const int o = side_of(ctx, ids, p, blocks);
    if (o == 0) {
      if (blocks) return false;
      continue;
    }
    const double g = apex(ctx, ids, p);
    if (g < ctx.m) return false;
    double& mn = mins[o > 0 ? 0 : 1];
    mn = std::min(mn, g);
  }
  ga = mins[0];
  gb = mins[1];
  return true;
}

bool usable(const Sphere& s, int dim) {
  bool ok = s.r > 0 && std::isfinite(s.r);
  for (int d = 0; d < dim; ++d) ok = ok && std::isfinite(s.c[d]) && std::isfinite(s.n[d]);
  return ok;
}

template <int D>
bool evaluate_face(Ctx<D>& ctx, const int* ids, double& ga, double& gb) {
  ++ctx.tested;
  Sphere s;
  bool reliable = true;
  if constexpr (D == 2) {
    sphere2(pt(ctx, static_cast<std::size_t>(ids[0])), pt(ctx, static_cast<std::size_t>(ids[1])), s);
  } else {
    const double sin2 = sphere3(pt(ctx, static_cast<std::size_t>(ids[0])),
                                pt(ctx, static_cast<std::size_t>(ids[1])),
                                pt(ctx, static_cast<std::size_t>(ids[2])), s);
    reliable = sin2 > kSliverSin2;
  }
  if (!reliable || !usable(s, D)) return scan_face(ctx, ids, ga, gb);
  double mins[2] = {1.0, 1.0};  // side a, side b
  // Every point with a negative apex value, or in D, lies in the open smallest ball (exact sign).
  ball_query(ctx, s.c, s.r * (1 + kBallRel) + ctx.tol);
  ctx.scanned += static_cast<double>(ctx.hits.size());
  for (const auto& h : ctx.hits) {
    if (is_vertex<D>(ids, h.first)) continue;
    const double* p = pt(ctx, h.first);
    bool blocks = false;
    const int o = side_of(ctx, ids, p, blocks);
    if (o == 0) {
      if (blocks) return false;
      continue;
    }
    const double g = apex(ctx, ids, p);
    if (g < ctx.m) return false;
    double& mn = mins[o > 0 ? 0 : 1];
    mn = std::min(mn, g);
  }
  for (int k = 0; k < 2; ++k)
    if (mins[k] > 0) grow_side(ctx, ids, s, k == 0 ? 1 : -1, mins[k]);
  ga = mins[0];
  gb = mins[1];
  return true;
}

Status scan_budget_status(bool estimated = false) {
  return {StatusCode::Unsupported,
          std::string("lens faces: more than 4e8 point tests") + (estimated ? ", estimated from the first candidates" : "") +
              " (a threshold near -1 makes nearly every pair a face, or "
              "near-degenerate faces need linear scans): use a threshold closer to 0 or fewer points; see "
              "docs/gamma-lens-graphs.md"};
}

// The 3D search refuses early when the point tests of its first 0.5 %, 1 %, 2 %, ... of the
// candidate triangles, extrapolated, exceed kEstimateFactor times the budget (300 or 500 points
// of a sphere at beta-lune 0.5 or 0.9 ran 20-36 s before the budget stopped them). It visits the
// vertices spread over the input (kEstimateBlock, kEstimateStride), so that each share is a
// sample of the whole. Counts only: the same decision on any machine.
constexpr double kEstimateShare = 0.005;
constexpr double kEstimateFactor = 2;
constexpr std::size_t kEstimateBlock = 64, kEstimateStride = 16;  // the pass's order (lens_faces3)

struct FoundFace {
  std::array<int, 3> ids;
  double ga, gb;
};

template <int D>
Status setup(Ctx<D>& ctx, const PointSet& points, double m, const GammaFaces& delaunay_faces) {
  ctx.ps = &points;
  ctx.m = m;
  const std::size_t n = points.size();
  ctx.cloud.xyz = points.coords.data();
  ctx.cloud.n = n;
  ctx.cloud.dim = static_cast<std::size_t>(D);
  double mabs = 0;
  for (int d = 0; d < D; ++d) {
    ctx.lo[d] = kInf;
    ctx.hi[d] = -kInf;
  }
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < D; ++d) {
      const double x = points[i][d];
      ctx.lo[d] = std::min(ctx.lo[d], x);
      ctx.hi[d] = std::max(ctx.hi[d], x);
      mabs = std::max(mabs, std::fabs(x));
    }
  double diag2 = 0;
  for (int d = 0; d < D; ++d) diag2 += (ctx.hi[d] - ctx.lo[d]) * (ctx.hi[d] - ctx.lo[d]);
  ctx.tol = 64 * std::numeric_limits<double>::epsilon() * mabs;
  ctx.far_radius = 1e4 * (std::sqrt(diag2) + mabs);
  try {
    ctx.tree = std::make_unique<KdTree<D>>(D, ctx.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  } catch (const std::exception& e) {
    return {StatusCode::Internal, std::string("lens faces: k-d tree construction failed: ") + e.what()};
  }
  ctx.delaunay.reserve(delaunay_faces.size() * 2 + 16);
  for (std::size_t f = 0; f < delaunay_faces.size(); ++f)
    ctx.delaunay.insert(face_key(&delaunay_faces.vertices[f * static_cast<std::size_t>(D)], D));
  return Status::ok();
}

// ---- best-first k-d tree walk (Hjaltason & Samet) ----------------------------------------------

template <int D>
struct Entry {
  double key;        // squared distance lower bound
  const void* node;  // nullptr: a point
  std::uint32_t idx;
  double lo[D], hi[D];
};

template <int D>
struct EntryGreater {
  bool operator()(const Entry<D>& a, const Entry<D>& b) const { return a.key > b.key; }
};

template <int D>
double box_dist2(const double* lo, const double* hi, const double* u) {
  double s = 0;
  for (int d = 0; d < D; ++d) {
    const double t = u[d] < lo[d] ? lo[d] - u[d] : (u[d] > hi[d] ? u[d] - hi[d] : 0.0);
    s += t * t;
  }
  return s;
}

// Walks the tree from u in increasing distance. on_point(idx, dist2) is called for every point
// (u included) not inside a pruned node; prune(entry) may discard a node; stop(key) ends the walk.
template <int D, class OnPoint, class Prune>
void best_first(const KdTree<D>& tree, const double* u, std::vector<Entry<D>>& heap,
                OnPoint&& on_point, Prune&& prune) {
  using Node = typename KdTree<D>::Node;
  heap.clear();
  if (tree.root_node == nullptr) return;
  const EntryGreater<D> cmp;
  Entry<D> root{};
  root.node = tree.root_node;
  for (int d = 0; d < D; ++d) {
    root.lo[d] = tree.root_bbox[static_cast<std::size_t>(d)].low;
    root.hi[d] = tree.root_bbox[static_cast<std::size_t>(d)].high;
  }
  root.key = box_dist2<D>(root.lo, root.hi, u);
  heap.push_back(root);
  const Cloud& cloud = tree.dataset;
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), cmp);
    const Entry<D> e = heap.back();
    heap.pop_back();
    if (e.node == nullptr) {
      if (!on_point(e.idx, e.key)) return;
      continue;
    }
    if (prune(e)) continue;
    const Node* node = static_cast<const Node*>(e.node);
    if (node->child1 == nullptr && node->child2 == nullptr) {
      for (auto i = node->node_type.lr.left; i < node->node_type.lr.right; ++i) {
        const std::uint32_t idx = tree.vAcc[i];
        Entry<D> pe{};
        pe.node = nullptr;
        pe.idx = idx;
        double s = 0;
        for (int d = 0; d < D; ++d) {
          const double t = cloud.kdtree_get_pt(idx, static_cast<std::size_t>(d)) - u[d];
          s += t * t;
        }
        pe.key = s;
        heap.push_back(pe);
        std::push_heap(heap.begin(), heap.end(), cmp);
      }
      continue;
    }
    const int f = node->node_type.sub.divfeat;
    Entry<D> c1 = e, c2 = e;
    c1.node = node->child1;
    c1.hi[f] = node->node_type.sub.divlow;
    c2.node = node->child2;
    c2.lo[f] = node->node_type.sub.divhigh;
    c1.key = box_dist2<D>(c1.lo, c1.hi, u);
    c2.key = box_dist2<D>(c2.lo, c2.hi, u);
    heap.push_back(c1);
    std::push_heap(heap.begin(), heap.end(), cmp);
    heap.push_back(c2);
    std::push_heap(heap.begin(), heap.end(), cmp);
  }
}

// ---- 2D: shadows (Lemma 1-3) -------------------------------------------------------------------

constexpr int kBins2 = 64;


struct Shadow2 {
  double psi = 0, sin_psi = 0;
  double bw = 2 * kPi / kBins2;
  std::array<double, kBins2> reach{};   // points of the bin beyond this distance are shadowed
  std::array<int, kBins2> witness{};
  int span = 0;
  std::vector<double> tab_s, tab_c;

  int bin_of(double phi) const {
    long j = static_cast<long>(std::floor((phi + kPi) / bw));
    j %= kBins2;
    if (j < 0) j += kBins2;
    return static_cast<int>(j);
  }
  void reset() {
    reach.fill(kInf);
    witness.fill(-1);
  }
  // Shadow of w (at distance delta, direction phi) seen from u: the cone with apex w, axis w-u,
  // half-angle psi. A ray from u at angle beta < psi from the axis enters it at distance
  // delta sin(psi) / sin(psi - beta) (Lemma 1). For the bin k steps away from phi's bin the
  // largest beta is k*bw + off or (k+1)*bw - off (off = phi's offset in its bin), so
  // sin(psi - beta) comes from the tables by angle addition (two trig calls per shadow).
  void prepare() {
    span = static_cast<int>(std::ceil(psi / bw)) + 1;
    tab_s.assign(static_cast<std::size_t>(span) + 2, 0.0);
    tab_c.assign(static_cast<std::size_t>(span) + 2, 0.0);
    for (int i = 0; i < span + 2; ++i) {
      tab_s[static_cast<std::size_t>(i)] = std::sin(psi - i * bw);
      tab_c[static_cast<std::size_t>(i)] = std::cos(psi - i * bw);
    }
  }
  void insert(double delta, double phi, int w) {
    if (!(psi > kTangentCut)) return;
    const double jraw = std::floor((phi + kPi) / bw);  // phi = pi lands in bin 0 with off 0
    const int jc = bin_of(phi);
    const double off = std::min(bw, std::max(0.0, phi + kPi - jraw * bw));
    const double so = std::sin(off), co = std::cos(off);
    for (int k = -span; k <= span; ++k) {
      // gap = psi - beta_max, written as (psi - i*bw) + sign*off
      int i;
      double sign;
      if (k > 0 || (k == 0 && off < 0.5 * bw)) {
        i = k + 1;
        sign = 1.0;
      } else {
        i = -k;
        sign = -1.0;
      }
      const double gap = (psi - i * bw) + sign * off - kAngleSlack;
      if (gap <= kTangentCut) continue;
      const auto ii = static_cast<std::size_t>(i);
      // sin(gap) up to the slack term, which only lowers it (|d sin| <= |d angle|).
      const double sg = tab_s[ii] * co + sign * tab_c[ii] * so - kAngleSlack;
      const double bound = delta * sin_psi / sg;
      const auto j = static_cast<std::size_t>(((jc + k) % kBins2 + kBins2) % kBins2);
      if (bound < reach[j]) {
        reach[j] = bound;
        witness[j] = w;
      }
    }
  }
  // True if every point of the box (seen from u outside it) is certainly shadowed (Lemma 2).
  bool box_shadowed(const double* lo, const double* hi, const double* u, double key) const {
    if (!(key > 0)) return false;
    const double dmin = std::sqrt(key);
    const double cx = 0.5 * (lo[0] + hi[0]) - u[0], cy = 0.5 * (lo[1] + hi[1]) - u[1];
    const double phic = std::atan2(cy, cx);
    double amin = kInf, amax = -kInf;
    for (int k = 0; k < 4; ++k) {
      const double x = ((k & 1) ? hi[0] : lo[0]) - u[0];
      const double y = ((k & 2) ? hi[1] : lo[1]) - u[1];
      double d = std::atan2(y, x) - phic;
      if (d > kPi) d -= 2 * kPi;
      if (d < -kPi) d += 2 * kPi;
      amin = std::min(amin, d);
      amax = std::max(amax, d);
    }
    amin -= kAngleSlack;
    amax += kAngleSlack;
    if (amax - amin >= kPi) return false;
    const int j0 = bin_of(phic + amin);
    const int j1 = bin_of(phic + amax);
    const int count = ((j1 - j0) % kBins2 + kBins2) % kBins2;
    for (int k = 0; k <= count; ++k) {
      const int j = (j0 + k) % kBins2;
      if (!(dmin > reach[static_cast<std::size_t>(j)] * (1 + kRel))) return false;
    }
    return true;
  }
};

Status lens_faces2(Ctx<2>& ctx, std::vector<FoundFace>& found) {
  const std::size_t n = ctx.ps->size();
  const double ms = std::max(-1.0, ctx.m - kShrink);
  Shadow2 sh;
  sh.psi = std::asin(std::min(1.0, 1.0 - std::fabs(ms)));
  sh.sin_psi = std::sin(sh.psi);
  sh.prepare();
  std::vector<Entry<2>> heap;
  heap.reserve(256);
  bool overflow = false;
  for (std::size_t ui = 0; ui < n && !overflow; ++ui) {
    const auto u = static_cast<std::uint32_t>(ui);
    const double* pu = pt(ctx, ui);
    sh.reset();
    auto on_point = [&](std::uint32_t v, double key) {
      if (v == u) return true;
      ctx.scanned += 1;  // (near m = -1 the shadows prune little: every pair is visited)
      const double* pv = pt(ctx, v);
      const double dx = pv[0] - pu[0], dy = pv[1] - pu[1];
      const double len = std::sqrt(key);
      const double phi = std::atan2(dy, dx);
      const int j = sh.bin_of(phi);
      const bool shadowed = len > sh.reach[static_cast<std::size_t>(j)] * (1 + kRel);
      if (!shadowed && v > u) {
        const int ids[2] = {static_cast<int>(u), static_cast<int>(v)};
        if (ctx.delaunay.count(face_key(ids, 2)) == 0) {
          bool reject = false;
          const int w = sh.witness[static_cast<std::size_t>(j)];
          if (w >= 0 && static_cast<std::uint32_t>(w) != v) {
            // Cheap exact check with the nearest shadow caster first (same predicate as below).
            const double* pw = pt(ctx, static_cast<std::size_t>(w));
            const int o = orient2(pu, pv, pw);
            reject = (o == 0) ? diametral_side2(pu, pv, pw) < 0 : apex_gamma2(pu, pv, pw) < ctx.m;
            if (reject) ++ctx.tested;
          }
          double ga = 0, gb = 0;
          if (!reject && evaluate_face(ctx, ids, ga, gb)) {
            found.push_back({{ids[0], ids[1], -1}, ga, gb});
            if (found.size() > kMaxFaces) {
              overflow = true;
              return false;
            }
          }
          if (ctx.over_budget()) return false;
        }
      }
      sh.insert(len, phi, static_cast<int>(v));
      return true;
    };
    auto prune = [&](const Entry<2>& e) { return sh.box_shadowed(e.lo, e.hi, pu, e.key); };
    best_first<2>(*ctx.tree, pu, heap, on_point, prune);
    if (ctx.over_budget()) return scan_budget_status();
  }
  if (overflow)
    return {StatusCode::Unsupported,
            "lens faces: more than 2e7 non-Delaunay faces for m = " + std::to_string(ctx.m) +
                "; use a threshold closer to 0"};
  return Status::ok();
}

// ---- 3D: ice-cream cones (Lemma 6-7) -----------------------------------------------------------

constexpr int kCube = 6;                       // cube-map cells per face edge
constexpr int kBins3 = 6 * kCube * kCube;

struct DirBins {
  std::array<std::array<double, 3>, kBins3> centre{};
  std::array<double, kBins3> radius{};  // max angle from the centre to the cell, + slack
  double max_radius = 0;

  static void face_point(int face, double s, double t, double out[3]) {
    const int axis = face / 2;
    const double sign = (face % 2 == 0) ? 1.0 : -1.0;
    out[axis] = sign;
    out[(axis + 1) % 3] = s;
    out[(axis + 2) % 3] = t;
    const double l = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    for (int d = 0; d < 3; ++d) out[d] /= l;
  }
  DirBins() {
    for (int face = 0; face < 6; ++face)
      for (int i = 0; i < kCube; ++i)
        for (int k = 0; k < kCube; ++k) {
          const std::size_t j = static_cast<std::size_t>((face * kCube + i) * kCube + k);
          const double s0 = -1 + 2.0 * i / kCube, s1 = -1 + 2.0 * (i + 1) / kCube;
          const double t0 = -1 + 2.0 * k / kCube, t1 = -1 + 2.0 * (k + 1) / kCube;
          double c[3];
          face_point(face, 0.5 * (s0 + s1), 0.5 * (t0 + t1), c);
          centre[j] = {c[0], c[1], c[2]};
          double rad = 0;
          const double cs[2] = {s0, s1}, ct[2] = {t0, t1};
          for (double s : cs)
            for (double t : ct) {
              double q[3];
              face_point(face, s, t, q);
              const double dot = std::min(1.0, c[0] * q[0] + c[1] * q[1] + c[2] * q[2]);
              rad = std::max(rad, std::acos(dot));
            }
          // Cube-map cells are bounded by great-circle arcs, so the farthest point is a corner.
          radius[j] = rad + 1e-6;
          max_radius = std::max(max_radius, radius[j]);
        }
  }
  int bin_of(const double e[3]) const {
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (std::fabs(e[d]) > std::fabs(e[axis])) axis = d;
    const double a = std::fabs(e[axis]);
    const int face = 2 * axis + (e[axis] < 0 ? 1 : 0);
    auto cell = [&](double x) {
      int i = static_cast<int>(std::floor((x / a + 1) * 0.5 * kCube));
      return std::min(kCube - 1, std::max(0, i));
    };
    return (face * kCube + cell(e[(axis + 1) % 3])) * kCube + cell(e[(axis + 2) % 3]);
  }
};

struct IceCream {
  double alpha = 0, rho = 0;
  const DirBins* bins = nullptr;
  std::array<double, kBins3> reach{};  // triangles with axis in the bin and r > reach are blocked
  double hmax = kInf;

  void reset() {
    reach.fill(kInf);
    hmax = kInf;
  }
  // w at distance delta in unit direction f lies in conv(u ∪ B(c, ρr)) when the angle beta
  // between f and the axis is < alpha and delta < r (cos beta + sqrt(rho^2 - sin^2 beta)).
  void insert(double delta, const double f[3]) {
    if (!(alpha > kTangentCut)) return;
    const double cut = std::cos(std::min(kPi, alpha + bins->max_radius));
    bool changed = false;
    for (std::size_t j = 0; j < static_cast<std::size_t>(kBins3); ++j) {
      const auto& b = bins->centre[j];
      const double dot = b[0] * f[0] + b[1] * f[1] + b[2] * f[2];
      if (dot < cut) continue;
      const double beta = std::acos(std::min(1.0, dot)) + bins->radius[j] + kAngleSlack;
      if (beta >= alpha - kTangentCut) continue;
      const double sb = std::sin(beta);
      const double tau = std::cos(beta) + std::sqrt(std::max(0.0, rho * rho - sb * sb));
      const double bound = delta / tau;
      if (bound < reach[j]) {
        reach[j] = bound;
        changed = true;
      }
    }
    if (changed) hmax = *std::max_element(reach.begin(), reach.end());
  }
};

// Rounds up to float (stored envelopes stay conservative).
float up_float(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// The blocking cone of the lens parameter m (shrunk by kShrink), over the direction bins.
IceCream make_ice_cream(double m, const DirBins& bins) {
  const double ms = std::max(-1.0, m - kShrink);
  const double big_r = 1.0 / (1.0 - std::fabs(ms));  // R / r
  IceCream ice;
  ice.bins = &bins;
  ice.rho = std::isfinite(big_r) ? big_r - std::sqrt(std::max(0.0, big_r * big_r - 1.0)) : 0.0;
  ice.alpha = std::asin(std::min(1.0, ice.rho));
  return ice;
}

Status lens_faces3(Ctx<3>& ctx, std::vector<FoundFace>& found) {
  const std::size_t n = ctx.ps->size();
  const DirBins bins;
  IceCream ice = make_ice_cream(ctx.m, bins);

  // Pass 1: per vertex, the envelope and the points within 2 * hmax (Lemma 7).
  std::vector<float> env(n * static_cast<std::size_t>(kBins3));
  std::vector<double> hmax(n);
  std::vector<std::size_t> kstart(n + 1, 0);
  std::vector<std::uint32_t> klist;
  std::vector<Entry<3>> heap;
  std::vector<std::pair<double, std::uint32_t>> near;
  double budget = 0;
  for (std::size_t ui = 0; ui < n; ++ui) {
    const auto u = static_cast<std::uint32_t>(ui);
    const double* pu = pt(ctx, ui);
    ice.reset();
    near.clear();
    auto limit2 = [&]() {
      const double l = 2 * ice.hmax * (1 + kRel);
      return l * l;
    };
    auto on_point = [&](std::uint32_t v, double key) {
      if (key > limit2()) return false;
      if (v == u) return true;
      const double* pv = pt(ctx, v);
      const double len = std::sqrt(key);
      const double f[3] = {(pv[0] - pu[0]) / len, (pv[1] - pu[1]) / len, (pv[2] - pu[2]) / len};
      ice.insert(len, f);
      near.emplace_back(key, v);
      return true;
    };
    auto prune = [&](const Entry<3>& e) { return e.key > limit2(); };
    best_first<3>(*ctx.tree, pu, heap, on_point, prune);
    hmax[ui] = ice.hmax;
    for (std::size_t j = 0; j < static_cast<std::size_t>(kBins3); ++j)
      env[ui * kBins3 + j] = up_float(ice.reach[j]);
    const double lim = limit2();
    kstart[ui] = klist.size();
    for (const auto& q : near)
      if (q.first <= lim) klist.push_back(q.second);
    std::sort(klist.begin() + static_cast<std::ptrdiff_t>(kstart[ui]), klist.end());
    const double k = static_cast<double>(klist.size() - kstart[ui]);
    budget += 0.5 * k * k;
    if (budget > kTriangleBudget * 4)
      return {StatusCode::Unsupported,
              "lens faces (3D): too many candidate triangles; the vertex cones prune little on this "
              "input (surface samples, or m far below 0); see docs/gamma-lens-graphs.md"};
  }
  kstart[n] = klist.size();

  // Pass 2: each triangle is enumerated once, from its vertex with the smallest (hmax, id);
  // both other vertices lie within 2 r <= 2 hmax(owner) of it.
  auto before = [&](std::uint32_t a, std::uint32_t b) {
    return hmax[a] < hmax[b] || (hmax[a] == hmax[b] && a < b);
  };
  std::vector<std::uint32_t> cand;
  double total = 0;  // the candidate triangles of the whole pass (as `examined` counts them)
  for (std::size_t ui = 0; ui < n; ++ui) {
    double c = 0;
    for (std::size_t k = kstart[ui]; k < kstart[ui + 1]; ++k) c += before(static_cast<std::uint32_t>(ui), klist[k]) ? 1 : 0;
    total += 0.5 * c * c;
  }
  double examined = 0;
  double share = kEstimateShare;  // the next estimate's share of the candidates
  // The vertices in blocks of kEstimateBlock, every kEstimateStride-th block first: each share of
  // the pass is then spread over the whole input (an estimate from the first vertices in input
  // order saw one region). The faces found do not depend on the order (sorted below), nor does
  // any decision but the estimate's.
  std::vector<std::uint32_t> order;
  order.reserve(n);
  const std::size_t blocks = (n + kEstimateBlock - 1) / kEstimateBlock;
  for (std::size_t s = 0; s < kEstimateStride; ++s)
    for (std::size_t b = s; b < blocks; b += kEstimateStride)
      for (std::size_t v = b * kEstimateBlock; v < std::min(n, (b + 1) * kEstimateBlock); ++v)
        order.push_back(static_cast<std::uint32_t>(v));
  for (const std::uint32_t u : order) {
    const std::size_t ui = u;
    if (examined >= share * total && examined > 0) {
      if (ctx.scanned / examined * total > kEstimateFactor * kScanBudget) return scan_budget_status(true);
      share *= 2;
    }
    cand.clear();
    for (std::size_t k = kstart[ui]; k < kstart[ui + 1]; ++k)
      if (before(u, klist[k])) cand.push_back(klist[k]);
    examined += 0.5 * static_cast<double>(cand.size()) * static_cast<double>(cand.size());
    if (examined > kTriangleBudget)
      return {StatusCode::Unsupported,
              "lens faces (3D): candidate triangle budget (4e8) exhausted; the vertex cones prune "
              "little on this input (surface samples, or m far below 0)"};
    const double lim = 2 * hmax[ui] * (1 + kRel);
    for (std::size_t a = 0; a < cand.size(); ++a) {
      const std::uint32_t v = cand[a];
      for (std::size_t b = a + 1; b < cand.size(); ++b) {
        const std::uint32_t w = cand[b];
        const double* pv = pt(ctx, v);
        const double* pw = pt(ctx, w);
        const double dx = pv[0] - pw[0], dy = pv[1] - pw[1], dz = pv[2] - pw[2];
        if (dx * dx + dy * dy + dz * dz > lim * lim) continue;
        int ids[3] = {static_cast<int>(u), static_cast<int>(v), static_cast<int>(w)};
        std::sort(ids, ids + 3);
        const double* p0 = pt(ctx, static_cast<std::size_t>(ids[0]));
        const double* p1 = pt(ctx, static_cast<std::size_t>(ids[1]));
        const double* p2 = pt(ctx, static_cast<std::size_t>(ids[2]));
        if (collinear3(p0, p1, p2)) continue;
        Sphere s;
        const double sin2 = sphere3(p0, p1, p2, s);
        if (sin2 > kSliverSin2 && usable(s, 3)) {
          // Well-shaped enough that the computed circumcentre direction is within kAngleSlack.
          bool pruned = false;
          for (int k = 0; k < 3 && !pruned; ++k) {
            const auto x = static_cast<std::size_t>(ids[k]);
            const double* px = pt(ctx, x);
            if (s.r > hmax[x] * (1 + kRel)) {
              pruned = true;
              break;
            }
            const double e[3] = {s.c[0] - px[0], s.c[1] - px[1], s.c[2] - px[2]};
            const int j = bins.bin_of(e);
            if (s.r > static_cast<double>(env[x * kBins3 + static_cast<std::size_t>(j)]) * (1 + kRel))
              pruned = true;
          }
          if (pruned) continue;
        }
        if (ctx.delaunay.count(face_key(ids, 3)) != 0) continue;
        double ga = 0, gb = 0;
        const bool member = evaluate_face(ctx, ids, ga, gb);
        if (ctx.over_budget()) return scan_budget_status();
        if (member) {
          found.push_back({{ids[0], ids[1], ids[2]}, ga, gb});
          if (found.size() > kMaxFaces)
            return {StatusCode::Unsupported,
                    "lens faces: more than 2e7 non-Delaunay faces for m = " + std::to_string(ctx.m) +
                        "; use a threshold closer to 0"};
        }
      }
    }
  }
  return Status::ok();
}

}  // namespace

Status lens_faces(const PointSet& points, double m, const GammaFaces& delaunay_faces,
                  GammaFaces& out, std::size_t* candidates_tested) {
  if (candidates_tested) *candidates_tested = 0;
  if (points.dim != 2 && points.dim != 3)
    return {StatusCode::InvalidArgument, "lens faces: dimension must be 2 or 3"};
  if (out.dim != points.dim || delaunay_faces.dim != points.dim)
    return {StatusCode::InvalidArgument, "lens faces: face lists and points differ in dimension"};
  if (!(m >= -1.0 && m < 0.0))
    return {StatusCode::InvalidArgument, "lens faces: threshold m must satisfy -1 <= m < 0"};
  const std::size_t n = points.size();
  if (n < static_cast<std::size_t>(points.dim)) return Status::ok();
  if (points.dim == 3 && n >= (std::size_t{1} << 21))
    return {StatusCode::Unsupported, "lens faces (3D): at most 2^21 points"};
  const double dn = static_cast<double>(n);
  const double subsets = points.dim == 2 ? dn * (dn - 1) / 2 : dn * (dn - 1) * (dn - 2) / 6;
  if (m <= -1.0 && subsets > kMaxSubsets) {
    char count[32];
    std::snprintf(count, sizeof count, "%.3g", subsets);
    return {StatusCode::Unsupported,
            std::string("the complete graph (gamma = -1, preset complete: every face that no point blocks) of these points "
                        "has ") + count + " candidate faces, more than 2e7: use fewer points, or a gamma above -1"};
  }

  std::vector<FoundFace> found;
  std::size_t tested = 0;
  if (points.dim == 2) {
    Ctx<2> ctx;
    if (Status s = setup(ctx, points, m, delaunay_faces); !s) return s;
    Status s = lens_faces2(ctx, found);
    tested = ctx.tested;
    if (!s) {
      if (candidates_tested) *candidates_tested = tested;
      return s;
    }
  } else {
    Ctx<3> ctx;
    if (Status s = setup(ctx, points, m, delaunay_faces); !s) return s;
    Status s = lens_faces3(ctx, found);
    tested = ctx.tested;
    if (!s) {
      if (candidates_tested) *candidates_tested = tested;
      return s;
    }
  }
  if (candidates_tested) *candidates_tested = tested;
  std::sort(found.begin(), found.end(),
            [](const FoundFace& a, const FoundFace& b) { return a.ids < b.ids; });
  out.reserve(out.size() + found.size());
  for (const auto& f : found) out.push_back(f.ids.data(), f.ga, f.gb, 0);
  return Status::ok();
}

}  // namespace constrict::detail
