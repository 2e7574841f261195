// SPDX-License-Identifier: GPL-3.0-or-later
// The decision of the handle stage (docs/topology.md §"3D"): a region labelled inside that closes
// a loop, or labelled outside that opens a tunnel, is kept only when the surface around it has
// fewer bridge faces afterwards. A true handle the genus-0 growth had to cut shows as a wall of
// long faces across the tube at the cut; closing the loop removes it. Two parts that nearly touch
// (labels leaking across a gap) would instead get new faces spanning the gap: more bridges.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <map>
#include <memory>
#include <queue>
#include <vector>

#include "constrict/detail/stages3.hpp"
#include "core/detail/union_find.hpp"

namespace constrict::detail {
namespace {

// The fewest bridge faces (Mesh3Result::kBridgeRatio) around a region, per loop it closes, for it
// to be a handle's cut.
constexpr int kMinCutBridges = 4;
// A tube only about two spacings in radius has no such wall (its cut is a few faces across a
// short diameter, often none 4 spacings long), but closing it still turns the worst spot around
// the region into an even sample: measured on clean samples of chains, linked tori and tori,
// every true cut's worst bridge ratio was 2.6-35 before and 1.48-2.56 after; the false loop
// candidates of 68 sparse random subsets of the genus-0 models, of the models themselves and of
// noisy copies of them ended at 2.32 or more, or started below 2.7.
// A one-loop region is kept when its surface goes from a ratio of kThinCutBefore or more to
// kThinCutAfter or less with no bridge face left (docs/topology.md, "Sparse samples").
constexpr double kThinCutBefore = 3.0;
constexpr double kThinCutAfter = 2.25;
// The shortest loop such a region may close, in nearest-neighbour spacings (shortest_loop).
constexpr double kThinLoopMin = 16.0;
// ... and of a noisy tube's region that passes neither ratio test (bridge_handle_decision).
constexpr double kNoisyLoopMin = 48.0;
// A region that closes several loops and leaves long faces: its loops are this long at least.
constexpr double kSeveralLoopMin = 48.0;
constexpr double kNoisyDrop = 0.85;
// The fewest tetrahedra, and points on its boundary, of a void a seal encloses for it to be an
// inner shell's cavity (bridge_handle_decision), and its widest tetrahedron's bridge ratio.
constexpr std::size_t kMinCavity = 64;
constexpr double kMinCavityWidth = 5.0;

// On an even sample a closing region must leave no long face around it. A true cut is a wall
// across a tube: closing the loop takes the wall away, and on an even sample no other face is
// long. On machined parts (flat faces, sharp edges, through holes; bench/cad_sweep3.py), rotated
// in double precision so that the points of a face are coplanar up to rounding, regions along a
// sharp edge or a crease closed false loops of 3-133 spacings and left 2-7 long faces (7.50 ->
// 7.58, 26.4 -> 24.0, 37.3 -> 27.9): a box got genus 3, a part with one hole genus 6. Every true
// closing on those parts left none (worst ratio after: 2.1-2.4).
// An even sample is told by the 90th percentile of the bridge ratios of the surface's faces (at
// the first decision that needs it): 1.76-1.96 on blue noise (the shared topology sets
// 1.91-1.96), 2.2-2.55 on noisy samples and tubes from a grid, 3.2-3.4 on tubes sampled 4-8x more
// sparsely on one side (bench/handles_sweep3.py tori3u, eightn). On uneven samples true closings
// leave sparse long faces (13 -> 2 long faces, worst ratio 13.2 -> 13.7).
constexpr double kUnevenSample = 2.25;
// ... and a closing there that leaves at most one long face in kCutLeftShare of those it found
// is a cut's when it lowers the worst ratio to kCutLeftWorst of itself (and closes a loop of
// kThinLoopMin spacings), or to kCutLeftWorstLongLoop of itself with a loop of kCutLongLoop.
constexpr int kCutLeftShare = 8;
constexpr double kCutLeftWorst = 0.5;
constexpr double kCutLeftWorstLongLoop = 0.7;
constexpr double kCutLongLoop = 100.0;

// The q-quantile of the bridge ratios of the body's surface faces.
double surface_ratio_quantile(const Body3& b, const std::vector<double>& spacing, double q) {
  std::vector<double> r;
  r.reserve(2 * b.n);
  for (std::size_t t = 0; t < b.tets.size(); ++t) {
    if (!b.alive(static_cast<int>(t))) continue;
    const auto& v = b.tets[t];
    for (int i = 0; i < 4; ++i)
      if (!b.alive(b.nbr[t][uz(i)]))
        r.push_back(bridge_ratio3(*b.pts, spacing, v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][1])], v[uz(kFaceOut[i][2])]));
  }
  if (r.empty()) return 0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(r.size() - 1));
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(k), r.end());
  return r[k];
}

