// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "labels" of the 3D engine: inside/outside labels of the Delaunay tetrahedra by circumball
// propagation from the convex hull (docs/reconstruction-3d.md §4.6), and the point spacing.
#include <algorithm>
#include <cmath>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include "constrict/detail/stages3.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/fetch_ahead.hpp"
#include "core/detail/union_find.hpp"

namespace constrict::detail {
namespace {

// Quantisation of the confidence in [0, 1] for the bucket queue.
constexpr int kBuckets = 1024;
constexpr std::size_t kGrain = 4096;

using Ball = std::array<double, 4>;  // centre xyz, radius (radius < 0: flat)

// A hull tetrahedron whose circumradius exceeds kFlatHullRatio times its longest edge is nearly
// flat: its four points are coplanar up to rounding (exact columns and rings of points from a
// grid, as a marching-cubes mesh of a grid-aligned shape gives; a planar patch of the hull), so its
// ball is close to a half-space on either side of the face, and which side is decided by rounding.
// Seeding the propagation with it labels at full confidence in a random direction: on such a mesh
// of two capsules a flat hull tetrahedron seeded "inside", the label crossed the gap beside the
// tube and came back "outside" into it, and a quarter of the tube's cross-section was left out
// of the body. Such a tetrahedron seeds nothing (unless no other hull tetrahedron seeds); its
// neighbours label it.
constexpr double kFlatHullRatio = 64;

// The squared length of t's longest edge.
double longest_edge2(const Body3& b, std::size_t t) {
  const auto& v = b.tets[t];
  double e2 = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const double* p = b.P(v[uz(i)]);
      const double* q = b.P(v[uz(j)]);
      e2 = std::max(e2, (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    }
  return e2;
}

// A tetrahedron whose circumradius exceeds kCoplanarRatio times its longest edge has four points
// coplanar up to the rounding of their coordinates (its height is under a millionth of its size).
// The points of a flat face of a machined part, rotated in double precision, give thousands of
// them, a crust along the face (a rotated plate with a hole: 54 621 of 129 852 tetrahedra at 10^11
// or more; the shared models have none above 10^8). Each one's ball is a half-space on a side that
// rounding chose, and two of them pass a label to each other at confidence 1 (cos = +-1): a label
// that entered the crust anywhere ran along the whole face and into the part below it at full
// confidence. Two such tetrahedra pass no label to each other; each gets its label from its other
// neighbours. Nor has such a tetrahedron a radius (Labels3::lrad = kFlatLogRadius, as an exactly
// flat one): the growth takes the inside tetrahedra largest ball first and starts from the
// largest, and the crust's came first (an L-shaped bracket kept a tent across its notch).
constexpr double kCoplanarRatio = 1e6;
// ... and so is a tetrahedron six times whose volume is under kCoplanarVolume times the cube of its
// longest edge (a height of about 10^-12 of its size), whatever its computed radius: four points
// that are cocircular as well have no defined sphere, and rounding gives them any radius. Such are
// the corners of each square of a face sampled on a grid, then rotated: there the radius test
// missed the crust, and of 8 rotated boxes and plates with a hole the plates lost their hole and
// lay 2.6-5.0 median edges off; with this test 7 of 8 are right and within 0.4 edges.
constexpr double kCoplanarVolume = 1e-12;

// The growth takes the inside tetrahedra largest ball first (from the medial axis outwards). Points
// that are cospherical (a torus or any surface of revolution sampled on a grid of its parameters:
// two neighbouring rings of points lie on one sphere) give a cell of many tetrahedra with one ball,
// any tetrahedralization of which is Delaunay; their radii differ by rounding only (10^-13 on a grid
// torus), and in that order the growth locked on the cell's tetrahedra whose points it had already
// reached from elsewhere: a grid torus kept 5 900 inside tetrahedra (a third of its volume) out of
// the body, 104 points unreached, 566 faces across its tube. Among balls equal to within
// kDepthTie (relative), the tetrahedra nearer the ball's centre go first (depth: the distance of
// the centroid from the centre over the radius, in [0, 1)); then the torus grows whole (its one
// cut left), and the opposite order leaves two thirds of it out.
constexpr double kDepthTie = 1e-9;
double depth(const Body3& b, std::size_t t, const Ball& ball) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double c = 0.25 * (b.P(b.tets[t][0])[k] + b.P(b.tets[t][1])[k] + b.P(b.tets[t][2])[k] + b.P(b.tets[t][3])[k]);
    d2 += (c - ball[uz(k)]) * (c - ball[uz(k)]);
  }
  return std::min(1.0, std::sqrt(d2) / ball[3]);
}

// Four points coplanar up to rounding that lie on one circle too (up to kCocircularTol of the
// longest edge's fourth power in the in-circle determinant of their projection on the plane).
constexpr double kCocircularTol = 1e-9;
bool cocircular(const Body3& b, std::size_t t, double longest2) {
  const auto& v = b.tets[t];
  const double* a = b.P(v[0]);
  double e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) e[i][k] = b.P(v[uz(i + 1)])[k] - a[k];
  // The plane's normal: the largest cross product of two edges from a.
  double nrm[3] = {0, 0, 0}, best = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      const double c[3] = {e[i][1] * e[j][2] - e[i][2] * e[j][1], e[i][2] * e[j][0] - e[i][0] * e[j][2], e[i][0] * e[j][1] - e[i][1] * e[j][0]};
      const double l = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
      if (l > best) best = l, nrm[0] = c[0], nrm[1] = c[1], nrm[2] = c[2];
    }
  if (!(best > 0)) return true;
  // An orthonormal basis (u, w) of the plane.
  const double ln = std::sqrt(best);
  const double n0 = nrm[0] / ln, n1 = nrm[1] / ln, n2 = nrm[2] / ln;
  double u[3] = {e[0][0], e[0][1], e[0][2]};
  const double un = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  if (!(un > 0)) return true;
  for (double& x : u) x /= un;
  const double w[3] = {n1 * u[2] - n2 * u[1], n2 * u[0] - n0 * u[2], n0 * u[1] - n1 * u[0]};
  double px[3], py[3];
  for (int i = 0; i < 3; ++i) {
    px[i] = e[i][0] * u[0] + e[i][1] * u[1] + e[i][2] * u[2];
    py[i] = e[i][0] * w[0] + e[i][1] * w[1] + e[i][2] * w[2];
  }
  // In-circle of (0, 0), p0, p1, p2.
  const double det = px[0] * (py[1] * (px[2] * px[2] + py[2] * py[2]) - py[2] * (px[1] * px[1] + py[1] * py[1])) -
                     py[0] * (px[1] * (px[2] * px[2] + py[2] * py[2]) - px[2] * (px[1] * px[1] + py[1] * py[1])) +
                     (px[0] * px[0] + py[0] * py[0]) * (px[1] * py[2] - px[2] * py[1]);
  return std::fabs(det) <= kCocircularTol * longest2 * longest2;
}

