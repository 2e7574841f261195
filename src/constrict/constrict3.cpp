// SPDX-License-Identifier: GPL-3.0-or-later
// 3D γ-constriction of the Delaunay tetrahedralization (seed paper §4.2, §5; spec §3.1-3.5), the
// star-cavity fallback after a lock (paper §4.3) and the optional two-face sculpting post-pass
// (paper §4.2, candlestick). See docs/reconstruction-3d.md for the algorithm and guarantees.
#include <algorithm>
#include <memory>
#include <queue>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "constrict/constrict3.hpp"
#include "constrict/delaunay.hpp"
#include "constrict/criterion.hpp"
#include "constrict/gamma_graph.hpp"
#include "constrict/mesh.hpp"
#include "constrict/predicates.hpp"

namespace constrict {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Face opposite local vertex i of a positively oriented tetrahedron, oriented outward (the
// tetrahedron's vertex i lies on its negative side).
constexpr int kFaceOut[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

enum : std::uint8_t { kOutside = 0, kAlive = 1, kReplaced = 2 };

// Sign of the permutation (a, b, c, d) of (0, 1, 2, 3).
int parity4(int a, int b, int c, int d) {
  const int v[4] = {a, b, c, d};
  int inv = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inv += v[i] > v[j];
  return (inv & 1) ? -1 : 1;
}

std::array<int, 4> sorted4(std::array<int, 4> t) {
  std::sort(t.begin(), t.end());
  return t;
}

std::uint64_t edge_key(int u, int v) {
  if (u > v) std::swap(u, v);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) | static_cast<std::uint32_t>(v);
}

struct Entry {
  double key;
  int tet;
  std::uint32_t version;
};

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

}  // namespace

struct Constrictor3::Impl {
  const PointSet* pts = nullptr;
  std::shared_ptr<const PointSet> scaled;  // power-of-two scaled copy of the input (init), or null
  int scale_exp = 0;                       // pts = input * 2^-scale_exp
  Constrict3Options opt;
  Constrict3Visitor* visitor = nullptr;
  bool ready = false;

  // Faces + simplex_face of the Delaunay tets: read-only after init, shared by the copies of
  // this state that reconstruct3() runs for its size-bias candidates.
  std::shared_ptr<const DelaunayGamma3> dgp;
  const DelaunayGamma3& dg() const { return *dgp; }
  std::vector<std::array<int, 4>> tets;      // Delaunay tets, then fallback tets appended
  std::vector<std::array<int, 4>> nbr;       // neighbor across the face opposite vertex i
  std::size_t T0 = 0;                        // number of Delaunay tets
  std::vector<std::uint8_t> state;
  std::vector<std::uint32_t> ver;
  std::vector<char> onb;
  std::size_t n = 0, n_onb = 0, n_hull = 0;
  std::vector<Entry> heap;

  std::size_t removed = 0, removed1 = 0, removed2 = 0, removed_sculpt = 0;
  bool bridge_keys = false;                  // heap keys are face_bridge() (Sculpt3::Bridges)
  std::vector<double> spacing;               // nearest-neighbour distance per vertex
  std::shared_ptr<const std::vector<double>> face_log;  // ln bridge ratio per Delaunay face
  std::shared_ptr<const std::vector<float>> label;      // +conf outside / -conf inside per Delaunay tet
  std::shared_ptr<const std::vector<std::array<double, 4>>> terms;  // face_term of the Delaunay tets
  bool locked_now = false, stopped = false, first_lock = false;
  std::vector<int> stuck;
  double ms_delaunay = 0, ms_constrict = 0, ms_setup = 0;

  // Fallback state.
  std::vector<int> vert_tet;                 // an alive tet incident to each vertex (built on lock)
  std::vector<std::uint32_t> mark;           // per tet epoch marks
  std::uint32_t epoch = 0;
  std::size_t cavities = 0, cavity_attempts = 0;

  const double* P(int v) const { return (*pts)[uz(v)]; }
  bool alive(int t) const { return t >= 0 && state[uz(t)] == kAlive; }
  bool boundary_face(int t, int i) const { return !alive(nbr[uz(t)][uz(i)]); }

  // ---- heap (max by key, ties -> smallest sorted vertex-id tuple; spec §3.5) -------------------
  bool less(const Entry& a, const Entry& b) const {
    if (a.key != b.key) return a.key < b.key;
    return sorted4(tets[uz(a.tet)]) > sorted4(tets[uz(b.tet)]);
  }
  void heap_push(const Entry& e) {
    heap.push_back(e);
    std::push_heap(heap.begin(), heap.end(), [this](const Entry& a, const Entry& b) { return less(a, b); });
  }
  Entry heap_pop() {
    std::pop_heap(heap.begin(), heap.end(), [this](const Entry& a, const Entry& b) { return less(a, b); });
    Entry e = heap.back();
    heap.pop_back();
    return e;
  }