struct BridgeCount {
  int faces = 0;
  double worst = 0;
};

// Surfaces of the body holding points of two parts or more.
int mixed_surfaces(const Body3& b, const std::vector<int>& part_of) {
  UnionFind uf(b.n);
  for (std::size_t t = 0; t < b.tets.size(); ++t) {
    if (b.state[t] != kAlive) continue;
    for (int i = 0; i < 4; ++i) {
      if (!b.boundary_face(static_cast<int>(t), i)) continue;
      const auto& v = b.tets[t];
      for (int k = 1; k < 3; ++k) uf.join(v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][k])]);
    }
  }
  std::vector<int> part_at(b.n, -1);
  std::vector<char> mixed(b.n, 0);
  for (std::size_t v = 0; v < b.n; ++v) {
    if (!b.onb[v]) continue;
    const int r = uf.find(static_cast<int>(v));
    if (part_at[uz(r)] < 0) part_at[uz(r)] = part_of[v];
    else if (part_at[uz(r)] != part_of[v]) mixed[uz(r)] = 1;
  }
  int k = 0;
  for (char m : mixed) k += m;
  return k;
}

// The void a seal encloses: the tetrahedra outside the body reached from the region's faces
// without meeting the convex hull; its size and the points on its boundary. A search stops as
// soon as it meets the hull, or a tetrahedron of an earlier search that did: the exterior is
// large and only a void is measured. The widest tetrahedron (bridge ratio: longest edge over the
// largest spacing of its vertices) is measured by cavity_width, only for a void that is large.
struct CavityMeasure {
  std::size_t voids = 0, tets = 0, points = 0;  // enclosed components, their tetrahedra and points
  std::vector<int> void_tets;
  double widest = 0;
};
CavityMeasure enclosed_cavity(const Body3& b, const std::vector<int>& changed) {
  CavityMeasure m;
  std::vector<int> search_of(b.tets.size(), -1);  // the search that met each tetrahedron
  std::vector<char> reached_hull;                 // per search
  std::vector<char> vert(b.n, 0);
  std::vector<int> comp, stack;
  const auto outside = [&](int t) { return t >= 0 && b.state[uz(t)] == kOutside; };
  for (int t0 : changed)
    for (int i = 0; i < 4; ++i) {
      const int s0 = b.nbr[uz(t0)][uz(i)];
      if (!outside(s0) || search_of[uz(s0)] >= 0) continue;
      const int id = static_cast<int>(reached_hull.size());
      reached_hull.push_back(0);
      comp.assign(1, s0);
      stack.assign(1, s0);
      search_of[uz(s0)] = id;
      bool hull = false;
      while (!stack.empty() && !hull) {
        const int t = stack.back();
        stack.pop_back();
        for (int k = 0; k < 4 && !hull; ++k) {
          const int u = b.nbr[uz(t)][uz(k)];
          if (u < 0)
            hull = true;
          else if (!outside(u))
            continue;
          else if (search_of[uz(u)] >= 0)
            hull = search_of[uz(u)] != id && reached_hull[uz(search_of[uz(u)])];
          else {
            search_of[uz(u)] = id;
            comp.push_back(u);
            stack.push_back(u);
          }
        }
      }
      reached_hull[uz(id)] = hull ? 1 : 0;
      if (hull) continue;
      ++m.voids;
      m.tets += comp.size();
      for (int t : comp)
        for (int v : b.tets[uz(t)]) vert[uz(v)] = 1;
      m.void_tets.insert(m.void_tets.end(), comp.begin(), comp.end());
    }
  for (char c : vert) m.points += static_cast<std::size_t>(c);
  return m;
}

double cavity_width(const Body3& b, const std::vector<int>& void_tets, const std::vector<double>& spacing) {
  double w = 0;
  for (int t : void_tets) w = std::max(w, bridge_ratio3(*b.pts, spacing, b.tets[uz(t)]));
  return w;
}