// Flags of a tetrahedron (circumballs).
constexpr char kFlatHull = 1;  // on the convex hull and nearly flat (kFlatHullRatio)
constexpr char kCoplanar = 2;  // coplanar up to rounding (kCoplanarRatio, kCoplanarVolume)
constexpr char kSeam = 4;      // exactly flat (no ball): a seam (Through below)
constexpr char kThrough = 8;   // passes labels on through a seam (Through entries)
constexpr char kFlat = kSeam | kCoplanar;
constexpr char kCocircular = 16;  // coplanar up to rounding and cocircular too (cocircular())

// The circumballs, and each tetrahedron's flags.
BigArray<Ball> circumballs(const Body3& b, std::vector<char>& flags) {
  BigArray<Ball> ball;
  ball.allocate(b.T0);  // (every entry written below, on both cores: not zero-filled first)
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.T0, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      fetch_ahead(b.tets, t, r.end(), [&](int x) { __builtin_prefetch(b.P(x)); });
      const auto& v = b.tets[t];
      const double* a = b.P(v[0]);
      double e1[3], e2[3], e3[3];
      for (int k = 0; k < 3; ++k) {
        e1[k] = b.P(v[1])[k] - a[k];
        e2[k] = b.P(v[2])[k] - a[k];
        e3[k] = b.P(v[3])[k] - a[k];
      }
      const double cd[3] = {e2[1] * e3[2] - e2[2] * e3[1], e2[2] * e3[0] - e2[0] * e3[2], e2[0] * e3[1] - e2[1] * e3[0]};
      const double db[3] = {e3[1] * e1[2] - e3[2] * e1[1], e3[2] * e1[0] - e3[0] * e1[2], e3[0] * e1[1] - e3[1] * e1[0]};
      const double bc[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
      const double den = 2 * (e1[0] * cd[0] + e1[1] * cd[1] + e1[2] * cd[2]);
      const double nb = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2], nc = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2],
                   nd = e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2];
      Ball o{{0, 0, 0, -1}};
      if (den != 0 && std::isfinite(den)) {
        double x[3];
        for (int k = 0; k < 3; ++k) x[k] = (nb * cd[k] + nc * db[k] + nd * bc[k]) / den;
        const double rr = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (std::isfinite(rr)) o = {{a[0] + x[0], a[1] + x[1], a[2] + x[2], rr}};
      }
      ball[t] = o;
      char f = 0;
      if (o[3] > 0) {
        const double longest2 = longest_edge2(b, t), longest = std::sqrt(longest2);
        // (den = 2 e1 . (e2 x e3), twelve times the volume.)
        if (o[3] > kCoplanarRatio * longest || std::fabs(den) < 2 * kCoplanarVolume * longest2 * longest) {
          f |= kCoplanar;
          if (cocircular(b, t, longest2)) f |= kCocircular;
        }
        const auto& nt = b.nbr[t];
        const bool hull = nt[0] < 0 || nt[1] < 0 || nt[2] < 0 || nt[3] < 0;
        if (hull && o[3] > kFlatHullRatio * longest) f |= kFlatHull;
      }
      if (!(o[3] > 0)) f |= kSeam;
      flags[t] = f;
    }
  });
  return ball;
}

