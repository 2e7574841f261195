// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "gamma" of the 3D engine: the γ-constriction of the Delaunay tetrahedralization from the
// convex hull (seed paper §4.2, §5; spec gamma-graph.md §3.1-3.5), its keys, and the sculpting
// passes that reuse its removal rules.
#include <algorithm>
#include <cmath>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "constrict/criterion.hpp"
#include "constrict/detail/stages3.hpp"
#include "constrict/gamma_graph.hpp"

namespace constrict::detail {
namespace {

constexpr std::size_t kTermGrain = 8192, kFaceGrain = 16384;

// Sign of the permutation (a, b, c, d) of (0, 1, 2, 3).
int parity4(int a, int b, int c, int d) {
  const int v[4] = {a, b, c, d};
  int inv = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inv += v[i] > v[j];
  return (inv & 1) ? -1 : 1;
}

// 1 - γ(face opposite i; apex tets[t][i]) (spec gamma-graph.md §3.2, §3.4). For a Delaunay tet
// this is the stored side value of the face on the side of the apex (spec §2.3); cavity tets use
// the apex value directly.
double face_term_compute(const Body3& b, const DelaunayGamma3* dg, int t, int i) {
  const auto& v = b.tets[uz(t)];
  if (uz(t) < b.T0) {
    const int f = dg->simplex_face[uz(t)][uz(i)];
    std::array<std::pair<int, int>, 3> fv{};
    int k = 0;
    for (int l = 0; l < 4; ++l)
      if (l != i) fv[uz(k++)] = {v[uz(l)], l};
    std::sort(fv.begin(), fv.end());
    const int side = parity4(fv[0].second, fv[1].second, fv[2].second, i);
    const double g = side > 0 ? dg->faces.gamma_a[uz(f)] : dg->faces.gamma_b[uz(f)];
    return 1.0 - g;
  }
  const int* fo = kFaceOut[i];
  return 1.0 - apex_gamma3(b.P(v[uz(fo[0])]), b.P(v[uz(fo[1])]), b.P(v[uz(fo[2])]), b.P(v[uz(i)]));
}

}  // namespace

std::shared_ptr<const std::vector<std::array<double, 4>>> compute_face_terms3(const Body3& b, const DelaunayGamma3& dg) {
  auto out = std::make_shared<std::vector<std::array<double, 4>>>(b.T0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, b.T0, kTermGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t)
      for (int i = 0; i < 4; ++i) (*out)[t][uz(i)] = face_term_compute(b, &dg, static_cast<int>(t), i);
  });
  return out;
}

double bridge_ratio3(const PointSet& pts, const std::vector<double>& spacing, int a, int b, int c) {
  const auto d2 = [&](int x, int y) {
    const double dx = pts[uz(x)][0] - pts[uz(y)][0], dy = pts[uz(x)][1] - pts[uz(y)][1], dz = pts[uz(x)][2] - pts[uz(y)][2];
    return dx * dx + dy * dy + dz * dz;
  };
  const double longest = std::sqrt(std::max({d2(a, b), d2(b, c), d2(c, a)}));
  const double h = std::max({spacing[uz(a)], spacing[uz(b)], spacing[uz(c)]});
  return h > 0 ? longest / h : 0;
}

double bridge_ratio3(const PointSet& pts, const std::vector<double>& spacing, const std::array<int, 4>& t) {
  double longest = 0, h = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    h = std::max(h, spacing[uz(t[i])]);
    for (std::size_t j = i + 1; j < 4; ++j) {
      const double* p = pts[uz(t[i])];
      const double* q = pts[uz(t[j])];
      longest = std::max(longest, (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    }
  }
  return h > 0 ? std::sqrt(longest) / h : 0;
}

std::shared_ptr<const std::vector<double>> compute_face_log3(const Body3& b, const DelaunayGamma3& dg,
                                                             const std::vector<double>& spacing) {
  const GammaFaces& f = dg.faces;
  auto out = std::make_shared<std::vector<double>>(f.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), kFaceGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k)
      (*out)[k] = std::log(std::max(1.0, bridge_ratio3(*b.pts, spacing, f.vertex(k, 0), f.vertex(k, 1), f.vertex(k, 2))));
  });
  return out;
}

double HullConstriction3::face_term(int t, int i) const {
  if (uz(t) < b_.T0 && k_.terms) return (*k_.terms)[uz(t)][uz(i)];
  return face_term_compute(b_, k_.dg.get(), t, i);
}

double HullConstriction3::face_bridge(int t, int i) const {
  const auto& v = b_.tets[uz(t)];
  return bridge_ratio3(*b_.pts, *k_.spacing, v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][1])], v[uz(kFaceOut[i][2])]);
}

// ln(max(1, face_bridge)): precomputed for the Delaunay faces, on the fly for cavity tetrahedra.
double HullConstriction3::face_log_ratio(int t, int i) const {
  if (uz(t) < b_.T0 && k_.face_log) return (*k_.face_log)[uz(k_.dg->simplex_face[uz(t)][uz(i)])];
  return std::log(std::max(1.0, face_bridge(t, i)));
}

