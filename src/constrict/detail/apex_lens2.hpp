// SPDX-License-Identifier: GPL-3.0-or-later
// Where the points with a small apex value lie, for the 2D fallback's side searches
// (fallback2.cpp, sides_below). A point p sees segment ab under the angle θ = ∠apb; its apex
// value (spec §2.1) is below t < 0 iff θ > π - α with α = asin(1 + t). On each side of ab those
// points lie under a circular arc through a and b that meets the segment at the angle α and rises
// to (|ab| / 2) tan(α / 2) over its midpoint (a lens, thin at the segment's ends); the arc is
// convex, so it lies in the polygon of its tangents (cover(): kCoverTangents of them, from one
// end to the other). A search reads the grid cells of that polygon (cut at a height, for the
// layers of a search that starts near the segment) and tests each point's offsets along and
// across ab against the arc. The polygon hugs the lens near the segment's ends, where a long
// segment's ends meet the sampled band it spans; the trapezoid of three tangents used before
// read 25 points for each point in the lens there (the noisy curve's fallback,
// docs/benchmarks.md). Every bound is widened far above the rounding (of the apex values: 1e-9;
// of these formulas: 1 %; of the offsets: eps), so that no point with a value below t is ever
// skipped; the exact values then decide.
#pragma once
#include <algorithm>
#include <cmath>

namespace constrict::detail {

class ApexLens2 {
 public:
  /// The lens of segment a -> b (a != b, finite) for threshold t (t >= 0: the diametral disk's
  /// halves, the obtuse angles).
  ApexLens2(const double* a, const double* b, double t) : a_(a) {
    len_ = std::hypot(b[0] - a[0], b[1] - a[1]);
    ux_ = (b[0] - a[0]) / len_;
    uy_ = (b[1] - a[1]) / len_;
    eps_ = 1e-9 * len_ + 1e-12 * std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(b[0]), std::fabs(b[1])});
    const double s = std::min(1.0, 1.0 + t + 1e-9);
    chord2_ = (1 + 1e-6) * 0.25 * len_ * len_;
    if (s <= 0) return;  // no value lies below -1: an empty lens (height 0)
    const double alpha = std::asin(s);
    height_ = 1.01 * 0.5 * len_ * std::tan(0.5 * alpha);
    if (s < 1) centre_ = 0.99 * 0.5 * len_ / std::tan(alpha);
  }
  double length() const { return len_; }
  /// The lens's height over the segment (widened).
  double height() const { return height_; }
  /// Tangents of the arc that bound cover().
  static constexpr int kCoverTangents = 9;
  /// Most vertices of cover(): the tangents' kCoverTangents - 1 crossings, their two points of
  /// contact on the base line, and one more from the cut at height h.
  static constexpr int kMaxCover = kCoverTangents + 2;
  /// A convex polygon, its vertices q[0 .. m) in order, that holds every point p on side `side`
  /// (+1: left of a -> b; -1: right) for which may_hold(p, side, h) is true: the circle of
  /// may_hold, widened, cut by the lines eps below the segment and eps above height h, and
  /// bounded by kCoverTangents of its tangents between the points where it meets the lower line.
  /// (An empty lens, t < -1: the rectangle of the segment widened by eps, where may_hold still
  /// holds.)
  void cover(double side, double h, double (*q)[2], int& m) const {
    const double e = 2 * eps_;
    const double nx = -uy_ * side, ny = ux_ * side;
    m = 0;
    const auto put = [&](double x, double w) {
      q[m][0] = a_[0] + x * ux_ + w * nx;
      q[m][1] = a_[1] + x * uy_ + w * ny;
      ++m;
    };
    if (height_ <= 0) {
      put(-e, -e); put(len_ + e, -e); put(len_ + e, e); put(-e, e);
      return;
    }
    // In coordinates x along a -> b from a and w away from the segment on this side: the circle
    // has its centre at (len / 2, -centre_) and radius sqrt(chord2_ + centre_²) (may_hold).
    const double r = std::sqrt(chord2_ + centre_ * centre_) * (1 + 1e-9) + e;
    const double c = std::min(1.0, (centre_ - e) / r);
    const double phi0 = std::acos(c), step = 2 * phi0 / (kCoverTangents - 1);
    // Contact points of the first and last tangents (on the line w = -e), and the crossings of
    // consecutive tangents, at the middle angle and distance r / cos(step / 2) from the centre.
    double x[kMaxCover + 1], w[kMaxCover + 1];
    int n = 0;
    const double mid = 0.5 * len_, far = r / std::cos(0.5 * step);
    x[n] = mid - r * std::sin(phi0); w[n++] = -e;
    for (int i = 1; i < kCoverTangents; ++i) {
      const double phi = -phi0 + (i - 0.5) * step;
      x[n] = mid + far * std::sin(phi);
      w[n++] = -centre_ + far * std::cos(phi);
    }
    x[n] = mid + r * std::sin(phi0); w[n++] = -e;
    // Cut at w = h + e (one half-plane of a convex polygon: at most one vertex more).
    const double top = h + e;
    double cx[kMaxCover + 1], cw[kMaxCover + 1];
    int k = 0;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      const bool in_i = w[i] <= top, in_j = w[j] <= top;
      if (in_i) { cx[k] = x[i]; cw[k++] = w[i]; }
      if (in_i != in_j) {
        const double f = (top - w[i]) / (w[j] - w[i]);
        cx[k] = x[i] + f * (x[j] - x[i]);
        cw[k++] = top;
      }
    }
    // Back to the plane: a + x u + w n, n the unit normal on this side.
    for (int i = 0; i < k; ++i) put(cx[i], cw[i]);
  }
  /// Can point p, on side `side` and at most h above the segment, have an apex value below t?
  /// False only when it cannot: in coordinates x along the segment from its midpoint and w away
  /// from it, the arc is the circle x² + w² + 2 w centre = |ab|² / 4 (its centre lies
  /// (|ab| / 2) cot α beyond the segment; no cancellation for small α).
  bool may_hold(const double* p, double side, double h) const {
    const double px = p[0] - a_[0], py = p[1] - a_[1];
    const double x = px * ux_ + py * uy_, w = side * (py * ux_ - px * uy_);
    const double xm = x - 0.5 * len_;
    return !(x < -eps_ || x > len_ + eps_ || w < -eps_ || w > h + eps_ || xm * xm + w * w + 2 * w * centre_ > chord2_);
  }

 private:
  const double* a_;
  double len_ = 0, ux_ = 0, uy_ = 0, eps_ = 0;
  double height_ = 0;  // the arc's top over the segment
  double centre_ = 0;  // the circle's centre beyond the segment (1 % nearer)
  double chord2_ = 0;  // |ab|² / 4 (1e-6 larger)
};

}  // namespace constrict::detail
