// SPDX-License-Identifier: GPL-3.0-or-later
// validate_rings2() / validate_rings2_brute_force(): exact checks of a ring set (topology.hpp).
// Only orient2 and coordinate comparisons decide; the sweep is Shamos–Hoey's over the edges of all
// rings at once (src/validate/validate2.cpp has the one-polygon version).
#include <algorithm>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "constrict/detail/segments2.hpp"
#include "constrict/predicates.hpp"
#include "constrict/topology.hpp"
#include "core/detail/check_points.hpp"
#include "topology/detail/ring_nesting.hpp"

namespace constrict {
namespace {
using detail::closed_segments_meet;
using detail::same_side_collinear;

bool lex_less(const double* p, const double* q) { return p[0] < q[0] || (p[0] == q[0] && p[1] < q[1]); }

// All ring edges in one numbering: edge e = (v(e), v(next(e))), rings one after the other.
struct RingEdges {
  const PointSet& pts;
  const std::vector<Ring2>& rings;
  std::vector<std::size_t> first;  // first edge of each ring; first.back() = total
  std::vector<int> ring_of;        // per edge
  RingEdges(const PointSet& p, const std::vector<Ring2>& r) : pts(p), rings(r), first(r.size() + 1, 0) {
    for (std::size_t k = 0; k < r.size(); ++k) first[k + 1] = first[k] + r[k].indices.size();
    ring_of.resize(first.back());
    for (std::size_t k = 0; k < r.size(); ++k)
      std::fill(ring_of.begin() + static_cast<std::ptrdiff_t>(first[k]), ring_of.begin() + static_cast<std::ptrdiff_t>(first[k + 1]), static_cast<int>(k));
  }
  std::size_t size() const { return first.back(); }
  std::size_t nxt(std::size_t e) const {
    const auto k = static_cast<std::size_t>(ring_of[e]);
    return e + 1 == first[k + 1] ? first[k] : e + 1;
  }
  std::size_t prv(std::size_t e) const {
    const auto k = static_cast<std::size_t>(ring_of[e]);
    return e == first[k] ? first[k + 1] - 1 : e - 1;
  }
  const double* vtx(std::size_t e) const {
    const auto k = static_cast<std::size_t>(ring_of[e]);
    return pts[static_cast<std::size_t>(rings[k].indices[e - first[k]])];
  }
  // Do edges e and f meet in a forbidden way? Consecutive edges of a ring may share only their
  // common vertex (a fold-back is a meeting); any other two edges may not meet at all.
  bool conflict(std::size_t e, std::size_t f) const {
    if (e == f) return false;
    if (nxt(e) == f || nxt(f) == e) {
      const std::size_t a = nxt(e) == f ? e : f;
      if (nxt(nxt(a)) == a) return true;  // a ring of two vertices
      const double *u = vtx(a), *v = vtx(nxt(a)), *w = vtx(nxt(nxt(a)));
      return orient2(u, v, w) == 0 && same_side_collinear(v, u, w);
    }
    return closed_segments_meet(vtx(e), vtx(nxt(e)), vtx(f), vtx(nxt(f)));
  }
};

Status fail(RingsCheck* d, const std::string& why) {
  if (d) d->reason = why;
  return {StatusCode::InvalidArgument, why};
}

Status check_indices(const PointSet& points, const std::vector<Ring2>& rings, RingsCheck* d) {
  if (points.dim != 2) return fail(d, "validate_rings2: points must be 2D");
  // (A NaN point made every predicate at it false: a ring through it passed as valid.)
  if (Status f = detail::check_finite(points, "validate_rings2"); !f) {
    if (d) d->reason = f.message();
    return f;
  }
  const std::size_t n = points.size();
  std::vector<char> seen(n, 0);
  for (std::size_t k = 0; k < rings.size(); ++k) {
    const Ring2& r = rings[k];
    if (r.parent < -1 || r.parent >= static_cast<int>(rings.size()) || r.parent == static_cast<int>(k))
      return fail(d, "ring " + std::to_string(k) + ": parent " + std::to_string(r.parent) + " is not another ring");
    for (int v : r.indices)
      if (v < 0 || static_cast<std::size_t>(v) >= n) return fail(d, "ring " + std::to_string(k) + ": index " + std::to_string(v) + " out of range");
  }
  if (d) d->indices_ok = true;
  for (std::size_t k = 0; k < rings.size(); ++k) {
    if (rings[k].indices.size() < 3) return fail(d, "ring " + std::to_string(k) + " has fewer than 3 vertices");
    for (int v : rings[k].indices) {
      if (seen[static_cast<std::size_t>(v)]) return fail(d, "point " + std::to_string(v) + " appears more than once");
      seen[static_cast<std::size_t>(v)] = 1;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!seen[i]) return fail(d, "point " + std::to_string(i) + " is in no ring");
  if (d) d->all_points = true;
  return Status::ok();
}

std::string pair_reason(const RingEdges& E, std::size_t e, std::size_t f) {
  const int a = E.ring_of[e], b = E.ring_of[f];
  if (a == b) return "ring " + std::to_string(a) + " is not simple (edges " + std::to_string(e - E.first[static_cast<std::size_t>(a)]) +
                     " and " + std::to_string(f - E.first[static_cast<std::size_t>(a)]) + " meet)";
  return "rings " + std::to_string(std::min(a, b)) + " and " + std::to_string(std::max(a, b)) + " meet";
}

// Shamos–Hoey over all ring edges, oriented left (lexicographically smaller end) to right.
class Sweep {
 public:
  explicit Sweep(const RingEdges& E) : E_(E), left_(E.size()), right_(E.size()) {
    for (std::size_t e = 0; e < E.size(); ++e) {
      const double *a = E.vtx(e), *b = E.vtx(E.nxt(e));
      left_[e] = lex_less(a, b) ? a : b;
      right_[e] = lex_less(a, b) ? b : a;
    }
  }
  bool run(std::size_t& e_out, std::size_t& f_out) {
    const std::size_t n = E_.size();
    std::vector<std::size_t> order(n);  // vertex e = the start of edge e
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return lex_less(E_.vtx(i), E_.vtx(j)); });
    std::set<std::size_t, Cmp> active(Cmp{this});
    std::vector<std::set<std::size_t, Cmp>::iterator> where(n, active.end());
    const auto hit = [&](std::size_t e, std::size_t f) {
      e_out = e;
      f_out = f;
      return true;
    };
    for (std::size_t vi : order) {
      const double* v = E_.vtx(vi);
      const std::size_t inc[2] = {E_.prv(vi), vi};
      for (std::size_t e : inc) {  // deletions first: edges ending at v
        if (right_[e] != v || where[e] == active.end()) continue;
        auto it = where[e];
        auto above = std::next(it);
        if (it != active.begin() && above != active.end() && E_.conflict(*std::prev(it), *above)) return hit(*std::prev(it), *above);
        active.erase(it);
        where[e] = active.end();
      }
      for (std::size_t e : inc) {
        if (left_[e] != v) continue;
        auto res = active.insert(e);
        if (bad_) return hit(bad_e_, bad_f_);
        if (!res.second) return hit(e, *res.first);
        auto it = res.first;
        where[e] = it;
        auto above = std::next(it);
        if (above != active.end() && E_.conflict(e, *above)) return hit(e, *above);
        if (it != active.begin() && E_.conflict(e, *std::prev(it))) return hit(e, *std::prev(it));
      }
    }
    return false;
  }