void HullConstriction3::start_heap() {
  s_.heap.clear();
  for (std::size_t t = 0; t < b_.T0; ++t) {
    const auto& nb = b_.nbr[t];
    if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0 || nb[3] < 0) try_push(static_cast<int>(t));
  }
}

void HullConstriction3::push_all_alive() {
  s_.heap.clear();
  for (std::size_t t = 0; t < b_.tets.size(); ++t)
    if (b_.state[t] == kAlive) try_push(static_cast<int>(t));
}

// Removability (spec gamma-graph.md §3.3): 1 / 2 boundary faces by the one-face / two-face rule,
// else 0.
int HullConstriction3::removable(int t, double* key) const {
  int bi[4], nb = 0;
  for (int i = 0; i < 4; ++i)
    if (b_.boundary_face(t, i)) bi[nb++] = i;
  if (rule_ == RemovalKey::Bridge) {
    if (nb != 2 || b_.edge_on_boundary(t, bi[0], bi[1])) return 0;
    if (key) *key = std::max(face_bridge(t, bi[0]), face_bridge(t, bi[1]));
    return 2;
  }
  int r = 0;
  if (nb == 1) r = b_.onb[uz(b_.tets[uz(t)][uz(bi[0])])] ? 0 : 1;
  else if (nb == 2) r = b_.edge_on_boundary(t, bi[0], bi[1]) ? 0 : 2;
  if (r && key) *key = criterion_key(t, bi, nb);
  return r;
}

// Key of removing tet t with boundary faces bi[0..nb) (criterion.hpp, spec gamma-graph.md §3.4).
double HullConstriction3::criterion_key(int t, const int* bi, int nb) const {
  if (opt_.criterion == Criterion::MinAreaChange) {
    // Boissonnat 84b (seed paper §2.6): smallest (Σ interior - Σ boundary) / Σ all face areas.
    const auto& v = b_.tets[uz(t)];
    double areas[4];
    bool bd[4] = {false, false, false, false};
    for (int i = 0; i < 4; ++i)
      areas[i] = triangle_area3(b_.P(v[uz(kFaceOut[i][0])]), b_.P(v[uz(kFaceOut[i][1])]), b_.P(v[uz(kFaceOut[i][2])]));
    for (int k = 0; k < nb; ++k) bd[bi[k]] = true;
    return -area_change_ratio3(areas, bd);
  }
  double key = face_term(t, bi[0]);
  if (nb == 2) {
    // Seed paper §4.2: the sum of the two terms; TwoFaceKey::Max is the measured alternative and
    // Boissonnat 84a's rule (one face decides, seed paper §6).
    const double k2 = face_term(t, bi[1]);
    const bool sum = opt_.criterion == Criterion::Gamma && opt_.two_face_key == TwoFaceKey::Sum;
    key = sum ? key + k2 : std::max(key, k2);
  }
  if (opt_.label_weight > 0 && k_.labels && uz(t) < b_.T0) key += opt_.label_weight * k_.labels->label[uz(t)];
  if (opt_.size_bias > 0) {
    // Size bias (docs/reconstruction-3d.md §4.5): large surface faces relative to the local
    // spacing first, so that bridges across gaps are carved before their far side is reached.
    double lr = face_log_ratio(t, bi[0]);
    if (nb == 2) lr = std::max(lr, face_log_ratio(t, bi[1]));
    key += opt_.size_bias * lr;
  }
  return key;
}

void HullConstriction3::try_push(int t) {
  double key = 0;
  if (removable(t, &key)) s_.heap.push({key, t, b_.ver[uz(t)]}, b_.tets);
}

void HullConstriction3::remove(int t, int kind, double key, Stage3 stage) {
  b_.state[uz(t)] = kOutside;
  ++b_.ver[uz(t)];
  ++s_.removed;
  if (kind == 1) {
    ++s_.removed1;
    b_.mark_on_surface(t);
  } else {
    ++s_.removed2;
  }
  for (int i = 0; i < 4; ++i) {
    const int m = b_.nbr[uz(t)][uz(i)];
    if (b_.alive(m)) {
      ++b_.ver[uz(m)];
      try_push(m);
    }
  }
  // Spec gamma-graph.md §3.3 (ii): after a two-face removal the common edge leaves the surface;
  // a tet around it could become removable. Around that edge the only alive tet was t itself
  // (the surface is a 2-manifold, so the edge had exactly the two faces of t): nothing to
  // re-examine.
  if (visitor_) {
    Constrict3Event e;
    e.kind = Constrict3Event::Kind::RemoveTet;
    e.tet = b_.tets[uz(t)];
    e.boundary_faces = kind;
    e.criterion = key;
    e.stage = stage;
    visitor_->on_event(e);
  }
}

bool HullConstriction3::pop_and_remove(double min_key, Stage3 stage) {
  while (!s_.heap.empty()) {
    if (s_.heap.top().key < min_key) return false;
    const HeapEntry e = s_.heap.pop(b_.tets);
    if (!b_.alive(e.tet) || e.version != b_.ver[uz(e.tet)]) continue;
    double key = 0;
    const int kind = removable(e.tet, &key);
    if (!kind) continue;
    remove(e.tet, kind, key, stage);
    return true;
  }
  return false;
}

}  // namespace constrict::detail