// The shortest loop a closing region makes, in nearest-neighbour spacings (nearest_spacing3, the
// median over the region's points). The region R touches the body on faces that form one patch
// per end of the cut (patches: contact faces joined across shared edges); the loop goes through R
// and through the body from one patch to another. A Dijkstra over the body's tetrahedra (centroid
// to centroid) from every patch at once finds the first meeting of two patches' fronts. Searches
// stop beyond max_len spacings (then returns max_len).
// The faces where a region (its tetrahedra, sorted) touches the rest of the body — contact faces
// (region tetrahedron, face index) — and their patches: contact faces sharing an edge are one patch
// (uf over the contacts).
struct Contact {
  int t, i;
};
std::vector<Contact> contact_faces(const Body3& b, const std::vector<int>& changed, const std::vector<int>& sorted,
                                   UnionFind& uf) {
  const auto in_r = [&](int t) { return std::binary_search(sorted.begin(), sorted.end(), t); };
  std::vector<Contact> cf;
  for (int t : changed)
    for (int i = 0; i < 4; ++i) {
      const int m = b.nbr[uz(t)][uz(i)];
      if (m >= 0 && b.alive(m) && !in_r(m)) cf.push_back({t, i});
    }
  uf = UnionFind(cf.size());
  std::map<std::pair<int, int>, int> edge_face;
  for (std::size_t k = 0; k < cf.size(); ++k) {
    const auto& v = b.tets[uz(cf[k].t)];
    int f[3], c = 0;
    for (int l = 0; l < 4; ++l)
      if (l != cf[k].i) f[c++] = v[uz(l)];
    for (int e = 0; e < 3; ++e) {
      const int a = std::min(f[e], f[(e + 1) % 3]), z = std::max(f[e], f[(e + 1) % 3]);
      const auto [it, fresh] = edge_face.emplace(std::make_pair(a, z), static_cast<int>(k));
      if (!fresh) uf.join(it->second, static_cast<int>(k));
    }
  }
  return cf;
}

double shortest_loop(const Body3& b, const std::vector<int>& changed, const std::vector<double>& spacing,
                     double max_len, std::vector<int>* near_patch = nullptr) {
  std::vector<int> sorted = changed;
  std::sort(sorted.begin(), sorted.end());
  const auto in_r = [&](int t) { return std::binary_search(sorted.begin(), sorted.end(), t); };
  UnionFind uf(0);
  const std::vector<Contact> cf = contact_faces(b, changed, sorted, uf);
  if (cf.size() < 2) return 0;
  double h = 0;
  {
    std::vector<double> s;
    for (int t : changed)
      for (int v : b.tets[uz(t)]) s.push_back(spacing[uz(v)]);
    std::nth_element(s.begin(), s.begin() + static_cast<long>(s.size() / 2), s.end());
    h = s[s.size() / 2];
  }
  if (!(h > 0)) return max_len;
  const auto centroid = [&](int t, double* c) {
    c[0] = c[1] = c[2] = 0;
    for (int v : b.tets[uz(t)])
      for (int k = 0; k < 3; ++k) c[k] += 0.25 * b.P(v)[k];
  };
  const auto dist = [&](int s, int t) {
    double a[3], c[3];
    centroid(s, a);
    centroid(t, c);
    return std::sqrt((a[0] - c[0]) * (a[0] - c[0]) + (a[1] - c[1]) * (a[1] - c[1]) + (a[2] - c[2]) * (a[2] - c[2]));
  };
  std::map<int, std::pair<double, int>> label;  // body tetrahedron -> (distance, patch)
  using Item = std::pair<double, std::pair<int, int>>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
  for (std::size_t k = 0; k < cf.size(); ++k) {
    const int m = b.nbr[uz(cf[k].t)][uz(cf[k].i)];
    const int patch = uf.find(static_cast<int>(k));
    const double d0 = dist(cf[k].t, m);
    pq.push({d0, {m, patch}});
  }
  double best = max_len * h;
  int pa = -1, pb = -1;  // the two patches of the best loop
  const auto meet = [&](double len, int p, int q) {
    if (len < best) {
      best = len;
      pa = p;
      pb = q;
    }
  };
  while (!pq.empty()) {
    const auto [d, tp] = pq.top();
    pq.pop();
    if (2 * d >= best) break;
    const auto [t, patch] = tp;
    auto it = label.find(t);
    if (it != label.end()) {
      if (it->second.second != patch) meet(d + it->second.first, patch, it->second.second);
      continue;
    }
    label[t] = {d, patch};
    for (int m : b.nbr[uz(t)]) {
      if (m < 0 || !b.alive(m) || in_r(m)) continue;
      const auto jt = label.find(m);
      const double dm = d + dist(t, m);
      if (jt != label.end()) {
        if (jt->second.second != patch) meet(dm + jt->second.first, patch, jt->second.second);
        continue;
      }
      pq.push({dm, {m, patch}});
    }
  }
  if (near_patch && pa >= 0) {
    // The region's tetrahedra on the patch of the two with fewer contact faces (ties: the one
    // whose root, a contact index in the order of `changed`, is smaller).
    std::size_t na = 0, nb = 0;
    for (std::size_t k = 0; k < cf.size(); ++k) {
      const int r = uf.find(static_cast<int>(k));
      na += r == pa;
      nb += r == pb;
    }
    const int small = nb < na || (nb == na && pb < pa) ? pb : pa;
    near_patch->clear();
    for (std::size_t k = 0; k < cf.size(); ++k)
      if (uf.find(static_cast<int>(k)) == small) near_patch->push_back(cf[k].t);
    std::sort(near_patch->begin(), near_patch->end());
    near_patch->erase(std::unique(near_patch->begin(), near_patch->end()), near_patch->end());
  }
  // No meeting below the bound: the bound itself, exactly ((max_len * h) / h need not round back to
  // max_len unless it is a power of two: a bound of 48 came back as 47.99..., under the rule's 48).
  return pa < 0 ? max_len : best / h;
}

