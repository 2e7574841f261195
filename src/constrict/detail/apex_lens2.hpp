// SPDX-License-Identifier: GPL-3.0-or-later
// Where the points with a small apex value lie, for the 2D fallback's side searches
// (constrict2.cpp, sides_below). A point p sees segment ab under the angle θ = ∠apb; its apex
// value (spec §2.1) is below t < 0 iff θ > π - α with α = asin(1 + t). On each side of ab those
// points lie under a circular arc through a and b that meets the segment at the angle α and rises
// to (|ab| / 2) tan(α / 2) over its midpoint (a lens, thin at the segment's ends); the arc is
// convex, so it lies in the trapezoid between the segment, the tangents at its ends and the
// tangent at its top. A search reads the grid cells of the trapezoid (cut at a height, for the
// layers of a search that starts near the segment) and tests each point's offsets along and
// across ab against the arc. Every bound is widened far above the rounding (of the apex values:
// 1e-9; of these formulas: 1 %; of the offsets: eps), so that no point with a value below t is
// ever skipped; the exact values then decide.
#pragma once
#include <algorithm>
#include <cmath>

namespace constrict::detail {

class ApexLens2 {
 public:
  /// The lens of segment a -> b (a != b, finite) for threshold t (t >= 0: the diametral disk's
  /// halves, the obtuse angles).
  ApexLens2(const double* a, const double* b, double t) : a_(a), b_(b) {
    len_ = std::hypot(b[0] - a[0], b[1] - a[1]);
    ux_ = (b[0] - a[0]) / len_;
    uy_ = (b[1] - a[1]) / len_;
    eps_ = 1e-9 * len_ + 1e-12 * std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(b[0]), std::fabs(b[1])});
    const double s = std::min(1.0, 1.0 + t + 1e-9);
    chord2_ = (1 + 1e-6) * 0.25 * len_ * len_;
    if (s <= 0) return;  // no value lies below -1: an empty lens (height 0)
    const double alpha = std::asin(s);
    height_ = 1.01 * 0.5 * len_ * std::tan(0.5 * alpha);
    if (s < 1) {
      cot_ = 0.99 / std::tan(alpha);
      centre_ = 0.99 * 0.5 * len_ / std::tan(alpha);
    }
  }
  double length() const { return len_; }
  /// The lens's height over the segment (widened).
  double height() const { return height_; }
  /// The trapezoid on side `side` (+1: left of a -> b, where orient2 > 0; -1: right), cut at
  /// height h <= height(): its corners a, b, c, d (counter-clockwise for the left side).
  void trapezoid(double side, double h, double* c, double* d) const {
    const double off = h * cot_, nx = -uy_ * side * h, ny = ux_ * side * h;
    c[0] = b_[0] + nx - off * ux_;
    c[1] = b_[1] + ny - off * uy_;
    d[0] = a_[0] + nx + off * ux_;
    d[1] = a_[1] + ny + off * uy_;
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
  const double* b_;
  double len_ = 0, ux_ = 0, uy_ = 0, eps_ = 0;
  double height_ = 0;  // the arc's top over the segment
  double cot_ = 0;     // the trapezoid's sides: inward per unit of height
  double centre_ = 0;  // the circle's centre beyond the segment (1 % nearer)
  double chord2_ = 0;  // |ab|² / 4 (1e-6 larger)
};

}  // namespace constrict::detail