 private:
  struct Cmp {
    Sweep* s;
    bool operator()(std::size_t a, std::size_t b) const { return s->below(a, b); }
  };
  // Is edge a below edge b at the sweep line? A zero orientation means the two meet: flagged, unless
  // they are consecutive edges of one ring sharing their left end (checked by conflict()).
  bool below(std::size_t a, std::size_t b) const {
    if (a == b) return false;
    bool swap = false;
    if (lex_less(left_[b], left_[a])) {
      std::swap(a, b);
      swap = true;
    }
    int o = orient2(left_[a], right_[a], left_[b]);
    if (o == 0) {
      if (left_[b] != left_[a]) flag(a, b);
      o = orient2(left_[a], right_[a], right_[b]);
      if (o == 0) {
        flag(a, b);
        o = lex_less(right_[a], right_[b]) ? 1 : -1;
      }
    }
    return swap ? !(o > 0) : o > 0;
  }
  void flag(std::size_t a, std::size_t b) const {
    if (!bad_) {
      bad_ = true;
      bad_e_ = a;
      bad_f_ = b;
    }
  }
  const RingEdges& E_;
  std::vector<const double*> left_, right_;
  mutable bool bad_ = false;
  mutable std::size_t bad_e_ = 0, bad_f_ = 0;
};

// Orientation of ring k: the turn at its lexicographically smallest vertex (convex in a simple ring).
int orientation(const RingEdges& E, std::size_t k) {
  std::size_t m = E.first[k];
  for (std::size_t e = E.first[k] + 1; e < E.first[k + 1]; ++e)
    if (lex_less(E.vtx(e), E.vtx(m))) m = e;
  return orient2(E.vtx(E.prv(m)), E.vtx(m), E.vtx(E.nxt(m)));
}

Status check_orientation(const RingEdges& E, RingsCheck* d) {
  for (std::size_t k = 0; k < E.rings.size(); ++k) {
    const int want = E.rings[k].role == RingRole::Shell ? 1 : -1;
    if (orientation(E, k) != want)
      return fail(d, "ring " + std::to_string(k) + " (" + to_string(E.rings[k].role) + ") runs " + (want > 0 ? "clockwise" : "counter-clockwise"));
  }
  if (d) d->oriented = true;
  return Status::ok();
}

// Nesting: the parent must be the innermost ring around the ring, the role the depth's parity.
Status check_nesting(const RingEdges& E, RingsCheck* d, bool use_boxes) {
  std::vector<const std::vector<int>*> rings;
  for (const Ring2& r : E.rings) rings.push_back(&r.indices);
  const auto containers = detail::ring_containers(E.pts, rings, use_boxes);
  const auto innermost = detail::innermost_parents(containers);
  for (std::size_t k = 0; k < E.rings.size(); ++k) {
    const Ring2& r = E.rings[k];
    if (r.parent != innermost[k])
      return fail(d, "ring " + std::to_string(k) + ": parent " + std::to_string(r.parent) + ", but the innermost ring around it is " +
                         std::to_string(innermost[k]));
    const RingRole want = containers[k].size() % 2 == 0 ? RingRole::Shell : RingRole::Hole;
    if (r.role != want)
      return fail(d, "ring " + std::to_string(k) + " is at depth " + std::to_string(containers[k].size()) + ", so a " + to_string(want) +
                         ", not a " + to_string(r.role));
  }
  if (d) d->nested = true;
  return Status::ok();
}

Status validate(const PointSet& points, const std::vector<Ring2>& rings, RingsCheck* d, bool brute) {
  if (d) *d = RingsCheck{};
  if (Status s = check_indices(points, rings, d); !s) return s;
  const RingEdges E(points, rings);
  std::size_t e = 0, f = 0;
  bool met = false;
  if (brute) {
    for (std::size_t i = 0; i < E.size() && !met; ++i)
      for (std::size_t j = i + 1; j < E.size() && !met; ++j)
        if (E.conflict(i, j)) {
          e = i;
          f = j;
          met = true;
        }
  } else {
    met = Sweep(E).run(e, f);
  }
  if (met) {
    if (d) {
      d->met_a = E.ring_of[e];
      d->met_b = E.ring_of[f];
    }
    return fail(d, pair_reason(E, e, f));
  }
  if (d) d->simple = true;
  if (Status s = check_orientation(E, d); !s) return s;
  return check_nesting(E, d, !brute);
}

}  // namespace

Status validate_rings2(const PointSet& points, const std::vector<Ring2>& rings, RingsCheck* details) {
  return validate(points, rings, details, false);
}

Status validate_rings2_brute_force(const PointSet& points, const std::vector<Ring2>& rings, RingsCheck* details) {
  return validate(points, rings, details, true);
}

}  // namespace constrict