// Do two of the region's contact patches (as in shortest_loop) meet through body tetrahedra
// labelled inside, outside the region? That is: does one component of those tetrahedra (joined
// across shared faces) hold the neighbours of contacts of two patches? On a true handle the two
// patches meet only round the object, through nearly the whole body, so the components are found
// by Body3::face_components, one pass in tetrahedron order, rather than by a search from the
// contacts (a torus of 10^5 random points: 0.53 s with the search's marks in a hash map,
// 0.19 s in a flat array, 0.05 s so). in_region: all 0, kept between calls, given back so.
bool loop_through_inside(const Body3& b, const std::vector<int>& changed, const Labels3& lab,
                         std::vector<char>& in_region) {
  std::vector<int> sorted = changed;
  std::sort(sorted.begin(), sorted.end());
  UnionFind patches(0);
  const std::vector<Contact> cf = contact_faces(b, changed, sorted, patches);
  if (cf.size() < 2) return false;
  const std::size_t nt = b.tets.size();
  if (in_region.size() < nt) in_region.resize(nt, 0);
  for (int t : changed) in_region[uz(t)] = 1;
  const auto passable = [&](int t) {
    return t >= 0 && b.state[uz(t)] == kAlive && !in_region[uz(t)] && (uz(t) >= lab.label.size() || lab.label[uz(t)] < 0);
  };
  // The contacts' neighbours that can be passed, with their patches.
  std::vector<std::array<int, 2>> seeds;  // (tetrahedron, patch)
  for (std::size_t k = 0; k < cf.size(); ++k) {
    const int m = b.nbr[uz(cf[k].t)][uz(cf[k].i)];
    if (passable(m)) seeds.push_back({m, patches.find(static_cast<int>(k))});
  }
  bool met = false;
  if (seeds.size() >= 2) {
    UnionFind comp = b.face_components(passable);
    // (component root, patch), sorted: two patches in one component are neighbours.
    for (auto& s : seeds) s[0] = comp.find(s[0]);
    std::sort(seeds.begin(), seeds.end());
    for (std::size_t i = 1; i < seeds.size() && !met; ++i) met = seeds[i][0] == seeds[i - 1][0] && seeds[i][1] != seeds[i - 1][1];
  }
  for (int t : changed) in_region[uz(t)] = 0;
  return met;
}

// The outward normal (not normalised) of the triangle abc of a body tetrahedron whose fourth
// vertex is `inner`.
std::array<double, 3> outward_normal(const Body3& b, int a, int c, int d, int inner) {
  const double* p = b.P(a);
  const double* q = b.P(c);
  const double* r = b.P(d);
  const double* s = b.P(inner);
  const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
  std::array<double, 3> n{{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]}};
  if (n[0] * (s[0] - p[0]) + n[1] * (s[1] - p[1]) + n[2] * (s[2] - p[2]) > 0)
    for (double& x : n) x = -x;
  return n;
}

// Does a closing fold where its new surface meets the old one? Its new surface faces (the region's
// faces toward tetrahedra outside the body, the region now in it) against the surface faces of
// the body outside the region across their edges (the seam): a bend of 90 degrees or more there
// (outward normals at a dot product of 0 or less, a degenerate face counting as such). A cut
// across a tube continues the tube's surface over the seam; a bridge across the slot between two
// walls meets them at about right angles. Measured (docs/topology.md, "Limbs that nearly touch"):
// the true thin-tube and noisy-tube closings on even samples bend at most 79 degrees at their seam
// (sparse chains, linked tori, mugs, a thin-walled box), the false ones across a comb's slots
// 92-180. sorted_changed: the region, ascending.
bool folds_at_seam(const Body3& b, const std::vector<int>& sorted_changed) {
  const auto in_region = [&](int t) { return std::binary_search(sorted_changed.begin(), sorted_changed.end(), t); };
  for (int t : sorted_changed) {
    if (!b.alive(t)) continue;
    const auto& tv = b.tets[uz(t)];
    for (int i = 0; i < 4; ++i) {
      if (b.alive(b.nbr[uz(t)][uz(i)])) continue;
      int f[3], c = 0;
      for (int l = 0; l < 4; ++l)
        if (l != i) f[c++] = tv[uz(l)];
      const std::array<double, 3> n0 = outward_normal(b, f[0], f[1], f[2], tv[uz(i)]);
      for (int e = 0; e < 3; ++e) {
        // The other surface face at the edge (u, w): round the edge from t through the body,
        // first across t's face (u, w, tv[i]), to the first tetrahedron outside the body.
        const int u = f[e], w = f[(e + 1) % 3];
        int cur = t, exit_v = f[(e + 2) % 3], kept = tv[uz(i)];
        for (std::size_t guard = 0; guard <= b.tets.size(); ++guard) {
          const int nx = b.nbr[uz(cur)][uz(b.local_index(cur, exit_v))];
          if (!b.alive(nx)) break;
          int next_kept = -1;
          for (int x : b.tets[uz(nx)])
            if (x != u && x != w && x != kept) next_kept = x;
          exit_v = kept;
          kept = next_kept;
          cur = nx;
        }
        if (in_region(cur)) continue;  // (a face of the region's own new surface)
        const std::array<double, 3> n1 = outward_normal(b, u, w, kept, exit_v);
        if (!(n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] > 0)) return true;
      }
    }
  }
  return false;
}

}  // namespace

