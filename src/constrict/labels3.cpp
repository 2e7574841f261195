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

// Flags of a tetrahedron (circumballs).
constexpr char kFlatHull = 1;  // on the convex hull and nearly flat (kFlatHullRatio)
constexpr char kCoplanar = 2;  // coplanar up to rounding (kCoplanarRatio, kCoplanarVolume)

// The circumballs, and each tetrahedron's flags.
std::vector<Ball> circumballs(const Body3& b, std::vector<char>& flags) {
  std::vector<Ball> ball(b.T0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.T0, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
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
        if (o[3] > kCoplanarRatio * longest || std::fabs(den) < 2 * kCoplanarVolume * longest2 * longest) f |= kCoplanar;
        const auto& nt = b.nbr[t];
        const bool hull = nt[0] < 0 || nt[1] < 0 || nt[2] < 0 || nt[3] < 0;
        if (hull && o[3] > kFlatHullRatio * longest) f |= kFlatHull;
      }
      flags[t] = f;
    }
  });
  return ball;
}

// Cosine of the angle between the outer half-space of the hull face opposite i of t and t's
// circumball: the signed distance of the centre beyond the face over the radius (NaN if flat).
double hull_face_cos(const Body3& b, std::size_t t, int i, const Ball& ball) {
  const auto& v = b.tets[t];
  const double* p0 = b.P(v[uz(kFaceOut[i][0])]);
  const double* p1 = b.P(v[uz(kFaceOut[i][1])]);
  const double* p2 = b.P(v[uz(kFaceOut[i][2])]);
  const double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double w[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  const double nrm[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  const double ln = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
  if (!(ln > 0)) return NAN;
  const double* ap = b.P(v[uz(i)]);
  const double side = nrm[0] * (ap[0] - p0[0]) + nrm[1] * (ap[1] - p0[1]) + nrm[2] * (ap[2] - p0[2]);
  const double sgn = side > 0 ? -1.0 : 1.0;  // flip so that nrm points away from the apex
  const double dist =
      sgn * (nrm[0] * (ball[0] - p0[0]) + nrm[1] * (ball[1] - p0[1]) + nrm[2] * (ball[2] - p0[2])) / ln;
  return dist / ball[3];
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
  // encode(). Ignored once t is done.
  void push_coded(int t, float code, int lab_from) {
    if (!(code == code)) return;
    const float conf = std::abs(code);
    const int bk = static_cast<int>(conf * kBuckets);
    // A push into a lower bucket than a pending entry of the same tetrahedron could only pop
    // after that entry has labelled it (then it is skipped as done): not pushed, same labels.
    if (bk < best_b_[uz(t)]) return;
    best_b_[uz(t)] = static_cast<std::int16_t>(bk);
    const int lab = std::signbit(code) ? -lab_from : lab_from;
    bucket_[uz(bk)].push_back({t, lab < 0 ? -conf : conf});
    top_ = std::max(top_, bk);
  }
  bool pop(Item& out) {
    while (top_ >= 0 && bucket_[uz(top_)].empty()) --top_;
    if (top_ < 0) return false;
    out = bucket_[uz(top_)].back();
    bucket_[uz(top_)].pop_back();
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
  std::vector<std::vector<Item>> bucket_;
  std::vector<std::int16_t> best_b_;
  int top_ = -1;
};

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
  std::vector<std::array<float, 4>> pass(T0);
  std::vector<char> flags(T0);  // kFlatHull, kCoplanar
  {
    const std::vector<Ball> ball = circumballs(b, flags);
    out->lrad.resize(T0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T0, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t) {
        const Ball& bt = ball[t];
        out->lrad[t] = bt[3] > 0 && !(flags[t] & kCoplanar) ? std::log(bt[3]) : kFlatLogRadius;
        for (int i = 0; i < 4; ++i) {
          const int m = b.nbr[t][uz(i)];
          float code = NAN;
          if (m < 0) {  // a hull face: the cosine with the outer half-space, pushed below
            if (bt[3] > 0) code = LabelQueue::encode(hull_face_cos(b, t, i, bt));
          } else if (uz(m) < T0 && bt[3] > 0 && ball[uz(m)][3] > 0 &&
                     !(flags[t] & flags[uz(m)] & kCoplanar)) {
            const Ball& bm = ball[uz(m)];
            const double dx = bt[0] - bm[0], dy = bt[1] - bm[1], dz = bt[2] - bm[2];
            const double d2 = dx * dx + dy * dy + dz * dz;
            code = LabelQueue::encode((bt[3] * bt[3] + bm[3] * bm[3] - d2) / (2 * bt[3] * bm[3]));
          }
          pass[t][uz(i)] = code;
        }
      }
    });
  }
  // The hull's seeds, without the nearly flat tetrahedra; with them when there is no other (a
  // hull of points coplanar up to rounding).
  bool seeded = false;
  for (int with_flat = 0; with_flat < 2 && !seeded; ++with_flat)
    for (std::size_t t = 0; t < T0; ++t)
      for (int i = 0; i < 4; ++i)
        if (b.nbr[t][uz(i)] < 0 && (with_flat || !(flags[t] & kFlatHull)) && pass[t][uz(i)] == pass[t][uz(i)]) {
          q.push_coded(static_cast<int>(t), pass[t][uz(i)], +1);
          seeded = true;
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
      if (m >= 0 && uz(m) < T0) q.push_coded(m, code[uz(i)], lab);
    }
  }
  beside_task.wait();
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
