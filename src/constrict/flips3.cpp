// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "refine" of the 3D engine (Refine3; docs/reconstruction-3d.md §4): energy-decreasing
// surface edge flips through Delaunay tetrahedra, in both directions — remove a body tetrahedron
// with two surface faces (the paper's two-face rule, seed paper §4.2) or add back a removed one
// with two faces on the surface (its exact reverse).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "constrict/detail/stages3.hpp"
#include "core/detail/ordered_pack.hpp"

namespace constrict::detail {
namespace {

// Circumradius energy of a degenerate triangle: larger than that of any real one.
constexpr double kDegenerateEnergy = 1e300;
// A flip must lower the energy by this fraction of the old one: no flip-back cycles by rounding.
constexpr double kRelativeGain = 1e-9;
// Guard on the number of flips of one pass, per point (the energy strictly decreases anyway, but
// in small steps the number of flips is not bounded by the surface's size). On the shared and
// topology sets a pass made at most 0.6 flips per point; on 300 points of the moment curve, whose
// Delaunay tetrahedralization is quadratic in size (edges in ~100 tetrahedra), one pass made
// 88 000 flips of ~600 candidates each (a guard of 20 per tetrahedron let it run for minutes).
constexpr std::size_t kFlipsPerPoint = 8, kFlipsExtra = 100;
// Guard on a pass's work: each flip re-evaluates the tetrahedra around t's six edges, and each of
// those may walk around an edge of its own, so a flip costs about the sum of its rings' squared
// sizes. At most kRingWorkPerTet of it per tetrahedron, plus kRingWorkFloor. The shared, topology,
// noisy and handle sets use at most 40 per tetrahedron; 1 000 points on a helix, whose edges lie in
// hundreds of tetrahedra, used 20 000 (4 s; 2 000 points: 22 s).
constexpr std::size_t kRingWorkPerTet = 256, kRingWorkFloor = std::size_t{1} << 22;
// A flip whose edge lies in more tetrahedra than this is not tried. Every tetrahedron's gain is
// evaluated before the first flip, and each walks around its edge: on 10^5 points on a line and
// two off it (one edge in 10^5 tetrahedra, all of them candidates) that was 10^10 steps, 67 s.
// Edges of the shared, topology and handle sets lie in at most a few dozen; the helix above in
// hundreds.
constexpr int kMaxFlipRing = 1024;

class Flips3 {
 public:
  Flips3(Body3& b, Refine3 energy, Flips3Stats& st) : b_(b), energy_(energy), s_(st) {}

  void run() {
    // The first candidates: every tetrahedron's gain in parallel (flip_gain only reads the body),
    // gathered and pushed in index order. (The pops do not depend on the push order anyway: the heap's order is
    // total, by gain and then the sorted vertex ids.)
    const std::vector<HeapEntry> found = ordered_pack<HeapEntry>(b_.tets.size(), [&](std::size_t t, const auto& push) {
      const double g = flip_gain(static_cast<int>(t));
      if (g > 0) push(HeapEntry{g, static_cast<int>(t), b_.ver[t]});
    });
    for (const HeapEntry& e : found) heap_.push(e, b_.tets);
    std::vector<int> ring, touched;
    const std::size_t cap = kFlipsPerPoint * b_.n + kFlipsExtra;
    const std::size_t work_cap = kRingWorkPerTet * b_.tets.size() + kRingWorkFloor;
    std::size_t work = 0;
    for (std::size_t flips = 0; !heap_.empty() && flips < cap;) {
      if (work > work_cap) {
        s_.capped = true;
        break;
      }
      const HeapEntry e = heap_.pop(b_.tets);
      if (e.version != b_.ver[uz(e.tet)]) continue;
      if (flip_gain(e.tet) <= 0) continue;
      ++flips;
      const int t = e.tet;
      if (b_.alive(t)) {
        b_.state[uz(t)] = kOutside;
        ++s_.removed;
      } else {
        b_.state[uz(t)] = kAlive;
        ++s_.added;
      }
      ++b_.ver[uz(t)];
      // Candidates change only around t's edges: face neighbours change sides, and the surface
      // loses one edge and gains one (the removability of the tets around them changes).
      touched.clear();
      touched.push_back(t);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          b_.edge_ring(t, i, j, ring);
          touched.insert(touched.end(), ring.begin(), ring.end());
          work += ring.size() * ring.size();
        }
      std::sort(touched.begin(), touched.end());
      touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
      for (int x : touched) {
        ++b_.ver[uz(x)];
        const double gx = flip_gain(x);
        if (gx > 0) heap_.push({gx, x, b_.ver[uz(x)]}, b_.tets);
      }
    }
    s_.long_rings += long_rings_.load();
  }

 private:
  double face_energy(int a, int b, int c) const {
    const double* p = b_.P(a);
    const double* q = b_.P(b);
    const double* r = b_.P(c);
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const double w[3] = {r[0] - q[0], r[1] - q[1], r[2] - q[2]};
    const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
    const double area2 = std::sqrt(cx * cx + cy * cy + cz * cz);  // twice the area
    if (energy_ == Refine3::Area) return 0.5 * area2;
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double lv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double lw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    if (!(area2 > 0)) return kDegenerateEnergy;
    return lu * lv * lw / (2.0 * area2);  // circumradius abc / (4 A)
  }
  double face_energy_of(int t, int i) const {
    const auto& v = b_.tets[uz(t)];
    return face_energy(v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][1])], v[uz(kFaceOut[i][2])]);
  }
  // A flip through t: t (in the body or removed) has exactly two faces on the surface, and the
  // edge joining the two vertices opposite them is not on the surface (in the body: spec
  // gamma-graph.md §3.3 two-face rule; removed: its exact reverse, the edge touches no body
  // tetrahedron). Flipping replaces those two surface faces by t's other two faces: an edge flip
  // of the surface, so it stays a closed genus-0 2-manifold through the same points. Returns the
  // energy decrease, or -1.
  double flip_gain(int t) const {
    if (b_.state[uz(t)] == kReplaced) return -1;
    const bool a = b_.alive(t);
    int si[4], oi[4], ns = 0, no = 0;
    for (int i = 0; i < 4; ++i) {
      const bool on = a ? !b_.alive(b_.nbr[uz(t)][uz(i)]) : b_.alive(b_.nbr[uz(t)][uz(i)]);
      if (on) si[ns++] = i;
      else oi[no++] = i;
    }
    if (ns != 2) return -1;
    // The energy first (arithmetic on four points), the edge walk only for a shortening flip.
    const double e_old = face_energy_of(t, si[0]) + face_energy_of(t, si[1]);
    const double e_new = face_energy_of(t, oi[0]) + face_energy_of(t, oi[1]);
    const double gain = e_old - e_new;
    if (!(gain > kRelativeGain * e_old)) return -1;
    const int blocked = b_.edge_blocked_within(t, si[0], si[1], a, kMaxFlipRing);
    if (blocked < 0) long_rings_.fetch_add(1, std::memory_order_relaxed);
    return blocked == 0 ? gain : -1;
  }

  Body3& b_;
  Refine3 energy_;
  Flips3Stats& s_;
  mutable std::atomic<std::size_t> long_rings_{0};  // (flip_gain runs on both cores at first)
  TetHeap heap_;
};

}  // namespace

void flip_pass3(Body3& body, Refine3 energy, Flips3Stats& stats) { Flips3(body, energy, stats).run(); }

}  // namespace constrict::detail