HandleDecision bridge_handle_decision(const Body3& body, const std::vector<int>* part_of,
                                      std::shared_ptr<std::vector<Handle3Change>> log, const Labels3* labels,
                                      std::shared_ptr<const std::vector<double>> given_spacing) {
  // The spacing: the engine's, or made on first use (most bodies have no candidate region).
  auto own_spacing = std::make_shared<std::vector<double>>();
  const auto spacing_of = [given_spacing, own_spacing](const Body3& b) -> const std::vector<double>& {
    if (given_spacing) return *given_spacing;
    if (own_spacing->empty()) *own_spacing = nearest_spacing3(b);
    return *own_spacing;
  };
  auto uneven = std::make_shared<double>(-1);  // the surface's 90th-percentile ratio, on first use
  const bool debug = std::getenv("CONSTRICT_DEBUG_HANDLES") != nullptr;
  // Before any change: the surfaces holding two parts (one, or none).
  const int mixed0 = part_of ? mixed_surfaces(body, *part_of) : 0;  // (only with parts: the fallback run)
  auto in_region = std::make_shared<std::vector<char>>();  // loop_through_inside's marks
  return [spacing_of, uneven, debug, part_of, mixed0, log, labels, in_region](const Body3& b, const std::vector<int>& changed, bool added,
                                                long long dF, bool pinched, std::vector<int>* trim) {
    Handle3Change h;
    h.kind = !added ? Handle3Change::Kind::OpenTunnel : dF > 0 ? Handle3Change::Kind::CloseLoop : Handle3Change::Kind::SealCavity;
    h.tetrahedra = changed.size();
    h.delta_faces = dF;
    if (part_of && mixed0 > 0 && dF < 0 && mixed_surfaces(b, *part_of) < mixed0) {
      if (debug) std::fprintf(stderr, "handle seal: %zu tets separate two parts: kept\n", changed.size());
      h.separates_parts = true;
      if (log) log->push_back(h);
      return true;
    }
    // A cavity sealed inside one part: an inner shell whose gap to the outer one is under the gap
    // rule's threshold (a sparse hollow ball: a shell 2-3 sampling radii thick), or voids left
    // between the two sheets of a closed cut or among noisy points. Measured (sparse hollow balls;
    // sparse, noisy and random genus-0 and handle controls): the inner shells' cavities have 263
    // tetrahedra or more, 99 points or more, and a tetrahedron 5.66 spacings wide or wider; the
    // voids at most 32 tetrahedra and 48 points, and those with more than 8 points no tetrahedron
    // wider than 4.55. Kept: one new surface (dF = -4) around one void that is large and wide.
    if (dF < 0) {
      CavityMeasure m = enclosed_cavity(b, changed);
      const bool large = dF == -4 && m.voids == 1 && m.tets >= kMinCavity && m.points >= kMinCavity;
      if (large || debug) {
        m.widest = cavity_width(b, m.void_tets, spacing_of(b));
      }
      const bool shell = large && m.widest >= kMinCavityWidth;
      if (debug)
        std::fprintf(stderr, "handle seal: %zu tets, dF %lld, %zu void(s), %zu tets, %zu points, widest %.2f: %s\n",
                     changed.size(), dF, m.voids, m.tets, m.points, m.widest, shell ? "kept" : "undone");
      if (shell && log) {
        h.cavity_tetrahedra = m.tets;
        h.cavity_points = m.points;
        h.cavity_width = m.widest;
        log->push_back(h);
      }
      return shell;
    }
    // A handle belongs to one part: a loop closed (or a tunnel opened) through tetrahedra that
    // join two parts of the gap rule spans the gap between them (a hollow ball sampled at random:
    // loops across its cavity gave genus 10).
    if (part_of)
      for (int t : changed) {
        const auto& v = b.tets[uz(t)];
        const int p0 = (*part_of)[uz(v[0])];
        if ((*part_of)[uz(v[1])] != p0 || (*part_of)[uz(v[2])] != p0 || (*part_of)[uz(v[3])] != p0) {
          if (debug)
            std::fprintf(stderr, "handle %s: %zu tets join two parts: undone\n", added ? "close" : "open",
                         changed.size());
          return false;
        }
      }
    const std::vector<double>& spacing = spacing_of(b);
    std::vector<int> sorted = changed;
    std::sort(sorted.begin(), sorted.end());
    const auto was_changed = [&](int t) { return std::binary_search(sorted.begin(), sorted.end(), t); };
    const auto alive_before = [&](int t) { return t >= 0 && (was_changed(t) ? !b.alive(t) : b.alive(t)); };
    BridgeCount before, after;
    const auto count = [&](BridgeCount& c, int t, int i) {
      const auto& v = b.tets[uz(t)];
      const double r = bridge_ratio3(*b.pts, spacing, v[uz(kFaceOut[i][0])], v[uz(kFaceOut[i][1])], v[uz(kFaceOut[i][2])]);
      c.worst = std::max(c.worst, r);
      if (r >= Mesh3Result::kBridgeRatio) ++c.faces;
    };
    for (int t : changed)
      for (int i = 0; i < 4; ++i) {
        const int m = b.nbr[uz(t)][uz(i)];
        // Each face once: from the changed tetrahedron with the smaller index, or a neighbour
        // not changed.
        if (m >= 0 && was_changed(m) && m < t) continue;
        if (alive_before(t) != alive_before(m)) count(before, t, i);
        if (b.alive(t) != b.alive(m)) count(after, t, i);
      }
    // A cut shows as a few long faces at least (a tube two spacings wide: several), for each loop
    // the region closes (dF = 4 per loop); one long face less is a sparse spot, not a handle (a
    // random quarter of a genus-0 model), and a region closing two loops across 7 long faces held
    // a false one (a noisy chain).
    const long long loops = std::max(1LL, dF / 4);
    // A region that needed a move at a pinch to become valid is forced through its end state: it
    // must close one loop and at least halve the long faces (a true cut: 67 -> 5; false loops on
    // very unevenly sampled tubes: 9 -> 8, and two loops at once, 67 -> 6).
    const bool drop = pinched ? dF == 4 && 2 * after.faces <= before.faces : after.faces < before.faces;
    const bool by_bridges = drop && before.faces >= kMinCutBridges * loops;
    const bool thin_shape = !by_bridges && !pinched && added && dF == 4 && after.faces == 0 &&
                            before.worst >= kThinCutBefore && after.worst <= kThinCutAfter;
    // ... and the loop a thin tube's region closes must be long: noise under a surface makes small
    // tunnels that pass the ratio test, with loops of 3.9-11.3 spacings (noisy armadillo, igea,
    // spot; 21.7 at a noise of 1.4 spacings), while every true thin tube measured (tori, chains and
    // links of 385-1 500 points) closed one of 83 spacings or more. A torus whose hole is as wide as
    // its tube, two spacings thick, has a loop of about 25. (Measured only here: it is a search.)
    // A pinched region's loop likewise: with the local search kept from opening the loop again,
    // a pocket of a noisy genus-0 scan closed one of 2.5 spacings through a pinch (9 -> 0 long
    // faces), while the true pinched closings measured 107-381 (a noisy torus and chain, an
    // uneven eight). (The search stops at 16; under CONSTRICT_DEBUG_HANDLES it measures in full.)
    // So must a region that closes several loops at once (dF >= 8): on very unevenly sampled tubes
    // (bench/handles_sweep3.py, eightn) such regions held a false loop of 2.8-2.9 spacings (genus 3
    // for a figure eight); the rule changes no result of bench/topology_sweep3.py (90 sets), the
    // shared topology sets or 28 noisy copies of the handle sets.
    // A noisy tube (noise of 0.3 spacings on a tube 2-3 spacings in radius) has neither a wall of
    // long faces at its cut nor an even sample after closing it (after.worst stays above 2.25):
    // a region that closes one loop, leaves no long face and lowers the worst ratio by 15 % or
    // more (kNoisyDrop) is kept when its loop is long, kNoisyLoopMin spacings. Measured on noisy
    // chains of rings and figure-eight tubes: true closings lower the worst ratio by 18-55 % (one
    // by 3 %) with loops of 113-150 spacings; regions closing false tunnels under noisy genus-0
    // scans (elephant, igea, bunny, noise 0.3-0.8) have loops of 54-113 too, but lower it by 2-9 %.
    // A few long faces may stay where the sample is sparse (a figure-eight tube up to 8x sparser
    // on its sides, bench/handles_sweep3.py eightn: 3 -> 2 long faces, the worst ratio 10.5 ->
    // 4.2): the region is then measured the same way if it leaves fewer long faces than it found
    // (no control changed:
    // 81 noisy genus-0 copies, the 28 noisy handle sets, 54 implicit chains and eights, the
    // shared 3D and topology sets).
    // On an even sample (kUnevenSample: blue noise, as mesh vertices are) such a closing
    // must leave an even surface, as the thin tube's must: the true ones measured there (sparse
    // chains and linked tori of 600 points, bench/topology_sweep3.py) end at 1.75-2.05, while one
    // closing a slot two spacings wide between a comb's fingers (bench/limbs3.py) ended at 3.41.
    // And on an even sample neither rule keeps a closing that folds where it meets the surface
    // around it (folds_at_seam): a bridge across a slot that ends even looks like a sparse tube's
    // closing by every other measure here. Nor does the thin-tube rule on any sample (its
    // closings end even; no true one measured on an uneven sample folds, while three bridges
    // between limbs of uniformly random points did). The noisy-tube rule on an uneven sample
    // does not ask: a true closing on a noisy chain bent 140 degrees at its seam.
    const auto even_sample = [&] {
      if (*uneven < 0) *uneven = surface_ratio_quantile(b, spacing, 0.9);
      return *uneven < kUnevenSample;
    };
    const bool noisy_shape = !by_bridges && !thin_shape && !pinched && added && dF == 4 &&
                             (after.faces == 0 || after.faces < before.faces) && after.worst <= kNoisyDrop * before.worst;
    const bool weak_even = (thin_shape || noisy_shape) && even_sample();
    const bool ask_fold = thin_shape || (noisy_shape && weak_even && after.worst <= kThinCutAfter);
    const bool folds = ask_fold && folds_at_seam(b, sorted);
    const bool thin_tube = thin_shape && !folds;  // (it ends even: after.worst <= kThinCutAfter)
    const bool noisy_tube = noisy_shape && (!weak_even || (after.worst <= kThinCutAfter && !folds));
    const bool need_loop = thin_tube || noisy_tube || (by_bridges && pinched) || (by_bridges && dF >= 8);
    const double min_loop = noisy_tube ? kNoisyLoopMin : kThinLoopMin;
    // A closing region that closes several loops across a wall of long faces, one of them short,
    // is asked for again without its tetrahedra on one end of that loop: the patch with fewer
    // contact faces (trim).
    const bool several = added && by_bridges && dF >= 8 && !pinched;
    std::vector<int> near_patch;
    double loop = need_loop ? shortest_loop(b, changed, spacing, debug ? HUGE_VAL : several ? std::max(min_loop, kSeveralLoopMin) : min_loop,
                                            several && trim ? &near_patch : nullptr)
                            : -1;
    bool keep = need_loop ? loop >= min_loop : by_bridges;
    // ... and a region that closes several loops and leaves more than one long face per loop must
    // close long ones: on a thin wall sampled at random (a mug: density changing 4x, noise of 0.25
    // spacings) one region a few spacings wide closed 8 loops of 18 spacings and left 71 of its 629
    // long faces (genus 8 for a mug), while true closings of several loops leave none (a plate's
    // and a pot's neighbouring holes, loops of 17-32 spacings) or close long loops (two tori side
    // by side sampled unevenly: 221 -> 15 long faces, a loop of 1 344 spacings).
    if (keep && several && after.faces > loops && loop < kSeveralLoopMin) {
      if (debug)
        std::fprintf(stderr, "handle close: %lld loops leave %d long faces and one is %.1f spacings: undone\n", loops,
                     after.faces, loop);
      keep = false;
    }
    // On an even sample a closing leaves no long face (kUnevenSample above).
    if (keep && added && after.faces > 0) {
      if (*uneven < 0) *uneven = surface_ratio_quantile(b, spacing, 0.9);
      // ... unless it takes nearly all of them away, as from a wide cut, and closes a long loop:
      // where the sample itself has long faces (the vertices of a decimated mesh: long triangles
      // on flat and gently curved parts) a true cut's closing leaves a few of them beside it.
      // Measured (docs/topology.md, "Decimated meshes"), true closings: 116 -> 4, 52 -> 1,
      // 67 -> 2, 70 -> 1, 66 -> 3, 391 -> 3, 74 -> 1, 94 -> 1, 193 -> 6 long faces with the worst
      // ratio down to 0.08-0.44 of itself (loops of 22-600 spacings), and 91 -> 10, 318 -> 2,
      // 9 -> 1, 14 -> 1 with it down to 0.58-0.69 and loops of 170-809 (76 -> 2, 0.70, a loop of
      // 17: not told from the false ones). False ones: 14 -> 5, 7.24 -> 6.04 (a noisy open bunny
      // scan); boxes stacked 1.5 spacings apart 41 -> 3, 0.61, a loop of 40 (the labels leak
      // across the gap there); boxes 2 apart through a pinch 72 -> 1, 0.45, a loop of 17 (no true
      // one needed a pinch).
      const bool wide_cut = dF == 4 && !pinched && kCutLeftShare * after.faces <= before.faces &&
                            after.worst <= kCutLeftWorstLongLoop * before.worst;
      const bool even = *uneven < kUnevenSample;
      bool cut = false;
      if (even && wide_cut) {
        const double need = after.worst <= kCutLeftWorst * before.worst ? kThinLoopMin : kCutLongLoop;
        if (loop < need) loop = shortest_loop(b, changed, spacing, debug ? HUGE_VAL : need);
        cut = loop >= need;
      }
      if (even && !cut) {
        if (debug)
          std::fprintf(stderr, "handle close: %d long faces left (worst %.2f -> %.2f) on an even sample (%.2f): undone\n",
                       after.faces, before.worst, after.worst, *uneven);
        keep = false;
      }
    }
    // Parts that nearly touch (closer than the gap rule's threshold: one part) are joined where the
    // growth took outside steps to reach the second one; its genus-0 growth left cuts between
    // those steps, and closing them makes loops that all run through the steps, whatever the
    // bridge measure says. A closing is a handle of the object only when it closes a loop through
    // tetrahedra labelled inside. Measured (docs/topology.md, "Parts that nearly touch"): two
    // boxes 2 spacings apart, 6 of 8 false handles of bench/near_parts3.py at gaps of 1-2 spacings
    // gone, and a grid-sampled box's false handle; of 627 control sets 3 changed, two noisy
    // implicit chains of rings that already missed handles lost one more.
    if (keep && added && dF > 0 && labels && !loop_through_inside(b, changed, *labels, *in_region)) {
      if (debug) std::fprintf(stderr, "handle close: %zu tets close no loop through inside-labelled tetrahedra: undone\n", changed.size());
      keep = false;
    }
    if (!keep && several && trim) *trim = near_patch;
    // A closing region must not enclose a void: dF counts a new cavity surface as -4, so a region
    // that closed two loops and sealed a void (dF = 8 - 4) passed as one loop, and a noisy chain
    // of four rings got genus 5 and an inner surface of 4 points. Seals are decided above.
    if (keep && added) {
      const CavityMeasure cav = enclosed_cavity(b, changed);
      if (cav.voids > 0) {
        if (debug) std::fprintf(stderr, "handle close: %zu tets enclose a void: undone\n", changed.size());
        keep = false;
        // Asked for again without the region's tetrahedra next to the void (trim).
        if (trim) {
          std::vector<int> sorted_void = cav.void_tets;
          std::sort(sorted_void.begin(), sorted_void.end());
          for (int t : changed)
            for (int m : b.nbr[uz(t)])
              if (m >= 0 && std::binary_search(sorted_void.begin(), sorted_void.end(), m)) {
                trim->push_back(t);
                break;
              }
        }
      }
    }
    if (keep && log) {
      h.pinched = pinched;
      if (loop >= 0) h.loop_spacings = loop;
      h.bridges_before = before.faces;
      h.bridges_after = after.faces;
      h.worst_ratio_before = before.worst;
      h.worst_ratio_after = after.worst;
      log->push_back(h);
    }
    if (debug) {
      double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
      for (int t : changed)
        for (int v : b.tets[uz(t)])
          for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b.P(v)[k]);
            hi[k] = std::max(hi[k], b.P(v)[k]);
          }
      std::fprintf(stderr,
                   "handle %s: %zu tets, dF %lld%s, bridges %d -> %d, worst %.2f -> %.2f, loop %.1f: %s (box %.3g %.3g "
                   "%.3g - %.3g %.3g %.3g)\n",
                   added ? "close" : "open", changed.size(), dF, pinched ? " (pinch)" : "", before.faces, after.faces,
                   before.worst, after.worst, loop, keep ? "kept" : "undone", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    }
    return keep;
  };
}

}  // namespace constrict::detail

namespace constrict {
const char* to_string(Handle3Change::Kind k) noexcept {
  switch (k) {
    case Handle3Change::Kind::CloseLoop: return "close-loop";
    case Handle3Change::Kind::OpenTunnel: return "open-tunnel";
    case Handle3Change::Kind::SealCavity: return "seal-cavity";
  }
  return "?";
}
}  // namespace constrict