// The unnormalised outward normal of face i of t (kFaceOut order).
std::array<double, 3> face_normal(const Body3& b, std::size_t t, int i) {
  const auto& v = b.tets[t];
  const double* p0 = b.P(v[uz(kFaceOut[i][0])]);
  const double* p1 = b.P(v[uz(kFaceOut[i][1])]);
  const double* p2 = b.P(v[uz(kFaceOut[i][2])]);
  const double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double w[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  return {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
}

// Cosine of the angle between the outer half-space of the hull face opposite i of t and t's
// circumball: the signed distance of the centre beyond the face over the radius (NaN if flat).
// The cosine of the ball with the outer half-space of a plane through p0 with normal nrm, outer
// being the side away from the reference whose signed offset along nrm is `inner` (NaN when the
// normal vanishes): the signed distance of the centre beyond the plane over the radius.
double half_space_cos(const double* p0, const std::array<double, 3>& nrm, double inner, const Ball& ball) {
  const double ln = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
  if (!(ln > 0)) return NAN;
  const double sgn = inner > 0 ? -1.0 : 1.0;  // flip so that nrm points away from the reference
  const double dist =
      sgn * (nrm[0] * (ball[0] - p0[0]) + nrm[1] * (ball[1] - p0[1]) + nrm[2] * (ball[2] - p0[2])) / ln;
  return dist / ball[3];
}

double hull_face_cos(const Body3& b, std::size_t t, int i, const Ball& ball) {
  const auto& v = b.tets[t];
  const double* p0 = b.P(v[uz(kFaceOut[i][0])]);
  const auto nrm = face_normal(b, t, i);
  const double* ap = b.P(v[uz(i)]);  // the reference: the apex
  return half_space_cos(p0, nrm, nrm[0] * (ap[0] - p0[0]) + nrm[1] * (ap[1] - p0[1]) + nrm[2] * (ap[2] - p0[2]), ball);
}

// Flat tetrahedra. Points on a grid of a surface of revolution (a torus or a vase sampled on a
// grid of its parameters: every ring of points cocircular and coplanar, every grid square an
// isosceles trapezoid, cocircular and coplanar) and machined faces sampled on a grid give whole
// sets of tetrahedra with no volume: across the solid, one disc per ring; on the surface, one per
// grid square. An exactly flat one has no ball and passed nothing: the slabs between a vase's rings
// got their labels at random, and the growth left a wall across the vase at each ring (a grid vase:
// 15.4 of its 19.5 units of area were faces across its inside). One coplanar up to rounding has a
// ball that is a half-space on a side rounding chose, and its cosines are as random.
// So (docs/reconstruction-3d.md §4.10):
// - an exactly flat tetrahedron (a seam) passes labels *through* itself: from a tetrahedron on one
//   side to those on its other side (through several seams when they are stacked), with the cosine
//   of their two balls; a hull face beyond a seam seeds the tetrahedron before it;
// - those cosines, and the cosines to or from a tetrahedron coplanar up to rounding whose four
//   points are cocircular too (no ball at all: a grid square, a ring's disc), count kWeakPass times
//   less: they decide only where no other path reaches. Where balls pass through one circle, on
//   both sides of a grid square or of a ring's disc, they meet at a cosine near 1 whether the
//   square is a wall or the disc lies across the solid: at full weight grid-faced plates lost their
//   holes, and weakening every coplanar tetrahedron (blue-noise flat faces too, whose huge balls
//   are half-spaces) gave a near-touching pair of boxes a false handle;
// - afterwards a connected set of flat tetrahedra that lies between tetrahedra labelled inside only
//   (no hull face, no other neighbour) is inside too (a disc across the solid), with the radius of
//   the largest inside ball beside it (label_flat_sets).
constexpr double kWeakPass = 1.0 / 1024;  // below the bucket queue's first bucket
struct Through {
  std::uint32_t from;  // the tetrahedron that passes the label on
  std::uint32_t to;    // the one it reaches through a seam
  float code;          // LabelQueue::encode of the cosine of their balls
};
constexpr std::size_t kMaxSeamWalk = 64;  // seams visited per face (a bound on pathological stacks)

// The index of t among m's neighbours.
int back_index(const Body3& b, int m, int t) {
  for (int k = 0; k < 4; ++k)
    if (b.nbr[uz(m)][uz(k)] == t) return k;
  return -1;
}

// Bucket queue over the confidence quantised to 1/kBuckets (a binary heap of the ~4 pushes per
// tetrahedron costs more than the rest); LIFO inside a bucket, all sequential, so the labels are
// deterministic.
class LabelQueue {
 public:
  struct Item {
    int tet;
    float label;  // the label it gets: lab * confidence (sign bit: inside)
  };
  explicit LabelQueue(std::size_t T0) : bucket_(kBuckets + 1), best_b_(T0, -1) {}
  // A cosine as the queue uses it, in one float: NaN (nothing passed on), else the confidence
  // float(|cos|) with the sign bit set when the label flips (cos < 0).
  static float encode(double cosv) {
    if (!(cosv == cosv)) return NAN;
    const double c = std::max(-1.0, std::min(1.0, cosv));
    const float conf = static_cast<float>(std::abs(c));
    return c >= 0 ? conf : -conf;
  }
  // A label passed on from a tetrahedron labelled lab_from (+1 / -1), through a cosine coded by
  // encode(). Ignored once t is done; true when pushed.
  bool push_coded(int t, float code, int lab_from) {
    if (!(code == code)) return false;
    const float conf = std::abs(code);
    const int bk = static_cast<int>(conf * kBuckets);
    // A push into a lower bucket than a pending entry of the same tetrahedron could only pop
    // after that entry has labelled it (then it is skipped as done): not pushed, same labels.
    if (bk < best_b_[uz(t)]) return false;
    best_b_[uz(t)] = static_cast<std::int16_t>(bk);
    const int lab = std::signbit(code) ? -lab_from : lab_from;
    bucket_[uz(bk)].push({t, lab < 0 ? -conf : conf});
    top_ = std::max(top_, bk);
    return true;
  }
  bool pop(Item& out) {
    while (top_ >= 0 && bucket_[uz(top_)].empty()) --top_;
    if (top_ < 0) return false;
    out = bucket_[uz(top_)].pop();
    return true;
  }
  // The tetrahedron of the next pop if no push comes first, or -1 (a guess for prefetching).
  int next_guess() const { return top_ >= 0 && !bucket_[uz(top_)].empty() ? bucket_[uz(top_)].back().tet : -1; }
  const std::int16_t* mark_of(int t) const { return &best_b_[uz(t)]; }
  // A labelled tetrahedron takes no more pushes (its mark is above every bucket).
  bool done(int t) const { return best_b_[uz(t)] == kDone; }
  void mark_done(int t) { best_b_[uz(t)] = kDone; }

 private:
  static constexpr std::int16_t kDone = kBuckets + 1;
  // A bucket: a stack whose push is inline (std::vector's was an out-of-line call per push, 15 %
  // of the propagation on the 10^6 star).
  class Stack {
   public:
    bool empty() const { return size_ == 0; }
    const Item& back() const { return data_[size_ - 1]; }
    Item pop() { return data_[--size_]; }
    void push(const Item& x) {
      if (size_ == data_.size()) grow();
      data_[size_++] = x;
    }

   private:
    [[gnu::noinline]] void grow() { data_.resize(std::max<std::size_t>(64, 2 * data_.size())); }
    std::vector<Item> data_;
    std::size_t size_ = 0;
  };
  std::vector<Stack> bucket_;
  std::vector<std::int16_t> best_b_;
  int top_ = -1;
};

// Calls found(f, k, normal of face k of f) for each face k through which a walk from t into the
// seam m0 leaves the seams on their other side: the faces of a seam whose outward normals point
// against that of the face it was entered by; a neighbour across such a face that is a seam too is
// walked into (at most kMaxSeamWalk seams).
template <class Found>
void seams_beyond(const Body3& b, const std::vector<char>& flags, int t, int m0, std::vector<std::pair<int, int>>& stack,
                  std::vector<int>& seen, const Found& found) {
  stack.assign(1, {m0, back_index(b, m0, t)});
  seen.assign(1, m0);
  while (!stack.empty()) {
    const auto [f, j] = stack.back();
    stack.pop_back();
    if (j < 0) continue;
    const auto nj = face_normal(b, uz(f), j);
    for (int k = 0; k < 4; ++k) {
      if (k == j) continue;
      const auto nk = face_normal(b, uz(f), k);
      if (!(nk[0] * nj[0] + nk[1] * nj[1] + nk[2] * nj[2] < 0)) continue;  // not across
      const int n = b.nbr[uz(f)][uz(k)];
      if (n >= 0 && uz(n) >= b.T0) continue;
      if (n >= 0 && (flags[uz(n)] & kSeam)) {
        if (seen.size() < kMaxSeamWalk && std::find(seen.begin(), seen.end(), n) == seen.end()) {
          seen.push_back(n);
          stack.push_back({n, back_index(b, n, f)});
        }
      } else {
        found(f, k, nk);
      }
    }
  }
}

// The cosine of t's ball with the outer half-space of the hull face k of the seam f (normal nk):
// the signed distance of the centre beyond the face (away from t's points) over the radius.
double beyond_hull_cos(const Body3& b, std::size_t t, int f, int k, const std::array<double, 3>& nk, const Ball& ball) {
  const double* p0 = b.P(b.tets[uz(f)][uz(kFaceOut[k][0])]);
  double side = 0;  // the reference: t's points
  for (int v : b.tets[t]) side += nk[0] * (b.P(v)[0] - p0[0]) + nk[1] * (b.P(v)[1] - p0[1]) + nk[2] * (b.P(v)[2] - p0[2]);
  return half_space_cos(p0, nk, side, ball);
}

// A connected set of flat tetrahedra (joined across their shared faces) with no hull face, whose
// other neighbours are all labelled inside, is inside (a ring's disc across a solid); the others
// keep their labels (a grid square on the surface). An inside flat tetrahedron joins the growth with
// the largest inside ball beside it (or beside its set), just after that tetrahedron: last of all,
// the growth went past a ring's disc before it had crossed the whole disc, and the rest of the disc
// stayed a wall. Never the seed (its radius is just below a neighbour's).
void label_flat_sets(const Body3& b, const std::vector<char>& flags, Labels3& out) {
  const std::size_t T0 = b.T0;
  std::vector<int> flat;
  for (std::size_t t = 0; t < T0; ++t)
    if (flags[t] & kFlat) flat.push_back(static_cast<int>(t));
  if (flat.empty()) return;
  const auto index = [&](int t) {
    return static_cast<int>(std::lower_bound(flat.begin(), flat.end(), t) - flat.begin());
  };
  const auto is_flat = [&](int m) { return m >= 0 && uz(m) < T0 && (flags[uz(m)] & kFlat); };
  UnionFind uf(flat.size());
  for (std::size_t k = 0; k < flat.size(); ++k)
    for (int m : b.nbr[uz(flat[k])])
      if (is_flat(m)) uf.join(static_cast<int>(k), index(m));
  std::vector<double> sum(flat.size(), 0.0), set_lrad(flat.size(), kFlatLogRadius);
  std::vector<int> count(flat.size(), 0);
  std::vector<char> not_inside(flat.size(), 0);
  for (std::size_t k = 0; k < flat.size(); ++k) {
    const auto r = uz(uf.find(static_cast<int>(k)));
    for (int m : b.nbr[uz(flat[k])]) {
      if (is_flat(m)) continue;
      if (m < 0 || uz(m) >= T0 || !(out.label[uz(m)] < 0)) {
        not_inside[r] = 1;
        continue;
      }
      sum[r] += out.label[uz(m)];
      ++count[r];
      set_lrad[r] = std::max(set_lrad[r], out.lrad[uz(m)]);
    }
  }
  for (std::size_t k = 0; k < flat.size(); ++k) {
    const auto r = uz(uf.find(static_cast<int>(k)));
    if (not_inside[r] || count[r] == 0) continue;
    const int t = flat[k];
    out.label[uz(t)] = static_cast<float>(sum[r] / count[r]);
    double own = kFlatLogRadius;
    for (int m : b.nbr[uz(t)])
      if (!is_flat(m) && m >= 0 && uz(m) < T0) own = std::max(own, out.lrad[uz(m)]);
    if (!(own > kFlatLogRadius)) own = set_lrad[r];
    if (own > kFlatLogRadius) out.lrad[uz(t)] = std::nextafter(own, -HUGE_VAL);
  }
}

}  // namespace

// The outer half-space of a hull face and the circumball of its tetrahedron meet at an angle
// whose cosine is hull_face_cos; two adjacent circumballs meet at cos = (r1² + r2² - d²) /
// (2 r1 r2). A deep intersection (cos > 0) passes the label on, a shallow one (cos < 0) the
// opposite label, with confidence |cos|; the most confident assignments are made first, each
// tetrahedron once.
std::shared_ptr<const Labels3> compute_labels3(const Body3& b, const std::function<void()>& beside) {
  const std::size_t T0 = b.T0;
  auto out = std::make_shared<Labels3>();
  LabelQueue q(T0);
  // The cosine passed on through each face, from t to its neighbour (the same expression in the
  // same order as the propagation would evaluate it; at a hull face the cosine with the outer
  // half-space), computed in parallel beforehand: the sequential propagation then reads only the
  // tetrahedron it pops, not its neighbours' balls.
  BigArray<std::array<float, 4>> pass;  // (every entry written below, in parallel: not zero-filled)
  pass.allocate(T0);
  std::vector<char> flags(T0);  // kFlatHull, kCoplanar, kSeam, kThrough
  // Passes through seams (sorted by `from`), and the hull faces beyond seams (`to` unused).
  std::vector<Through> through, hull_seeds;
  std::atomic<bool> any_flat{false};  // (label_flat_sets has nothing to do without one)
  {
    const BigArray<Ball> ball = circumballs(b, flags);
    const auto cosine = [](const Ball& x, const Ball& y) {
      const double dx = x[0] - y[0], dy = x[1] - y[1], dz = x[2] - y[2];
      return (x[3] * x[3] + y[3] * y[3] - (dx * dx + dy * dy + dz * dz)) / (2 * x[3] * y[3]);
    };
    out->lrad.resize(T0);
    std::atomic<bool> any_seam{false};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T0, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
      bool seam_here = false, flat_here = false;
      for (std::size_t t = r.begin(); t != r.end(); ++t) {
        // The neighbours' balls and flags lie anywhere in their arrays (half of this loop's time
        // was the first load of a neighbour's ball): fetched a few tetrahedra before.
        fetch_ahead(b.nbr, t, r.end(), [&](int m) {
          if (m < 0 || uz(m) >= T0) return;
          __builtin_prefetch(&ball[uz(m)][0]);
          __builtin_prefetch(&ball[uz(m)][3]);
          __builtin_prefetch(&flags[uz(m)]);
        });
        const Ball& bt = ball[t];
        seam_here = seam_here || (flags[t] & kSeam);
        flat_here = flat_here || (flags[t] & kFlat);
        out->lrad[t] = bt[3] > 0 && !(flags[t] & kCoplanar) ? std::log(bt[3]) - kDepthTie * depth(b, t, bt) : kFlatLogRadius;
        for (int i = 0; i < 4; ++i) {
          const int m = b.nbr[t][uz(i)];
          float code = NAN;
          if (m < 0) {  // a hull face: the cosine with the outer half-space, pushed below
            if (bt[3] > 0) code = LabelQueue::encode(hull_face_cos(b, t, i, bt));
          } else if (uz(m) < T0 && bt[3] > 0 && ball[uz(m)][3] > 0 && !(flags[t] & flags[uz(m)] & kCoplanar)) {
            const double weight = (flags[t] | flags[uz(m)]) & kCocircular ? kWeakPass : 1.0;
            code = LabelQueue::encode(weight * cosine(bt, ball[uz(m)]));
          }
          pass[t][uz(i)] = code;
        }
      }
      if (seam_here) any_seam.store(true, std::memory_order_relaxed);
      if (flat_here) any_flat.store(true, std::memory_order_relaxed);
    });
    if (any_seam.load()) {
      // For each tetrahedron beside a seam, the tetrahedra (and hull faces) on the seam's other
      // side: a walk through stacked seams, each entered through one face and left through the
      // faces whose outward normals point the other way. Per block of tetrahedra, then joined in
      // block order (sorted by `from`, whatever the thread count).
      struct Found {
        std::vector<Through> through, hull;
      };
      const std::size_t blocks = (T0 + kGrain - 1) / kGrain;
      std::vector<Found> found(blocks);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<std::pair<int, int>> stack;
        std::vector<int> seen;
        for (std::size_t blk = r.begin(); blk != r.end(); ++blk)
          for (std::size_t t = blk * kGrain; t < std::min(T0, (blk + 1) * kGrain); ++t) {
            if (!(ball[t][3] > 0)) continue;
            for (int i = 0; i < 4; ++i) {
              const int m0 = b.nbr[t][uz(i)];
              if (m0 < 0 || uz(m0) >= T0 || !(flags[uz(m0)] & kSeam)) continue;
              seams_beyond(b, flags, static_cast<int>(t), m0, stack, seen, [&](int f, int k, const std::array<double, 3>& nk) {
                const int n = b.nbr[uz(f)][uz(k)];
                if (n < 0) {
                  const float code = LabelQueue::encode(kWeakPass * beyond_hull_cos(b, t, f, k, nk, ball[t]));
                  if (code == code) found[blk].hull.push_back({static_cast<std::uint32_t>(t), 0, code});
                } else if (uz(n) != t && ball[uz(n)][3] > 0) {
                  const float code = LabelQueue::encode(kWeakPass * cosine(ball[t], ball[uz(n)]));
                  if (code == code) found[blk].through.push_back({static_cast<std::uint32_t>(t), static_cast<std::uint32_t>(n), code});
                }
              });
            }
          }
      });
      for (Found& fd : found) {
        through.insert(through.end(), fd.through.begin(), fd.through.end());
        hull_seeds.insert(hull_seeds.end(), fd.hull.begin(), fd.hull.end());
      }
      for (const Through& e : through) flags[e.from] |= kThrough;
    }
  }
  // The hull's seeds (and those beyond seams), without the nearly flat tetrahedra; with them when
  // there is no other (a hull of points coplanar up to rounding).
  bool seeded = false;
  for (int with_flat = 0; with_flat < 2 && !seeded; ++with_flat) {
    for (std::size_t t = 0; t < T0; ++t)
      for (int i = 0; i < 4; ++i)
        if (b.nbr[t][uz(i)] < 0 && (with_flat || !(flags[t] & kFlatHull)) && pass[t][uz(i)] == pass[t][uz(i)]) {
          q.push_coded(static_cast<int>(t), pass[t][uz(i)], +1);
          seeded = true;
        }
    if (with_flat == 0)
      for (const Through& h : hull_seeds) {
        q.push_coded(static_cast<int>(h.from), h.code, +1);
        seeded = true;
      }
  }
  out->label.assign(T0, 0.0f);
  // The propagation below runs on one core: the caller's work that does not read the labels runs
  // on the other one meanwhile (its results cannot depend on the order: it shares nothing with
  // this loop).
  tbb::task_group beside_task;
  if (beside) beside_task.run([&beside] { beside(); });
  LabelQueue::Item it{};
  while (q.pop(it)) {
    // The pops read the tetrahedra in label order, at random: the likely next one is fetched
    // while this one is handled.
    if (const int nx = q.next_guess(); nx >= 0) {
      __builtin_prefetch(q.mark_of(nx));
      __builtin_prefetch(&pass[uz(nx)]);
      __builtin_prefetch(&b.nbr[uz(nx)]);
      __builtin_prefetch(&out->label[uz(nx)], 1);
    }
    if (q.done(it.tet)) continue;
    q.mark_done(it.tet);
    out->label[uz(it.tet)] = it.label;
    const int lab = std::signbit(it.label) ? -1 : 1;
    const auto& code = pass[uz(it.tet)];
    for (int i = 0; i < 4; ++i) {
      const int m = b.nbr[uz(it.tet)][uz(i)];
      // A pushed tetrahedron is fetched now: the pushes of the top bucket pop next (last in,
      // first out), and their records were the loop's misses (0.85 -> 0.75 s on the 10⁶ star).
      if (m >= 0 && uz(m) < T0 && q.push_coded(m, code[uz(i)], lab)) {
        __builtin_prefetch(&b.nbr[uz(m)]);
        __builtin_prefetch(&pass[uz(m)]);
      }
    }
    if (flags[uz(it.tet)] & kThrough) {
      const auto from = static_cast<std::uint32_t>(it.tet);
      auto e = std::lower_bound(through.begin(), through.end(), from, [](const Through& x, std::uint32_t f) { return x.from < f; });
      for (; e != through.end() && e->from == from; ++e) q.push_coded(static_cast<int>(e->to), e->code, lab);
    }
  }
  beside_task.wait();
  if (any_flat.load()) label_flat_sets(b, flags, *out);
  return out;
}