  // 1 - γ(face opposite i; apex tets[t][i]) (spec §3.2, §3.4). For a Delaunay tet this is the
  // stored side value of the face on the side of the apex (spec §2.3); fallback tets use the apex
  // value directly.
  double face_term(int t, int i) const {
    if (uz(t) < T0 && terms) return (*terms)[uz(t)][uz(i)];
    return face_term_compute(t, i);
  }
  // Precomputes face_term of every Delaunay tetrahedron (shared by the variant runs): the key is
  // evaluated at every push, and this removes the sort and the parity from the hot loop.
  void compute_terms() {
    auto out = std::make_shared<std::vector<std::array<double, 4>>>(T0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T0, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t)
        for (int i = 0; i < 4; ++i) (*out)[t][uz(i)] = face_term_compute(static_cast<int>(t), i);
    });
    terms = std::move(out);
  }
  double face_term_compute(int t, int i) const {
    const auto& v = tets[uz(t)];
    if (uz(t) < T0) {
      const int f = dg().simplex_face[uz(t)][uz(i)];
      std::array<std::pair<int, int>, 3> fv{};
      int k = 0;
      for (int l = 0; l < 4; ++l)
        if (l != i) fv[uz(k++)] = {v[uz(l)], l};
      std::sort(fv.begin(), fv.end());
      const int side = parity4(fv[0].second, fv[1].second, fv[2].second, i);
      const double g = side > 0 ? dg().faces.gamma_a[uz(f)] : dg().faces.gamma_b[uz(f)];
      return 1.0 - g;
    }
    const int* fo = kFaceOut[i];
    return 1.0 - apex_gamma3(P(v[uz(fo[0])]), P(v[uz(fo[1])]), P(v[uz(fo[2])]), P(v[uz(i)]));
  }

  int local_index(int t, int vertex) const {
    const auto& v = tets[uz(t)];
    for (int l = 0; l < 4; ++l)
      if (v[uz(l)] == vertex) return l;
    return -1;
  }

  // Walks around the edge (tets[t][i], tets[t][j]) from t through the tetrahedra sharing it, in
  // direction dir (0 or 1), calling f(next) for each neighbour met: next < 0 at the convex hull,
  // next == t when the ring closes. Stops when f returns true.
  template <class F> void walk_edge(int t, int i, int j, int dir, F&& f) const {
    const int a = tets[uz(t)][uz(i)], b = tets[uz(t)][uz(j)];
    int k = 0;
    while (k == i || k == j) ++k;
    int l = 0;
    while (l == i || l == j || l == k) ++l;
    int cur = t, exit_v = tets[uz(t)][uz(dir ? l : k)], keep = tets[uz(t)][uz(dir ? k : l)];
    for (std::size_t guard = 0; guard < tets.size() + 1; ++guard) {
      const int li = local_index(cur, exit_v);
      CONSTRICT_CHECK(li >= 0, "edge walk lost its way");
      const int nx = nbr[uz(cur)][uz(li)];
      if (f(nx) || nx < 0 || nx == t) return;
      int w = -1;
      for (int x : tets[uz(nx)])
        if (x != a && x != b && x != keep) w = x;
      exit_v = keep;
      keep = w;
      cur = nx;
    }
    CONSTRICT_CHECK(false, "edge walk did not terminate");
  }

  // Is the edge (tets[t][i], tets[t][j]) on the surface? It is iff the walk around it meets a
  // non-alive tetrahedron before closing.
  bool edge_on_boundary(int t, int i, int j) const {
    bool on = false;
    walk_edge(t, i, j, 0, [&](int nx) {
      on = !alive(nx);
      return on;
    });
    return on;
  }

  // Is the edge (tets[t][i], tets[t][j]) an edge of some alive tetrahedron other than t? (The
  // walk goes both ways when the ring is open at the convex hull.)
  bool edge_touches_body(int t, int i, int j) const {
    bool hit = false, hull = false;
    walk_edge(t, i, j, 0, [&](int nx) {
      if (nx < 0) { hull = true; return true; }
      hit = alive(nx);
      return hit;
    });
    if (!hit && hull)  // the ring is open at the hull: walk the other way too
      walk_edge(t, i, j, 1, [&](int nx) {
        if (nx < 0) return true;
        hit = alive(nx);
        return hit;
      });
    return hit;
  }
  // Bridge ratio of the triangle abc: its longest edge over the largest nearest-neighbour
  // distance of its vertices (size bias, Sculpt3::Bridges).
  double bridge_ratio(int a, int b, int c) const {
    const auto d2 = [&](int x, int y) {
      const double dx = P(x)[0] - P(y)[0], dy = P(x)[1] - P(y)[1], dz = P(x)[2] - P(y)[2];
      return dx * dx + dy * dy + dz * dz;
    };
    const double longest = std::sqrt(std::max({d2(a, b), d2(b, c), d2(c, a)}));
    const double h = std::max({spacing[uz(a)], spacing[uz(b)], spacing[uz(c)]});
    return h > 0 ? longest / h : 0;
  }
  // bridge_ratio of the face opposite i.
  double face_bridge(int t, int i) const {
    const auto& v = tets[uz(t)];
    return bridge_ratio(v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][1])], v[uz(kFaceOut[i][2])]);
  }
  // ln(max(1, face_bridge)) of the face opposite i: precomputed for the Delaunay faces (shared by
  // the candidate runs), computed on the fly for fallback tetrahedra.
  double face_log_ratio(int t, int i) const {
    if (uz(t) < T0 && face_log) return (*face_log)[uz(dg().simplex_face[uz(t)][uz(i)])];
    return std::log(std::max(1.0, face_bridge(t, i)));
  }
  void compute_face_log() {
    const GammaFaces& f = dg().faces;
    auto out = std::make_shared<std::vector<double>>(f.size(), 0.0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 16384), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k)
        (*out)[k] = std::log(std::max(1.0, bridge_ratio(f.vertex(k, 0), f.vertex(k, 1), f.vertex(k, 2))));
    });
    face_log = std::move(out);
  }
  // Inside/outside labels of the Delaunay tetrahedra by circumball propagation (power-crust
  // style): the outer half-space of a hull face and the circumball of its tetrahedron meet at an
  // angle whose cosine is the signed distance of the circumcentre beyond the face over the radius;
  // two adjacent circumballs meet at cos = (r1² + r2² - d²) / (2 r1 r2). A deep intersection
  // (cos > 0) passes the label on, a shallow one (cos < 0) the opposite label, with confidence
  // |cos|; the most confident assignments are made first (a max-heap), each tetrahedron once.
  void compute_labels() {
    std::vector<std::array<double, 4>> ball(T0);  // centre xyz, radius (radius < 0: flat)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T0, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t) {
        const auto& v = tets[t];
        const double* a = P(v[0]);
        double b[3], c[3], d[3];
        for (int k = 0; k < 3; ++k) {
          b[k] = P(v[1])[k] - a[k];
          c[k] = P(v[2])[k] - a[k];
          d[k] = P(v[3])[k] - a[k];
        }
        const double cd[3] = {c[1] * d[2] - c[2] * d[1], c[2] * d[0] - c[0] * d[2], c[0] * d[1] - c[1] * d[0]};
        const double db[3] = {d[1] * b[2] - d[2] * b[1], d[2] * b[0] - d[0] * b[2], d[0] * b[1] - d[1] * b[0]};
        const double bc[3] = {b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]};
        const double den = 2 * (b[0] * cd[0] + b[1] * cd[1] + b[2] * cd[2]);
        const double nb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2], nc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2],
                     nd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        std::array<double, 4> o{{0, 0, 0, -1}};
        if (den != 0 && std::isfinite(den)) {
          double x[3];
          for (int k = 0; k < 3; ++k) x[k] = (nb * cd[k] + nc * db[k] + nd * bc[k]) / den;
          const double rr = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
          if (std::isfinite(rr)) o = {{a[0] + x[0], a[1] + x[1], a[2] + x[2], rr}};
        }
        ball[t] = o;
      }
    });
    // Bucket queue over the confidence quantised to 1/kBuckets (a binary heap of the ~4 pushes
    // per tetrahedron costs more than the rest); LIFO inside a bucket, all sequential, so the
    // labels are deterministic.
    constexpr int kBuckets = 1024;
    struct Item {
      int tet;
      signed char lab;
      float conf;
    };
    std::vector<std::vector<Item>> bucket(kBuckets + 1);
    int top = -1;
    // A push into a lower bucket than a pending entry of the same tetrahedron could only pop after
    // that entry has labelled it (then it is skipped as done): not pushed, same labels.
    std::vector<std::int16_t> best_b(T0, -1);
    const auto qpush = [&](const Item& it) {
      const int b = static_cast<int>(it.conf * kBuckets);
      if (b < best_b[uz(it.tet)]) return;
      best_b[uz(it.tet)] = static_cast<std::int16_t>(b);
      bucket[uz(b)].push_back(it);
      top = std::max(top, b);
    };
    auto out = std::make_shared<std::vector<float>>(T0, 0.0f);
    std::vector<char> done(T0, 0);
    const auto push = [&](int t, double cosv, int lab_from) {
      if (!(cosv == cosv)) return;
      const double c = std::max(-1.0, std::min(1.0, cosv));
      qpush({t, static_cast<signed char>(c >= 0 ? lab_from : -lab_from), static_cast<float>(std::abs(c))});
    };
    for (std::size_t t = 0; t < T0; ++t)
      for (int i = 0; i < 4; ++i) {
        if (nbr[t][uz(i)] >= 0 || ball[t][3] <= 0) continue;
        // Outward normal of the hull face opposite i (the apex tets[t][i] is on the inner side).
        const auto& v = tets[t];
        const double* p0 = P(v[uz(kFaceOut[i][0])]);
        const double* p1 = P(v[uz(kFaceOut[i][1])]);
        const double* p2 = P(v[uz(kFaceOut[i][2])]);
        const double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        const double w[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double nrm[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        const double ln = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        if (!(ln > 0)) continue;
        const double* ap = P(v[uz(i)]);
        const double side = nrm[0] * (ap[0] - p0[0]) + nrm[1] * (ap[1] - p0[1]) + nrm[2] * (ap[2] - p0[2]);
        const double sgn = side > 0 ? -1.0 : 1.0;  // flip so that nrm points away from the apex
        const double dist = sgn * (nrm[0] * (ball[t][0] - p0[0]) + nrm[1] * (ball[t][1] - p0[1]) +
                                   nrm[2] * (ball[t][2] - p0[2])) / ln;
        push(static_cast<int>(t), dist / ball[t][3], +1);
      }
    while (top >= 0) {
      if (bucket[uz(top)].empty()) {
        --top;
        continue;
      }
      const Item it = bucket[uz(top)].back();
      bucket[uz(top)].pop_back();
      if (done[uz(it.tet)]) continue;
      done[uz(it.tet)] = 1;
      (*out)[uz(it.tet)] = it.lab * it.conf;
      const auto& bt = ball[uz(it.tet)];
      for (int i = 0; i < 4; ++i) {
        const int m = nbr[uz(it.tet)][uz(i)];
        if (m < 0 || uz(m) >= T0 || done[uz(m)]) continue;
        const auto& bm = ball[uz(m)];
        if (bt[3] <= 0 || bm[3] <= 0) continue;
        const double dx = bt[0] - bm[0], dy = bt[1] - bm[1], dz = bt[2] - bm[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        push(m, (bt[3] * bt[3] + bm[3] * bm[3] - d2) / (2 * bt[3] * bm[3]), it.lab);
      }
    }
    label = std::move(out);
    lrad.resize(T0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T0, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t) lrad[t] = ball[t][3] > 0 ? std::log(ball[t][3]) : -1e300;
    });
  }

  void compute_spacing() {
    spacing.assign(n, HUGE_VAL);
    for (std::size_t t = 0; t < T0; ++t) {
      const auto& v = tets[t];
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const int a = v[uz(i)], b = v[uz(j)];
          const double dx = P(a)[0] - P(b)[0], dy = P(a)[1] - P(b)[1], dz = P(a)[2] - P(b)[2];
          const double l = std::sqrt(dx * dx + dy * dy + dz * dz);
          spacing[uz(a)] = std::min(spacing[uz(a)], l);
          spacing[uz(b)] = std::min(spacing[uz(b)], l);
        }
    }
  }

  // The initial heap: the tetrahedra on the convex hull.
  void start_heap() {
    heap.clear();
    for (std::size_t t = 0; t < T0; ++t) {
      const auto& nb = nbr[t];
      if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0 || nb[3] < 0) try_push(static_cast<int>(t));
    }
  }

  // Removability (spec §3.3): 1 / 2 boundary faces by the one-face / two-face rule, else 0.
  int removable(int t, double* key) const {
    int bi[4], nb = 0;
    for (int i = 0; i < 4; ++i)
      if (boundary_face(t, i)) bi[nb++] = i;
    if (bridge_keys) {
      if (nb != 2 || edge_on_boundary(t, bi[0], bi[1])) return 0;
      if (key) *key = std::max(face_bridge(t, bi[0]), face_bridge(t, bi[1]));
      return 2;
    }
    int r = 0;
    if (nb == 1) r = onb[uz(tets[uz(t)][uz(bi[0])])] ? 0 : 1;
    else if (nb == 2) r = edge_on_boundary(t, bi[0], bi[1]) ? 0 : 2;
    if (r && key) *key = criterion_key(t, bi, nb);
    return r;
  }

  // Key of removing tet t with boundary faces bi[0..nb) (criterion.hpp, spec §3.4).
  double criterion_key(int t, const int* bi, int nb) const {
    if (opt.criterion == Criterion::MinAreaChange) {
      // Boissonnat 84b (seed paper §2.6): smallest (Σ interior - Σ boundary) / Σ all face areas.
      const auto& v = tets[uz(t)];
      double areas[4];
      bool bd[4] = {false, false, false, false};
      for (int i = 0; i < 4; ++i)
        areas[i] = triangle_area3(P(v[uz(kFaceOut[i][0])]), P(v[uz(kFaceOut[i][1])]), P(v[uz(kFaceOut[i][2])]));
      for (int k = 0; k < nb; ++k) bd[bi[k]] = true;
      return -area_change_ratio3(areas, bd);
    }
    double key = face_term(t, bi[0]);
    if (nb == 2) {
      // Paper §4.2: the sum of the two terms; TwoFaceKey::Max is the measured alternative and
      // Boissonnat 84a's rule (one face decides, seed paper §6).
      const double k2 = face_term(t, bi[1]);
      const bool sum = opt.criterion == Criterion::Gamma && opt.two_face_key == TwoFaceKey::Sum;
      key = sum ? key + k2 : std::max(key, k2);
    }
    if (opt.label_weight > 0 && label && uz(t) < T0) key += opt.label_weight * (*label)[uz(t)];
    if (opt.size_bias > 0) {
      // Size bias (docs/reconstruction-3d.md §4.5): large surface faces relative to the local
      // spacing first, so that bridges across gaps are carved before their far side is reached.
      double lr = face_log_ratio(t, bi[0]);
      if (nb == 2) lr = std::max(lr, face_log_ratio(t, bi[1]));
      key += opt.size_bias * lr;
    }
    return key;
  }

  void try_push(int t) {
    double key = 0;
    if (removable(t, &key)) heap_push({key, t, ver[uz(t)]});
  }

  void remove(int t, int kind, double key, const char* stage) {
    state[uz(t)] = kOutside;
    ++ver[uz(t)];
    ++removed;
    if (kind == 1) {
      ++removed1;
      for (int i = 0; i < 4; ++i) {
        const int x = tets[uz(t)][uz(i)];
        if (!onb[uz(x)]) { onb[uz(x)] = 1; ++n_onb; }
      }
    } else {
      ++removed2;
    }
    for (int i = 0; i < 4; ++i) {
      const int m = nbr[uz(t)][uz(i)];
      if (alive(m)) {
        ++ver[uz(m)];
        try_push(m);
      }
    }
    // Spec §3.3 (ii): after a two-face removal the common edge leaves the surface; a tet around it
    // could become removable. Around that edge the only alive tet was t itself (the surface is a
    // 2-manifold, so the edge had exactly the two faces of t), so there is nothing to re-examine.
    if (visitor) {
      Constrict3Event e;
      e.kind = Constrict3Event::Kind::RemoveTet;
      e.tet = tets[uz(t)];
      e.boundary_faces = kind;
      e.criterion = key;
      e.stage = stage;
      visitor->on_event(e);
    }
  }

  // Pops until one removal is done. min_key: stop (return false) when the best key is below it.
  bool pop_and_remove(double min_key, const char* stage) {
    while (!heap.empty()) {
      if (heap.front().key < min_key) return false;
      const Entry e = heap_pop();
      if (!alive(e.tet) || e.version != ver[uz(e.tet)]) continue;
      double key = 0;
      const int kind = removable(e.tet, &key);
      if (!kind) continue;
      remove(e.tet, kind, key, stage);
      return true;
    }
    return false;
  }

  bool step() {
    if (!ready || stopped || n_onb == n) return false;
    stepped = true;
    ensure_hull_start();
    if (removed >= opt.stop_after) { stopped = true; return false; }
    if (pop_and_remove(-1e300, "gamma")) return true;
    locked_now = true;
    if (visitor) {
      Constrict3Event e;
      e.kind = Constrict3Event::Kind::Lock;
      e.stage = "gamma";
      visitor->on_event(e);
    }
    return false;
  }

  std::vector<int> inside() const {
    std::vector<int> r;
    for (std::size_t v = 0; v < n; ++v)
      if (!onb[v]) r.push_back(static_cast<int>(v));
    return r;
  }

  TriMesh3 surface() const {
    TriMesh3 m;
    for (std::size_t t = 0; t < tets.size(); ++t) {
      if (state[t] != kAlive) continue;
      for (int i = 0; i < 4; ++i)
        if (boundary_face(static_cast<int>(t), i)) {
          const auto& v = tets[t];
          m.triangles.push_back({{v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][1])], v[uz(kFaceOut[i][2])]}});
        }
    }
    return m;
  }

  // ---- fallback: star-cavity re-tetrahedralization (docs/reconstruction-3d.md §3) ------------

  int new_tet(const std::array<int, 4>& v) {
    tets.push_back(v);
    nbr.push_back({{-1, -1, -1, -1}});
    state.push_back(kAlive);
    ver.push_back(0);
    mark.push_back(0);
    return static_cast<int>(tets.size() - 1);
  }

  void build_vert_tet() {
    vert_tet.assign(n, -1);
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (state[t] == kAlive)
        for (int x : tets[t]) vert_tet[uz(x)] = static_cast<int>(t);
  }

  // The tets around vertex p (all alive: p is not on the surface).
  // The side of the surface the cavity works in: the body (the constriction's stuck points are
  // inside it) or, mirrored for the growth (§4.7), the Delaunay tetrahedra outside the body (the
  // growth's unreached points are there; the convex hull then bounds the side).
  bool mirror_cavity = false;
  bool in_side(int m) const { return mirror_cavity ? m >= 0 && state[uz(m)] == kOutside : alive(m); }
  bool star_of(int p, std::vector<int>& out) {
    out.clear();
    const int t0 = vert_tet[uz(p)];
    if (!in_side(t0) || local_index(t0, p) < 0) return false;
    ++epoch;
    mark[uz(t0)] = epoch;
    out.push_back(t0);
    for (std::size_t q = 0; q < out.size(); ++q) {
      const int t = out[q];
      for (int i = 0; i < 4; ++i) {
        if (tets[uz(t)][uz(i)] == p) continue;
        const int m = nbr[uz(t)][uz(i)];
        if (mirror_cavity && m < 0) continue;  // p on the convex hull: this hull face stays
        if (!in_side(m)) return false;  // p would be on the surface
        if (mark[uz(m)] != epoch) { mark[uz(m)] = epoch; out.push_back(m); }
      }
      if (out.size() > 100000) return false;
    }
    return true;
  }

  struct Target {
    double key;
    int t, i;
    std::array<int, 3> ids;
  };

  // Rank of inserting p through surface face abc (the tet (a,b,c,p) removed by its one face).
  double target_key(int a, int b, int c, int p) const {
    if (opt.criterion != Criterion::MinAreaChange) return 1.0 - apex_gamma3(P(a), P(b), P(c), P(p));
    const double areas[4] = {triangle_area3(P(a), P(b), P(c)), triangle_area3(P(a), P(b), P(p)),
                             triangle_area3(P(b), P(c), P(p)), triangle_area3(P(c), P(a), P(p))};
    const bool bd[4] = {true, false, false, false};
    return -area_change_ratio3(areas, bd);
  }

  // Surface faces within `depth` face-hops of p's star that p sees from inside, best key first.
  void targets_of(int p, const std::vector<int>& star, int depth, std::vector<Target>& out) {
    out.clear();
    ++epoch;
    std::vector<int> cur = star, next;
    for (int t : cur) mark[uz(t)] = epoch;
    for (int d = 0; d <= depth && !cur.empty(); ++d) {
      next.clear();
      for (int t : cur) {
        for (int i = 0; i < 4; ++i) {
          const int m = nbr[uz(t)][uz(i)];
          if (mirror_cavity ? alive(m) : !alive(m)) {
            const auto& v = tets[uz(t)];
            const int a = v[uz(kFaceOut[i][0])], b = v[uz(kFaceOut[i][1])], c = v[uz(kFaceOut[i][2])];
            if (orient3(P(a), P(b), P(c), P(p)) < 0) {
              std::array<int, 3> ids{{a, b, c}};
              std::sort(ids.begin(), ids.end());
              out.push_back({target_key(a, b, c, p), t, i, ids});
            }
          } else if (in_side(m) && mark[uz(m)] != epoch) {
            mark[uz(m)] = epoch;
            next.push_back(m);
          }
        }
      }
      std::swap(cur, next);
    }
    std::sort(out.begin(), out.end(), [](const Target& x, const Target& y) {
      return x.key != y.key ? x.key > y.key : x.ids < y.ids;
    });
  }

  // Grows U = star(p) ∪ {tet behind the target face} until every face of its boundary is seen
  // from p strictly from inside (orient3 < 0), then replaces U by the cone from p over its
  // boundary. All tests exact. Returns false (and leaves everything unchanged) when U would have
  // to grow across the surface, exceeds the size limit, swallows a vertex, or is not a sphere.
  bool try_cavity(int p, const std::vector<int>& star, const Target& tg) {
    ++cavity_attempts;
    ++epoch;
    const std::uint32_t in_u = epoch;
    std::vector<int> U;
    for (int t : star) { mark[uz(t)] = in_u; U.push_back(t); }
    if (mark[uz(tg.t)] != in_u) { mark[uz(tg.t)] = in_u; U.push_back(tg.t); }
    // Visibility closure. Faces are re-scanned per added tet (worklist).
    std::vector<int> work = U;
    while (!work.empty()) {
      const int t = work.back();
      work.pop_back();
      if (mark[uz(t)] != in_u) continue;
      for (int i = 0; i < 4; ++i) {
        const int m = nbr[uz(t)][uz(i)];
        if (m >= 0 && mark[uz(m)] == in_u) continue;
        const auto& v = tets[uz(t)];
        const int a = v[uz(kFaceOut[i][0])], b = v[uz(kFaceOut[i][1])], c = v[uz(kFaceOut[i][2])];
        if (a == p || b == p || c == p) {
          if (mirror_cavity && m < 0) continue;  // a convex-hull face at p: it stays (cone side)
          return false;                          // p on U's boundary: cannot happen, be safe
        }
        if (orient3(P(a), P(b), P(c), P(p)) < 0) continue;  // visible
        if (!in_side(m)) return false;                      // would cross the surface
        if (U.size() >= opt.max_cavity_tets) return false;
        mark[uz(m)] = in_u;
        U.push_back(m);
        work.push_back(m);
        // t's own other faces stay valid; m's faces are scanned when popped.
      }
    }
    // U's boundary faces, outward from U.
    struct BFace { int a, b, c, outside; };
    std::vector<BFace> bf;
    std::vector<std::uint64_t> hull_edges;  // edges opposite p of the hull faces at p (mirror)
    for (int t : U)
      for (int i = 0; i < 4; ++i) {
        const int m = nbr[uz(t)][uz(i)];
        if (m >= 0 && mark[uz(m)] == in_u) continue;
        const auto& v = tets[uz(t)];
        const int a = v[uz(kFaceOut[i][0])], b = v[uz(kFaceOut[i][1])], c = v[uz(kFaceOut[i][2])];
        if (a == p || b == p || c == p) {  // (only a hull face at p gets here, see above)
          hull_edges.push_back(a == p ? edge_key(b, c) : b == p ? edge_key(a, c) : edge_key(a, b));
          continue;
        }
        bf.push_back({a, b, c, m});
      }
    std::sort(hull_edges.begin(), hull_edges.end());
    // No vertex of U may disappear: every vertex of U other than p lies on its boundary.
    {
      std::vector<int> vb, vu;
      for (const auto& f : bf) { vb.push_back(f.a); vb.push_back(f.b); vb.push_back(f.c); }
      for (int t : U)
        for (int x : tets[uz(t)])
          if (x != p) vu.push_back(x);
      std::sort(vb.begin(), vb.end());
      vb.erase(std::unique(vb.begin(), vb.end()), vb.end());
      std::sort(vu.begin(), vu.end());
      vu.erase(std::unique(vu.begin(), vu.end()), vu.end());
      if (vb != vu) return false;
    }
    // Edge pairing of the boundary (must be a closed 2-manifold: every edge in exactly 2 faces).
    std::unordered_map<std::uint64_t, std::array<int, 4>> edge_slots;  // -> (tet, local, tet, local)
    edge_slots.reserve(bf.size() * 2);
    std::vector<int> created;
    created.reserve(bf.size());
    // Create the cone tets (f.a, f.c, f.b, p): positively oriented since orient3(a,b,c,p) < 0.
    const std::size_t first_new = tets.size();
    for (std::size_t k = 0; k < bf.size(); ++k) {
      const auto& f = bf[k];
      const std::array<int, 4> v{{f.a, f.c, f.b, p}};
      // local faces containing p: opposite w0 (edge w1w2), w1 (edge w0w2), w2 (edge w0w1)
      const std::uint64_t keys[3] = {edge_key(v[1], v[2]), edge_key(v[0], v[2]), edge_key(v[0], v[1])};
      const int tid = static_cast<int>(first_new + k);
      for (int j = 0; j < 3; ++j) {
        auto it = edge_slots.find(keys[j]);
        if (it == edge_slots.end()) {
          edge_slots.emplace(keys[j], std::array<int, 4>{{tid, j, -1, -1}});
        } else {
          if (it->second[2] != -1) return false;  // edge in > 2 boundary faces
          it->second[2] = tid;
          it->second[3] = j;
        }
      }
    }
    // Every cone face at p is shared by two cone tetrahedra, or is one of the hull faces at p.
    std::size_t open = 0;
    for (const auto& kv : edge_slots) {
      const bool hull = std::binary_search(hull_edges.begin(), hull_edges.end(), kv.first);
      if ((kv.second[2] == -1) != hull) return false;
      open += hull ? 1 : 0;
    }
    if (open != hull_edges.size()) return false;
    // Commit.
    for (std::size_t k = 0; k < bf.size(); ++k) {
      const auto& f = bf[k];
      const int tid = new_tet({{f.a, f.c, f.b, p}});
      if (mirror_cavity) state[uz(tid)] = kOutside;  // the cone stays outside the body
      created.push_back(tid);
      nbr[uz(tid)][3] = f.outside;
      if (f.outside >= 0) {
        // Repoint the outside tet's neighbor (it pointed to the U tet behind this face).
        for (int j = 0; j < 4; ++j) {
          const int x = nbr[uz(f.outside)][uz(j)];
          if (x >= 0 && x < static_cast<int>(first_new) && mark[uz(x)] == in_u) {
            // the face of f.outside opposite j must be {a,b,c}
            const auto& w = tets[uz(f.outside)];
            const int opp = w[uz(j)];
            if (opp != f.a && opp != f.b && opp != f.c) nbr[uz(f.outside)][uz(j)] = tid;
          }
        }
      }
    }
    for (const auto& kv : edge_slots) {
      const auto& s = kv.second;
      nbr[uz(s[0])][uz(s[1])] = s[2];
      if (s[2] >= 0) nbr[uz(s[2])][uz(s[3])] = s[0];
    }
    for (int t : U) { state[uz(t)] = kReplaced; ++ver[uz(t)]; }
    for (int t : created)
      for (int x : tets[uz(t)]) vert_tet[uz(x)] = t;
    for (int t : created)
      if (!mirror_cavity && boundary_face(t, 3)) try_push(t);
    last_created.swap(created);
    last_target = tg.ids;
    // Alive tets outside U keep their faces; their removability is unchanged.
    ++cavities;
    if (visitor) {
      Constrict3Event e;
      e.kind = Constrict3Event::Kind::Cavity;
      e.point = p;
      e.cavity_size = U.size();
      e.stage = "cavity";
      visitor->on_event(e);
    }
    return true;
  }

  std::vector<int> last_created;  // the cone tetrahedra of the last successful try_cavity
  std::array<int, 3> last_target{};  // its target face (sorted ids)
  bool place_by_cavity(int p) {
    std::vector<int> star;
    if (!star_of(p, star)) return false;
    std::vector<Target> tg;
    for (int depth : {3, 8, 24}) {
      targets_of(p, star, depth, tg);
      const std::size_t tries = std::min<std::size_t>(tg.size(), depth == 3 ? 6 : 24);
      for (std::size_t k = 0; k < tries; ++k)
        if (try_cavity(p, star, tg[k])) return true;
    }
    return false;
  }

  // ---- Refine3 post-pass: energy-decreasing surface edge flips (docs/reconstruction-3d.md §4) --

  // Tets around the edge (tets[t][i], tets[t][j]), any state but replaced, t first. Walks both
  // ways when the ring is open (convex hull).
  void edge_ring(int t, int i, int j, std::vector<int>& out) const {
    out.clear();
    out.push_back(t);
    bool closed = false;
    for (int dir = 0; dir < 2 && !closed; ++dir)
      walk_edge(t, i, j, dir, [&](int nx) {
        if (nx < 0) return true;  // open ring: walk the other way
        if (nx == t) {
          closed = true;
          return true;
        }
        out.push_back(nx);
        return false;
      });
  }

  double face_energy(int a, int b, int c) const {
    const double* p = P(a);
    const double* q = P(b);
    const double* r = P(c);
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const double w[3] = {r[0] - q[0], r[1] - q[1], r[2] - q[2]};
    const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
    const double area2 = std::sqrt(cx * cx + cy * cy + cz * cz);  // twice the area
    if (energy == Refine3::Area) return 0.5 * area2;
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double lv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double lw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    if (!(area2 > 0)) return 1e300;
    return lu * lv * lw / (2.0 * area2);  // circumradius abc / (4 A)
  }

  double face_energy_of(int t, int i) const {
    const auto& v = tets[uz(t)];
    return face_energy(v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][1])], v[uz(kFaceOut[i][2])]);
  }

  // A flip through t: t (alive or removed) has exactly two faces on the surface, and the edge
  // joining the two vertices opposite them is not on the surface (alive t: spec §3.3 two-face
  // rule; removed t: its exact reverse, the edge touches no alive tet). Flipping replaces those two
  // surface faces by t's other two faces: an edge flip of the surface, so it stays a closed
  // genus-0 2-manifold through the same points. Returns the energy decrease, or -1.
  double flip_gain(int t) const {
    if (state[uz(t)] == kReplaced) return -1;
    const bool a = alive(t);
    int si[4], oi[4], ns = 0, no = 0;
    for (int i = 0; i < 4; ++i) {
      const bool on = a ? !alive(nbr[uz(t)][uz(i)]) : alive(nbr[uz(t)][uz(i)]);
      if (on) si[ns++] = i; else oi[no++] = i;
    }
    if (ns != 2) return -1;
    // The energy first (arithmetic on four points), the edge walk only for a shortening flip.
    const double e_old = face_energy_of(t, si[0]) + face_energy_of(t, si[1]);
    const double e_new = face_energy_of(t, oi[0]) + face_energy_of(t, oi[1]);
    const double gain = e_old - e_new;
    if (!(gain > 1e-9 * e_old)) return -1;  // relative margin: no flip-back cycles by rounding
    if (a) {
      if (edge_on_boundary(t, si[0], si[1])) return -1;
    } else if (edge_touches_body(t, si[0], si[1])) {
      return -1;
    }
    return gain;
  }

  std::size_t refine_added = 0, refine_removed = 0;
  Refine3 energy = Refine3::Area;

  void refine() {
    heap.clear();
    for (std::size_t t = 0; t < tets.size(); ++t) {
      const double g = flip_gain(static_cast<int>(t));
      if (g > 0) heap_push({g, static_cast<int>(t), ver[t]});
    }
    std::vector<int> ring, touched;
    const std::size_t cap = 20 * tets.size() + 100;  // guard; energy strictly decreases anyway
    for (std::size_t flips = 0; !heap.empty() && flips < cap;) {
      const Entry e = heap_pop();
      if (e.version != ver[uz(e.tet)]) continue;
      const double g = flip_gain(e.tet);
      if (g <= 0) continue;
      ++flips;
      const int t = e.tet;
      if (alive(t)) {
        state[uz(t)] = kOutside;
        ++refine_removed;
      } else {
        state[uz(t)] = kAlive;
        ++refine_added;
      }
      ++ver[uz(t)];
      // Candidates change only around t's edges: face neighbours change sides, and the surface
      // loses one edge and gains one (the removability of the tets around them changes).
      touched.clear();
      touched.push_back(t);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          edge_ring(t, i, j, ring);
          touched.insert(touched.end(), ring.begin(), ring.end());
        }
      std::sort(touched.begin(), touched.end());
      touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
      for (int x : touched) {
        ++ver[uz(x)];
        const double gx = flip_gain(x);
        if (gx > 0) heap_push({gx, x, ver[uz(x)]});
      }
    }
    heap.clear();
  }

  // ---- growth (docs/reconstruction-3d.md §4.7) ------------------------------------------------
  // The body grows from the inside instead of shrinking from the hull: it starts with the inside
  // tetrahedron of the largest circumradius and adds Delaunay tetrahedra only by the mirror
  // images of the removal rules, so it stays a triangulated ball: a tetrahedron glued along one
  // face whose fourth vertex is not yet in the body, or glued along two faces whose free edge is
  // not yet in the body (never three faces: that would bury a vertex). Every vertex in the body is
  // therefore on its surface. Order: tetrahedra labelled inside by the largest circumradius first
  // (from the medial axis outwards, which keeps the growth front from wrapping around pockets);
  // when none is left, a tetrahedron labelled outside only if it brings a new point into the
  // body (one-face rule), least confident first (thin parts the labels miss).
  std::vector<double> lrad;  // ln circumradius per Delaunay tetrahedron (labels), -1e300 if flat
  std::vector<char> queued;  // growth: in the heap (its key is static: one entry is enough)
  std::size_t grown = 0, grown_outside = 0;
  // 1 / 2: t can join the body glued along one / two faces; 0: it cannot.
  // one_face_only: only the one-face rule counts (no edge walk for the two-face rule).
  int addable(int t, bool one_face_only = false) const {
    int g[4], ng = 0;
    for (int i = 0; i < 4; ++i)
      if (alive(nbr[uz(t)][uz(i)])) g[ng++] = i;
    if (ng == 1) return onb[uz(tets[uz(t)][uz(g[0])])] ? 0 : 1;
    if (ng == 2 && !one_face_only) return edge_touches_body(t, g[0], g[1]) ? 0 : 2;
    return 0;
  }
  // Inside: 1000 + ln r (above every outside key); outside: 1 - confidence, in [0, 1].
  double grow_key(int t) const {
    const double l = (*label)[uz(t)];
    if (l < 0) return 1000.0 + std::max(-500.0, lrad[uz(t)]);
    return 1.0 - l;
  }
  void grow_add(int t) {
    state[uz(t)] = kAlive;
    ++ver[uz(t)];
    ++grown;
    for (int x : tets[uz(t)])
      if (!onb[uz(x)]) { onb[uz(x)] = 1; ++n_onb; }
    // A tetrahedron whose glued faces change is examined again; one heap entry per tetrahedron
    // suffices (static key), so the pop order is that of a re-push per change.
    for (int m : nbr[uz(t)])
      if (m >= 0 && uz(m) < T0 && !alive(m) && !queued[uz(m)]) {
        queued[uz(m)] = 1;
        heap_push({grow_key(m), m, 0});
      }
  }
  // Grows the body; true when every point is on its surface. The caller restores the hull state
  // otherwise (reset_to_hull).
  bool grow() {
    int seed = -1;  // largest circumradius, ties -> smallest sorted vertex ids (not the index)
    for (std::size_t t = 0; t < T0; ++t)
      if ((*label)[t] < 0 && lrad[t] > -1e300 &&
          (seed < 0 || lrad[t] > lrad[uz(seed)] || (lrad[t] == lrad[uz(seed)] && sorted4(tets[t]) < sorted4(tets[uz(seed)]))))
        seed = static_cast<int>(t);
    if (seed < 0) return false;
    state.assign(T0, kOutside);
    for (auto& v : ver) ++v;
    onb.assign(n, 0);
    n_onb = 0;
    heap.clear();
    queued.assign(T0, 0);
    grow_add(seed);
    while (!heap.empty()) {
      const Entry e = heap_pop();
      queued[uz(e.tet)] = 0;
      if (alive(e.tet)) continue;
      // Outside: the one-face rule only (its fourth vertex is a new point).
      const bool outside = !((*label)[uz(e.tet)] < 0);
      if (!addable(e.tet, outside)) continue;
      if (outside) ++grown_outside;
      grow_add(e.tet);
    }
    heap.clear();
    std::vector<char>().swap(queued);
    if (n_onb < n && opt.fallback != Fallback3::None) place_unreached();
    return n_onb == n;
  }
  // Growth lock: a point that no Delaunay tetrahedron can bring into the body (its star is cut
  // off from the body by tetrahedra whose fourth vertex is already in it) gets a cone over a body
  // face it sees: the star-cavity re-tetrahedralization of §3, mirrored to the outside of the body
  // (it re-tetrahedralizes a star-shaped region of outside tetrahedra, exactly, and leaves the
  // body unchanged); the cone tetrahedron over the body face then joins the body by the one-face
  // rule. Points in ascending id, passes while one succeeds.
  std::size_t grow_cavities = 0;
  std::vector<std::array<int, 4>> nbr_delaunay;  // adjacency before place_unreached (for a reset)
  void place_unreached() {
    nbr_delaunay = nbr;
    vert_tet.assign(n, -1);
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (state[t] == kOutside)
        for (int x : tets[t]) vert_tet[uz(x)] = static_cast<int>(t);
    const std::size_t cav0 = cavities, att0 = cavity_attempts;
    for (bool progress = true; progress && n_onb < n;) {
      progress = false;
      for (std::size_t p = 0; p < n; ++p) {
        if (onb[p]) continue;
        mirror_cavity = true;
        const bool ok = place_by_cavity(static_cast<int>(p));
        mirror_cavity = false;
        if (!ok) continue;
        // The cone over the target face (the best-ranked body face p sees) joins the body.
        int cone = -1;
        for (int t : last_created) {
          std::array<int, 3> base{{tets[uz(t)][0], tets[uz(t)][1], tets[uz(t)][2]}};
          std::sort(base.begin(), base.end());
          if (base == last_target) { cone = t; break; }
        }
        CONSTRICT_CHECK(cone >= 0 && alive(nbr[uz(cone)][3]), "growth cavity without a cone over its target face");
        state[uz(cone)] = kAlive;
        ++ver[uz(cone)];
        ++grown;
        for (int x : tets[uz(cone)])
          if (!onb[uz(x)]) { onb[uz(x)] = 1; ++n_onb; }
        ++grow_cavities;
        progress = true;
      }
    }
    cavities = cav0;  // (the constriction's fallback counts stay its own)
    cavity_attempts = att0;
  }
  // The state of init(): the whole tetrahedralization, the hull points on the boundary.
  void reset_to_hull() {
    if (tets.size() > T0) {  // undo the growth's cavities: the Delaunay tetrahedra again
      tets.resize(T0);
      nbr.swap(nbr_delaunay);
      nbr.resize(T0);
      ver.resize(T0);
      mark.resize(T0);
    }
    std::vector<std::array<int, 4>>().swap(nbr_delaunay);
    state.assign(T0, kAlive);
    for (auto& v : ver) ++v;
    onb.assign(n, 0);
    n_onb = 0;
    for (std::size_t t = 0; t < T0; ++t)
      for (int i = 0; i < 4; ++i)
        if (nbr[t][uz(i)] < 0)
          for (int k = 0; k < 3; ++k) {
            const int x = tets[t][uz(kFaceOut[i][k])];
            if (!onb[uz(x)]) { onb[uz(x)] = 1; ++n_onb; }
          }
    grown = grown_outside = grow_cavities = filled = 0;
    grew = false;
    heap.clear();
    hull_ready = false;
  }
  // The constriction from the hull needs the face terms, the spacing / bridge ratios (size bias)
  // and its initial heap; they are made on first use, so a growth that reaches every point does
  // not pay for them.
  bool need_size = false, hull_ready = false, stepped = false, grow_only = false, grew = false;
  // The options ask for the growth (decided before the tetrahedralization: init builds the DT
  // alone then); it runs when the labels exist and some point is inside the hull (else the hull
  // itself is the answer).
  bool grow_planned() const {
    return opt.grow && opt.criterion == Criterion::Gamma && opt.stop_after == SIZE_MAX && opt.sculpt == Sculpt3::None;
  }
  bool can_grow() const { return grow_planned() && label && n_hull < n; }
  void ensure_hull_start() {
    if (hull_ready) return;
    auto t0 = Clock::now();
    if (!dgp) {
      // Same builder, same input: the same tetrahedra in the same order (checked).
      auto dg = std::make_shared<DelaunayGamma3>();
      const Status st = delaunay_gamma3(*pts, *dg, false);
      CONSTRICT_CHECK(st.is_ok() && dg->dt.tets.size() == T0 && std::equal(dg->dt.tets.begin(), dg->dt.tets.end(), tets.begin()),
                      "the γ pass did not reproduce the tetrahedralization");
      dg->dt = Delaunay3{};
      dgp = std::move(dg);
      ms_delaunay += ms_since(t0);
      t0 = Clock::now();
    }
    if (!terms) compute_terms();
    if (need_size && !face_log) {
      compute_spacing();
      compute_face_log();
    }
    start_heap();
    hull_ready = true;
    ms_setup += ms_since(t0);
  }

  // ---- carve pass: remove the surface-connected tetrahedra labelled outside ------------------
  // (docs/reconstruction-3d.md §4.6). The constriction rules keep the surface a 2-manifold at
  // every single removal, which blocks the "bridges": regions labelled outside whose vertices are
  // all on the surface already (removing any of their tetrahedra pinches a vertex). Here each
  // connected region of outside tetrahedra is carved from the surface inwards, through
  // non-manifold intermediate states, and the state is kept only where it is valid again:
  // every vertex touched has a single-cycle surface link (vertex- and edge-manifold, still in
  // the body) and the surface has 2N-4 faces (Euler characteristic 2). The region's removals
  // after its last valid state are undone. Connectivity is checked once at the end.
  std::vector<int> vt_off, vt_idx;  // alive tets per vertex at the start of the carve (CSR)
  std::size_t carved = 0, carve_regions = 0, carve_undone = 0, filled = 0;
  // all: every tetrahedron that can be in the body (the fill adds tetrahedra), else the alive ones.
  void build_vt(bool all) {
    const auto in = [&](std::size_t t) { return all ? state[t] != kReplaced : state[t] == kAlive; };
    vt_off.assign(n + 1, 0);
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (in(t))
        for (int x : tets[t]) ++vt_off[uz(x) + 1];
    for (std::size_t v = 0; v < n; ++v) vt_off[v + 1] += vt_off[v];
    vt_idx.assign(uz(vt_off[n]), 0);
    std::vector<int> fill(vt_off.begin(), vt_off.end() - 1);
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (in(t))
        for (int x : tets[t]) vt_idx[uz(fill[uz(x)]++)] = static_cast<int>(t);
  }
  // Is the surface around v a single disk (the link of v one simple cycle)?
  bool vertex_manifold(int v, std::vector<std::array<int, 2>>& link) const {
    link.clear();
    for (int k = vt_off[uz(v)]; k < vt_off[uz(v) + 1]; ++k) {
      const int t = vt_idx[uz(k)];
      if (!alive(t)) continue;
      const int li = local_index(t, v);
      for (int i = 0; i < 4; ++i) {
        if (i == li || alive(nbr[uz(t)][uz(i)])) continue;
        std::array<int, 2> e{};
        int c = 0;
        for (int l = 0; l < 4; ++l)
          if (l != i && l != li) e[uz(c++)] = tets[uz(t)][uz(l)];
        link.push_back(e);
      }
    }
    if (link.size() < 3) return false;
    // Every link vertex of degree 2, and one cycle through all link edges.
    std::size_t steps = 0;
    int cur = link[0][1];
    std::size_t cur_e = 0;
    for (;;) {
      std::size_t next_e = SIZE_MAX;
      int deg = 0;
      for (std::size_t j = 0; j < link.size(); ++j)
        if (link[j][0] == cur || link[j][1] == cur) {
          ++deg;
          if (j != cur_e) next_e = j;
        }
      if (deg != 2) return false;
      ++steps;
      const int nx = link[next_e][0] == cur ? link[next_e][1] : link[next_e][0];
      cur = nx;
      cur_e = next_e;
      if (cur_e == 0) break;
      if (steps > link.size()) return false;
    }
    return steps == link.size();
  }
  int surface_faces_of(int t) const {
    int k = 0;
    for (int i = 0; i < 4; ++i) k += boundary_face(t, i) ? 1 : 0;
    return k;
  }
  // Keeps vertex x's "not manifold" flag and the count of such vertices up to date.
  void update_bad(int x, std::vector<char>& bad_of, std::size_t& nbad, std::vector<std::array<int, 2>>& link) const {
    const char b = vertex_manifold(x, link) ? 0 : 1;
    if (b != bad_of[uz(x)]) {
      nbad = b ? nbad + 1 : nbad - 1;
      bad_of[uz(x)] = b;
    }
  }
  // Body (side = kAlive): is it one face-connected piece? Outside (side = kOutside): does every
  // tetrahedron outside the body reach the convex hull through outside tetrahedra (no enclosed
  // void)? One breadth-first search from the first body tetrahedron / from the hull.
  bool side_connected(std::uint8_t side) const {
    std::vector<char> seen(tets.size(), 0);
    std::vector<int> st;
    for (std::size_t t = 0; t < tets.size(); ++t) {
      if (state[t] != side) continue;
      bool start = side == kAlive;
      for (int m : nbr[t]) start = start || m < 0;
      if (start) {
        seen[t] = 1;
        st.push_back(static_cast<int>(t));
        if (side == kAlive) break;
      }
    }
    if (side == kAlive && st.empty()) return false;
    while (!st.empty()) {
      const int t = st.back();
      st.pop_back();
      for (int m : nbr[uz(t)])
        if (m >= 0 && state[uz(m)] == side && !seen[uz(m)]) { seen[uz(m)] = 1; st.push_back(m); }
    }
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (state[t] == side && !seen[t]) return false;
    return true;
  }
  // Carve (fill = false): remove the surface-connected regions of tetrahedra labelled outside
  // with confidence >= min_conf. Fill (fill = true): the mirror image, add the regions of
  // Delaunay tetrahedra labelled inside (confidence >= min_conf) that the body left out.
  void carve(double min_conf, bool fill = false) {
    if (!label) return;
    if (fill) {
      // Nothing to fill (the usual case): no left-out inside tetrahedron touches the body.
      bool any = false;
      for (std::size_t t = 0; t < T0 && !any; ++t) {
        if (state[t] != kOutside || !((*label)[t] <= -min_conf)) continue;
        for (int m : nbr[t]) any = any || alive(m);
      }
      if (!any) return;
    }
    build_vt(fill);
    const std::vector<std::uint8_t> state0 = state;
    std::size_t F = 0;
    std::vector<int> alive_at(n, 0);  // body tetrahedra per vertex
    for (std::size_t t = 0; t < tets.size(); ++t)
      if (state[t] == kAlive) {
        F += uz(surface_faces_of(static_cast<int>(t)));
        for (int x : tets[t]) ++alive_at[uz(x)];
      }
    const std::size_t targetF = 2 * n - 4;
    if (F != targetF) return;
    // A vertex whose body tetrahedra are all labelled outside (a thin part the labels miss)
    // keeps one of them, its anchor: the one with the shortest longest edge.
    const auto outside = [&](std::size_t t) { return t < T0 && (*label)[t] >= min_conf; };
    std::vector<char> anchor(tets.size(), 0);
    if (!fill) {
      std::vector<char> keep_v(n, 1);
      for (std::size_t t = 0; t < tets.size(); ++t)
        if (state[t] == kAlive && !outside(t))
          for (int x : tets[t]) keep_v[uz(x)] = 0;
      std::vector<double> best(n, HUGE_VAL);
      std::vector<int> arg(n, -1);
      for (std::size_t t = 0; t < tets.size(); ++t) {
        if (state[t] != kAlive) continue;
        const auto& v = tets[t];
        double le = 0;
        for (int i = 0; i < 4; ++i)
          for (int j = i + 1; j < 4; ++j) {
            const double* a = P(v[uz(i)]);
            const double* b = P(v[uz(j)]);
            le = std::max(le, (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
          }
        for (int x : v)
          if (keep_v[uz(x)] && le < best[uz(x)]) { best[uz(x)] = le; arg[uz(x)] = static_cast<int>(t); }
      }
      for (std::size_t v = 0; v < n; ++v)
        if (arg[v] >= 0) anchor[uz(arg[v])] = 1;
    }
    const auto cand = [&](int t) {
      if (fill) return uz(t) < T0 && state[uz(t)] == kOutside && (*label)[uz(t)] <= -min_conf;
      return alive(t) && outside(uz(t)) && !anchor[uz(t)];
    };
    // Label order: most confident first (outside: largest label; inside: smallest).
    const auto prio = [&](int t) { return fill ? -(*label)[uz(t)] : (*label)[uz(t)]; };
    std::vector<char> seen(tets.size(), 0), bad_of(n, 0), dirty(n, 0);
    std::vector<int> dirty_list;
    std::size_t nbad = 0;
    std::vector<int> region, pending;
    std::vector<std::array<int, 2>> link;
    const auto toggle = [&](int t, bool make_alive) {
      if (make_alive) {
        for (int x : tets[uz(t)]) ++alive_at[uz(x)];
        state[uz(t)] = kAlive;
        F = F - 4 + 2 * uz(surface_faces_of(t));
      } else {
        F = F + 4 - 2 * uz(surface_faces_of(t));
        for (int x : tets[uz(t)]) --alive_at[uz(x)];
        state[uz(t)] = kOutside;
      }
      ++ver[uz(t)];
      for (int x : tets[uz(t)])
        if (!dirty[uz(x)]) { dirty[uz(x)] = 1; dirty_list.push_back(x); }
    };
    // The manifold flags of the vertices touched since the last flush are evaluated lazily: a
    // valid state needs F == 2N-4 first (O(1)), so long invalid runs (a genus-1 hole carved
    // through, high-degree vertices) do not pay a link evaluation per toggle.
    const auto flush = [&]() {
      for (int x : dirty_list) {
        dirty[uz(x)] = 0;
        update_bad(x, bad_of, nbad, link);
      }
      dirty_list.clear();
    };
    const auto valid_now = [&]() {
      if (F != targetF) return false;
      flush();
      return nbad == 0;
    };
    for (std::size_t s0 = 0; s0 < T0; ++s0) {
      if (seen[s0] || !cand(static_cast<int>(s0))) continue;
      // The face-connected region of outside tetrahedra around s0.
      region.clear();
      region.push_back(static_cast<int>(s0));
      seen[s0] = 1;
      bool touches_surface = false;
      for (std::size_t q = 0; q < region.size(); ++q)
        for (int m : nbr[uz(region[q])]) {
          if (fill ? alive(m) : !alive(m)) touches_surface = true;
          else if (m >= 0 && !seen[uz(m)] && cand(m)) { seen[uz(m)] = 1; region.push_back(m); }
        }
      if (!touches_surface) continue;
      ++carve_regions;
      // Most confident first, ties -> smaller id; a tetrahedron is removed once it has a surface
      // face (no cavities) and is not the last body tetrahedron of a vertex.
      std::priority_queue<std::pair<float, int>> pq;
      // (fill: a tetrahedron outside the body is glued to it iff it has fewer than 4 surface faces)
      const auto at_front = [&](int t) { return fill ? !alive(t) && surface_faces_of(t) < 4 : alive(t) && surface_faces_of(t) > 0; };
      for (int t : region)
        if (at_front(t)) pq.push({prio(t), -t});
      pending.clear();
      while (!pq.empty()) {
        const int t = -pq.top().second;
        pq.pop();
        if (!at_front(t)) continue;
        bool last = false;
        for (int x : tets[uz(t)]) last = last || (!fill && alive_at[uz(x)] == 1);
        if (last) continue;
        toggle(t, fill);
        pending.push_back(t);
        for (int m : nbr[uz(t)])
          if (m >= 0 && cand(m)) pq.push({prio(m), -m});
        if (valid_now()) pending.clear();  // a valid state: keep it
      }
      flush();
      // Repair: put back removed tetrahedra at the vertices that are not manifold, latest removal
      // first, a few rounds; keep the state if it is valid then.
      for (int round = 0; round < 16 && nbad > 0 && !pending.empty(); ++round)
        for (std::size_t j = pending.size(); j-- > 0 && nbad > 0;) {
          const int t = pending[j];
          if (alive(t) != fill) continue;
          bool at_bad = false;
          for (int x : tets[uz(t)]) at_bad = at_bad || bad_of[uz(x)];
          if (at_bad) {
            toggle(t, !fill);
            flush();
          }
        }
      std::vector<int> still;
      for (int t : pending)
        if (alive(t) == fill) still.push_back(t);
      if (nbad == 0 && F == targetF) still.clear();
      // Undo back to the last valid state.
      carve_undone += still.size();
      // (flush re-evaluates every vertex a toggle touched: the only ones whose links change.)
      for (auto it = still.rbegin(); it != still.rend(); ++it) toggle(*it, !fill);
      flush();
      CONSTRICT_CHECK(F == targetF && nbad == 0, "carve undo did not restore the surface");
    }
    if (fill) {
      // Every region ends valid (2N-4 faces, manifold vertices); a torus-shaped enclosed void
      // would also have 2N-4 faces in total: excluded here (then the whole pass is undone).
      filled = 0;
      for (std::size_t t = 0; t < state0.size(); ++t)
        if (state0[t] != kAlive && state[t] == kAlive) ++filled;
      if (filled > 0 && !side_connected(kOutside)) {  // (nothing kept: the state is the start state)
        state = state0;
        filled = 0;
      }
      return;
    }
    // Every region ends valid and genus 0 (2N-4 faces); a split into a sphere and a torus would
    // also have 2N-4 faces: excluded here (then the whole pass is undone).
    if (!side_connected(kAlive)) {
      state = state0;
      carved = 0;
      return;
    }
    carved = 0;
    for (std::size_t t = 0; t < state0.size(); ++t)
      if (state0[t] == kAlive && state[t] != kAlive) ++carved;
    removed += carved;
  }

  // ---- validation of the body -------------------------------------------------------------
  void check_body() const {
    for (std::size_t t = 0; t < tets.size(); ++t) {
      if (state[t] != kAlive) continue;
      const auto& v = tets[t];
      CONSTRICT_CHECK(orient3(P(v[0]), P(v[1]), P(v[2]), P(v[3])) > 0, "body tetrahedron not positive");
      for (int i = 0; i < 4; ++i) {
        const int m = nbr[t][uz(i)];
        if (!alive(m)) continue;
        int j = -1;
        for (int l = 0; l < 4; ++l)
          if (nbr[uz(m)][uz(l)] == static_cast<int>(t)) j = l;
        CONSTRICT_CHECK(j >= 0, "body adjacency not symmetric");
        std::array<int, 3> f1{}, f2{};
        int k1 = 0, k2 = 0;
        for (int l = 0; l < 4; ++l) {
          if (l != i) f1[uz(k1++)] = v[uz(l)];
          if (l != j) f2[uz(k2++)] = tets[uz(m)][uz(l)];
        }
        std::sort(f1.begin(), f1.end());
        std::sort(f2.begin(), f2.end());
        CONSTRICT_CHECK(f1 == f2, "body neighbours do not share the face");
      }
    }
  }
};

Constrictor3::Constrictor3() : impl_(std::make_unique<Impl>()) {}
Constrictor3::~Constrictor3() = default;

Status Constrictor3::init(const PointSet& points, const Constrict3Options& options,
                          Constrict3Visitor* visitor) {
  Impl& s = *impl_;
  s = Impl{};
  if (points.dim != 3) return {StatusCode::InvalidArgument, "reconstruct3 needs 3D points"};
  if (!(options.sculpt_threshold >= 0 && options.sculpt_threshold <= 4))
    return {StatusCode::InvalidArgument, "sculpt_threshold must be in [0, 4]"};
  if (!(options.size_bias >= 0 && options.size_bias <= 100 && options.label_weight >= 0 && options.label_weight <= 100))
    return {StatusCode::InvalidArgument, "size_bias and label_weight must be in [0, 100]"};
  if (Status st = check_points(points); !st) return st;
  s.pts = &points;
  // Far from 1 in magnitude, the double parts (γ magnitudes, circumballs, lengths) would overflow
  // or underflow: work on a copy scaled by a power of two, which changes no predicate and makes
  // every magnitude scale free (the result is then the same at any scale); areas and volumes are
  // scaled back in finish.
  {
    double m = 0;
    for (double c : points.coords) m = std::max(m, std::abs(c));
    int e = 0;
    std::frexp(m, &e);
    if (e > 64 || e < -64) {
      auto scaled = std::make_shared<PointSet>(points);
      for (double& c : scaled->coords) c = std::ldexp(c, -e);
      s.scale_exp = e;
      s.pts = scaled.get();
      s.scaled = std::move(scaled);
    }
  }
  s.opt = options;
  s.visitor = visitor;
  s.n = points.size();
  const auto t0 = Clock::now();
  if (s.grow_planned()) {
    // The growth reads the tetrahedralization and the labels only: the γ-values are computed
    // when the constriction from the hull needs them (ensure_hull_start).
    Delaunay3 dt;
    if (Status st = build_delaunay3(*s.pts, dt); !st) return st;
    s.tets = std::move(dt.tets);
    s.nbr = std::move(dt.neighbors);
  } else {
    auto dg = std::make_shared<DelaunayGamma3>();
    // The DT faces only: the co-spherical completion (every triple of a co-spherical cluster) is
    // part of the γ graph, not of the tetrahedralization the constriction carves.
    if (Status st = delaunay_gamma3(*s.pts, *dg, false); !st) return st;
    s.tets = std::move(dg->dt.tets);
    s.nbr = std::move(dg->dt.neighbors);
    dg->dt = Delaunay3{};
    s.dgp = std::move(dg);
  }
  s.ms_delaunay = ms_since(t0);
  s.T0 = s.tets.size();
  const auto t_setup = Clock::now();
  bool need_size = s.opt.size_bias > 0 || s.opt.sculpt == Sculpt3::Bridges,
       need_label = s.opt.label_weight > 0 || (s.opt.carve_confidence <= 1 && s.opt.criterion == Criterion::Gamma) ||
                    s.grow_planned();
  for (const Constrict3Variant& v : s.opt.variants) {
    need_size = need_size || v.size_bias > 0;
    need_label = need_label || v.label_weight > 0;
  }
  s.need_size = need_size;
  if (need_label) s.compute_labels();
  s.ms_setup = ms_since(t_setup);
  s.ver.assign(s.T0, 0);
  s.mark.assign(s.T0, 0);
  s.heap.reserve(s.T0 / 4 + 16);
  s.reset_to_hull();
  s.n_hull = s.n_onb;
  // (Every point on the hull after a DT-only build: nothing will be removed, so no γ pass and
  // no second tetrahedralization; the post-passes do not read γ.)
  if (!s.can_grow() && (s.dgp || s.n_onb < s.n)) s.ensure_hull_start();
  s.ready = true;
  return Status::ok();
}

bool Constrictor3::step() { return impl_->step(); }

TriMesh3 Constrictor3::surface() const { return impl_->surface(); }

std::vector<int> Constrictor3::inside_points() const { return impl_->inside(); }

Status Constrictor3::finish(Mesh3Result& r) { return finish_impl(*impl_, r, impl_->opt.validate); }

Status Constrictor3::finish_impl(Impl& s, Mesh3Result& r, bool validate) {
  if (!s.ready) return {StatusCode::Internal, "Constrictor3::finish before a successful init"};
  r = Mesh3Result{};
  r.size_bias = s.opt.size_bias;
  r.label_weight = s.opt.label_weight;
  r.ms_delaunay = s.ms_delaunay;
  r.ms_setup = s.ms_setup;
  r.delaunay_tets = s.T0;
  auto stage_event = [&](const char* name) {
    if (!s.visitor) return;
    Constrict3Event e;
    e.kind = Constrict3Event::Kind::StageBegin;
    e.stage = name;
    s.visitor->on_event(e);
  };
  r.stages.push_back({"hull", s.n_hull, 0});
  // (1) Delaunay constriction (the caller may have stepped already).
  auto t0 = Clock::now();
  // (0) Growth from the inside (§4.7), only from the untouched initial state.
  // Once per state: a second finish() returns the grown body again (the growth and the fill
  // assume the Delaunay tetrahedralization they start from).
  bool grown = s.grew;
  if (!grown && s.can_grow() && !s.stepped) {
    stage_event("grow");
    grown = s.grow();
    s.stepped = true;
    r.ms_grow = ms_since(t0);
    if (grown) {
      s.grew = true;
      stage_event("fill");
      t0 = Clock::now();
      s.carve(s.opt.carve_confidence <= 1 ? s.opt.carve_confidence : 0.5, true);
      r.ms_fill = ms_since(t0);
    } else {
      r.grow_unreached = s.n - s.n_onb;
      s.reset_to_hull();
      if (s.grow_only) {
        r.method = "grow-incomplete";
        return Status::ok();
      }
    }
    t0 = Clock::now();
  }
  if (grown) {
    r.grown = s.grown;
    r.grow_cavities = s.grow_cavities;
    r.grown_outside = s.grown_outside;
    r.filled = s.filled;
    r.stages.push_back({"grow", s.n - s.n_hull, 0});
    r.stages.push_back({"fill", 0, 0});
  }
  while (!grown && s.step()) {
  }
  r.ms_constrict = ms_since(t0);
  if (!grown) r.stages.push_back({"gamma", s.n_onb - s.n_hull, s.removed});
  r.method = grown ? "grow" : "gamma";
  if (s.n_onb < s.n && !s.stopped) {
    r.locked = true;
    r.stuck_points = s.inside();
    // (2) fallback
    if (s.opt.fallback == Fallback3::Auto) {
      stage_event("cavity");
      t0 = Clock::now();
      const std::size_t onb0 = s.n_onb, rem0 = s.removed;
      s.build_vert_tet();
      bool progress = true;
      while (s.n_onb < s.n && progress) {
        progress = false;
        for (int p : s.inside()) {
          if (s.onb[uz(p)]) continue;
          if (s.place_by_cavity(p)) {
            progress = true;
            while (s.pop_and_remove(-1e300, "cavity")) {
              if (s.n_onb == s.n) break;
            }
            if (s.n_onb == s.n) break;
          }
        }
      }
      r.ms_fallback = ms_since(t0);
      r.stages.push_back({"cavity", s.n_onb - onb0, s.removed - rem0});
      if (s.n_onb > onb0) r.method = "cavity";
    }
  }
  r.complete = s.n_onb == s.n;
  if (!r.complete) r.method = s.stopped ? "stopped" : "locked";
  if (r.complete && !grown && s.opt.carve_confidence <= 1 && s.opt.criterion == Criterion::Gamma && s.label) {
    stage_event("carve");
    t0 = Clock::now();
    s.carve(s.opt.carve_confidence);
    r.ms_carve = ms_since(t0);
    r.carved = s.carved;
    r.carve_undone = s.carve_undone;
    r.stages.push_back({"carve", 0, s.carved});
  }
  // (3) sculpting post-pass (only on complete surfaces: all points stay on the boundary since
  // two-face removals add no point and remove none).
  if (r.complete && s.opt.sculpt == Sculpt3::TwoFace) {
    stage_event("sculpt");
    t0 = Clock::now();
    const std::size_t rem0 = s.removed, r2 = s.removed2;
    while (s.pop_and_remove(s.opt.sculpt_threshold, "sculpt")) {
    }
    CONSTRICT_CHECK(s.removed - rem0 == s.removed2 - r2, "sculpting removed a one-face tetrahedron");
    s.removed_sculpt = s.removed - rem0;
    r.ms_sculpt = ms_since(t0);
    r.stages.push_back({"sculpt", 0, s.removed_sculpt});
  }
  // (4) Refine3 flip post-pass (complete surfaces only).
  if (r.complete && !grown && s.opt.refine != Refine3::None) {
    stage_event("refine");
    t0 = Clock::now();
    s.energy = s.opt.refine == Refine3::Alternate ? Refine3::Area : s.opt.refine;
    s.refine();
    if (s.opt.refine == Refine3::Alternate) {
      // The local minimum of one energy is usually not one of the other: one more Circumradius
      // pass, then Area again. Further rounds only ping-pong (measured: +0.2 % of GT triangles at
      // 2.5 x the time; docs/reconstruction-3d.md §4.1).
      s.energy = Refine3::Circumradius;
      s.refine();
      s.energy = Refine3::Area;
      s.refine();
    }
    r.ms_refine = ms_since(t0);
    r.stages.push_back({"refine", 0, s.refine_removed});
  }
  // (5) Bridge sculpting after the flips (the area flips keep big bridging faces).
  if (r.complete && s.opt.sculpt == Sculpt3::Bridges) {
    stage_event("sculpt");
    t0 = Clock::now();
    const std::size_t rem0 = s.removed;
    s.bridge_keys = true;
    s.heap.clear();
    for (std::size_t t = 0; t < s.tets.size(); ++t)
      if (s.state[t] == kAlive) s.try_push(static_cast<int>(t));
    while (s.pop_and_remove(s.opt.bridge_ratio, "sculpt")) {
    }
    s.bridge_keys = false;
    s.heap.clear();
    s.removed_sculpt = s.removed - rem0;
    r.ms_sculpt = ms_since(t0);
    r.stages.push_back({"sculpt", 0, s.removed_sculpt});
  }
  r.refine_added = s.refine_added;
  r.refine_removed = s.refine_removed;
  r.removed_one_face = s.removed1;
  r.removed_two_face = s.removed2;
  r.removed_sculpt = s.removed_sculpt;
  r.cavities = s.cavities;
  r.cavity_attempts = s.cavity_attempts;
  r.unplaced_points = s.inside();
  r.mesh = s.surface();
  for (std::size_t t = 0; t < s.tets.size(); ++t)
    if (s.state[t] == kAlive) {
      r.tets.push_back(s.tets[t]);
      if (t >= s.T0) ++r.non_delaunay_tets;
    }
  r.ms_setup = s.ms_setup;  // (the hull start may have been made on demand, with the γ pass)
  r.ms_delaunay = s.ms_delaunay;
  r.volume = std::ldexp(mesh_volume(*s.pts, r.mesh), 3 * s.scale_exp);
  r.surface_area = std::ldexp(mesh_area(*s.pts, r.mesh), 2 * s.scale_exp);
  if (validate) validate_result(s, r);
  return Status::ok();
}

void Constrictor3::validate_result(Impl& s, Mesh3Result& r) {
  const auto t0 = Clock::now();
  s.check_body();
  MeshCheckOptions mo;
  mo.require_all_points = r.complete;
  mo.self_intersections = s.opt.validate_self_intersections;
  MeshCheck mc;
  const Status vs = validate_mesh3(*s.pts, r.mesh, &mc, mo);
  CONSTRICT_CHECK(vs.is_ok(), "reconstruct3 produced an invalid surface: " + vs.message());
  r.ms_validate = ms_since(t0);
}

Status reconstruct3(const PointSet& points, const Constrict3Options& options, Mesh3Result& result,
                    Constrict3Visitor* visitor) {
  Constrictor3 c;
  const std::vector<Constrict3Variant>& cand = options.variants;
  for (const Constrict3Variant& v : cand)
    if (!(v.size_bias >= 0 && v.size_bias <= 100 && v.label_weight >= 0 && v.label_weight <= 100))
      return {StatusCode::InvalidArgument, "variants: size_bias and label_weight must be in [0, 100]"};
  if (!(options.size_bias >= 0 && options.size_bias <= 100 && options.label_weight >= 0 && options.label_weight <= 100))
    return {StatusCode::InvalidArgument, "size_bias and label_weight must be in [0, 100]"};
  // The size bias and the labels only enter the γ-type keys: min-area-change runs once.
  if (cand.size() < 2 || options.stop_after != SIZE_MAX || options.criterion == Criterion::MinAreaChange) {
    Constrict3Options o = options;
    if (!cand.empty()) {
      o.size_bias = cand[0].size_bias;
      o.label_weight = cand[0].label_weight;
    }
    o.variants.clear();
    if (Status s = c.init(points, o, visitor); !s) return s;
    return c.finish(result);
  }
  return c.run_candidates(points, options, result, visitor);
}

// One constriction per size-bias candidate from the same Delaunay tetrahedralization (shared,
// read-only), in parallel; the complete result with the smallest surface area wins, ties -> the
// earlier candidate (docs/reconstruction-3d.md §4.5). Each run is independent and sequential, so
// the choice does not depend on the thread count.
Status Constrictor3::run_candidates(const PointSet& points, const Constrict3Options& options,
                                    Mesh3Result& result, Constrict3Visitor* visitor) {
  Constrict3Options o = options;
  o.size_bias = options.variants[0].size_bias;
  o.label_weight = options.variants[0].label_weight;
  if (Status s = init(points, o, nullptr); !s) return s;
  std::size_t grow_unreached = 0;
  if (impl_->can_grow()) {
    // Growth first (§4.7): when it reaches every point, its surface is the result.
    Mesh3Result rg;
    impl_->grow_only = true;
    impl_->visitor = visitor;  // (stage events; the parallel variant runs below report none)
    const Status sg = finish_impl(*impl_, rg, false);
    impl_->visitor = nullptr;
    impl_->grow_only = false;
    if (!sg) return sg;
    if (rg.method == "grow") {
      result = std::move(rg);
      if (options.validate) validate_result(*impl_, result);
      return Status::ok();
    }
    impl_->opt.grow = false;  // the variants below start from the hull (reset by finish_impl)
    grow_unreached = rg.grow_unreached;
  }
  if (!impl_->dgp && impl_->n_onb == impl_->n) {
    // Every point on the convex hull: the variants would only differ in keys nothing uses.
    impl_->visitor = visitor;
    const Status sh = finish_impl(*impl_, result, false);
    impl_->visitor = nullptr;
    if (!sh) return sh;
    if (options.validate) validate_result(*impl_, result);
    return Status::ok();
  }
  if (visitor) {
    Constrict3Event e;
    e.kind = Constrict3Event::Kind::StageBegin;
    e.stage = "candidates";
    visitor->on_event(e);
  }
  impl_->ensure_hull_start();  // shared face terms and bridge ratios, before the copies
  const std::vector<Constrict3Variant>& cand = options.variants;
  const std::size_t k = cand.size();
  std::vector<Mesh3Result> res(k);
  std::vector<std::unique_ptr<Impl>> runs(k);
  std::vector<Status> st(k);
  const auto tv = Clock::now();
  tbb::parallel_for(std::size_t(0), k, [&](std::size_t i) {
    runs[i] = std::make_unique<Impl>(*impl_);
    runs[i]->opt.size_bias = cand[i].size_bias;
    runs[i]->opt.label_weight = cand[i].label_weight;
    runs[i]->start_heap();
    st[i] = finish_impl(*runs[i], res[i], false);
    // Keep only what the winner needs: the choice uses the result alone.
  });
  std::size_t best = k;
  for (std::size_t i = 0; i < k; ++i) {
    if (!st[i]) return st[i];
    if (best == k || (res[i].complete && !res[best].complete) ||
        (res[i].complete == res[best].complete && res[i].surface_area < res[best].surface_area))
      best = i;
  }
  std::vector<Constrict3Candidate> summary;
  for (std::size_t i = 0; i < k; ++i)
    summary.push_back({cand[i].size_bias, cand[i].label_weight, res[i].surface_area, res[i].complete, res[i].ms_constrict + res[i].ms_fallback +
                                                                           res[i].ms_sculpt + res[i].ms_carve + res[i].ms_refine});
  const double ms_runs = ms_since(tv);
  result = std::move(res[best]);
  result.grow_unreached = grow_unreached;
  result.candidates = std::move(summary);
  result.ms_variants = ms_runs;
  result.ms_setup = impl_->ms_setup;
  if (options.validate) validate_result(*runs[best], result);
  return Status::ok();
}

}  // namespace constrict