// The bits of a non-negative double: ordered as the doubles are.
static std::uint64_t bits_of(double d) {
  std::uint64_t u;
  std::memcpy(&u, &d, sizeof u);
  return u;
}

std::vector<double> nearest_spacing3(const Body3& b) {
  // The smallest squared length per point, then one square root: the root is monotone and
  // correctly rounded, so this is the minimum of the edges' lengths, bit for bit. In parallel
  // over the tetrahedra: a minimum does not depend on the order, and a non-negative double orders
  // as its bits do, so each point's minimum is kept by a compare-and-swap on the bits.
  std::unique_ptr<std::atomic<std::uint64_t>[]> best(new std::atomic<std::uint64_t>[b.n]);
  const std::uint64_t inf_bits = bits_of(HUGE_VAL);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.n, std::size_t{1} << 16),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v != r.end(); ++v)
                        best[v].store(inf_bits, std::memory_order_relaxed);
                    });
  const auto lower = [&](int x, std::uint64_t l) {
    std::atomic<std::uint64_t>& a = best[uz(x)];
    std::uint64_t cur = a.load(std::memory_order_relaxed);
    while (l < cur && !a.compare_exchange_weak(cur, l, std::memory_order_relaxed)) {}
  };
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, b.T0, std::size_t{1} << 14), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
          const auto& v = b.tets[t];
          for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
              const int x = v[uz(i)], y = v[uz(j)];
              const double dx = b.P(x)[0] - b.P(y)[0], dy = b.P(x)[1] - b.P(y)[1], dz = b.P(x)[2] - b.P(y)[2];
              const std::uint64_t l = bits_of(dx * dx + dy * dy + dz * dz);
              lower(x, l);
              lower(y, l);
            }
        }
      });
  std::vector<double> spacing(b.n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.n, std::size_t{1} << 16),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v != r.end(); ++v) {
                        const std::uint64_t l = best[v].load(std::memory_order_relaxed);
                        double d;
                        std::memcpy(&d, &l, sizeof d);
                        spacing[v] = std::sqrt(d);
                      }
                    });
  return spacing;
}

}  // namespace constrict::detail
