// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "repair" of reconstruct_surfaces3() (detail/surfaces3.hpp; docs/topology.md §"3D"): when
// the parts' surfaces are not made of Delaunay faces of all points (noisy or random samples of
// nested parts), the body that the parts' own bodies put in the tetrahedralization of all points,
// with the points that it buries or pinches repaired one at a time. Every decision is
// combinatorial (links, Euler characteristic) or an exact predicate; double areas only rank the
// valid choices, ties by sorted vertex ids.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include "constrict/predicates.hpp"
#include "core/detail/link_cycle.hpp"
#include "core/detail/tet_faces.hpp"
#include "core/detail/union_find.hpp"
#include "topology/detail/surfaces3.hpp"
#include "topology/detail/vertex_tets3.hpp"

namespace constrict::detail::surfaces3 {
namespace {

// The body of the parts' own surfaces in the tetrahedralization of all points, when those
// surfaces cannot be assembled as they are (noisy nested parts: a point that noise moved off its
// shell leaves a "tent" of faces that are not Delaunay faces of all points). A tetrahedron of dt
// lies inside c of the parts' closed surfaces and is in the body when c is odd: a part's depth is
// the number of other parts whose own body holds its first point (exact orient3); a tetrahedron
// of one part's points lies inside the parts around that part, and inside that part too when it
// is one of the part's own body tetrahedra (a Delaunay tetrahedron of all points is one of the
// part's points alone); a tetrahedron joining parts lies in the gap between them, inside the
// parts around the deepest of them. The tetrahedra keep dt's orientation.
std::vector<char> parts_body(const PointSet& pts, const Delaunay3& dt, const Parts& parts,
                             const std::vector<Mesh3Result>& res) {
  const std::size_t P = parts.points.size();
  std::vector<std::vector<std::array<int, 4>>> own(P);
  for (std::size_t k = 0; k < P; ++k)
    for (const auto& t : res[k].tets) {
      const auto& ids = parts.points[k];
      own[k].push_back({ids[uz(t[0])], ids[uz(t[1])], ids[uz(t[2])], ids[uz(t[3])]});
    }
  std::vector<int> depth(P, 0);
  for (std::size_t q = 0; q < P; ++q) {
    const double* x = pts[uz(parts.points[q].front())];
    for (std::size_t p = 0; p < P; ++p) {
      if (p == q) continue;
      for (const auto& t : own[p]) {
        const double* v[4] = {pts[uz(t[0])], pts[uz(t[1])], pts[uz(t[2])], pts[uz(t[3])]};
        if (orient3(x, v[1], v[2], v[3]) >= 0 && orient3(v[0], x, v[2], v[3]) >= 0 &&
            orient3(v[0], v[1], x, v[3]) >= 0 && orient3(v[0], v[1], v[2], x) >= 0) {
          ++depth[q];
          break;
        }
      }
    }
  }
  std::vector<std::array<int, 4>> inside;
  for (auto& o : own)
    for (auto t : o) {
      std::sort(t.begin(), t.end());
      inside.push_back(t);
    }
  std::sort(inside.begin(), inside.end());
  std::vector<char> body(dt.tets.size(), 0);
  for (std::size_t i = 0; i < dt.tets.size(); ++i) {
    const auto& t = dt.tets[i];
    const int k0 = parts.part_of[uz(t[0])];
    bool one = true;
    int c = 0;
    for (int v : t) {
      const int k = parts.part_of[uz(v)];
      one = one && k == k0;
      c = std::max(c, depth[uz(k)]);
    }
    if (one) {
      std::array<int, 4> key = t;
      std::sort(key.begin(), key.end());
      c = depth[uz(k0)] + (std::binary_search(inside.begin(), inside.end(), key) ? 1 : 0);
    }
    body[i] = static_cast<char>(c % 2 == 1);
  }
  return body;
}

// Repairs the points where the body of parts_body() is not a surface: a point not on it (buried
// in the body, or in a region outside it) or whose free faces do not form one disk. Toggles one
// tetrahedron of dt at the point, else two that share a face, else (a point off the surface) a
// channel of up to kChannel tetrahedra in the point's state from one at the point to one with a
// free face. A choice is valid when every vertex of its tetrahedra (the only links that change)
// ends on the surface with a link that is one cycle and the surface keeps its Euler
// characteristic (two faces more for each point brought to it: no handle, no extra surface);
// among the valid ones the one that adds the least area (double arithmetic, a choice only),
// ties by the smaller sorted vertex ids. Points in ascending order (canonical ids: the same for
// any file order). The points left then go to a local search (local_search). in_body: per
// tetrahedron of dt, updated; run() adds the toggles to changed and is false when a defect is
// left (in_body is then not a body to use) or the work bound was reached.
// Work bound: the tetrahedra read by the link and surface tests, at most kWorkPerIncidence per
// tetrahedron-vertex incidence plus kWorkFloor (as the carve's, carve3.cpp). Points along curves
// in space have thousands of tetrahedra at every point: 1 500 points on a circle and 1 500 on its
// axis (two parts) ran here for more than 10 minutes without it.
class SurfaceRepair {
  static constexpr int kChannel = 4;
  static constexpr std::size_t kSearchSteps = 16;
  static constexpr std::size_t kWorkPerIncidence = 64, kWorkFloor = std::size_t(1) << 20;

 public:
  SurfaceRepair(const PointSet& pts, const Delaunay3& dt, std::vector<char>& in_body, const std::vector<int>* part_of)
      : pts_(pts), dt_(dt), in_(in_body), part_of_(part_of), at_(dt) {
    // Face ids through the neighbour relation (a face and its mirror in the neighbour share one).
    const std::size_t T = dt.tets.size();
    face_id_.assign(T, {{-1, -1, -1, -1}});
    int faces = 0;
    for (std::size_t t = 0; t < T; ++t)
      for (int i = 0; i < 4; ++i) {
        if (face_id_[t][uz(i)] >= 0) continue;
        face_id_[t][uz(i)] = faces;
        const int m = dt.neighbors[t][uz(i)];
        if (m >= 0)
          for (int j = 0; j < 4; ++j)
            if (dt.neighbors[uz(m)][uz(j)] == static_cast<int>(t)) face_id_[uz(m)][uz(j)] = faces;
        ++faces;
      }
    work_limit_ = kWorkPerIncidence * 4 * T + kWorkFloor;
    count_.assign(uz(faces), 0);
    for (std::size_t t = 0; t < T; ++t)
      if (in_[t])
        for (int i = 0; i < 4; ++i) ++count_[uz(face_id_[t][uz(i)])];
    for (const int c : count_) nfree_ += c == 1 ? 1 : 0;
  }

  bool capped() const { return capped_; }
  // The work done (on_surface, vertex_ok and the local search's tries), and work done before by
  // another repair of the same body, which counts against this one's bound.
  std::size_t work() const { return work_; }
  void start_after(std::size_t work) { work_ = work; }
  // Past the work bound (class comment): run() gives up, and says so.
  bool over_budget() {
    capped_ = capped_ || work_ > work_limit_;
    return capped_;
  }
  // target_faces: the face count of the parts' own surfaces (the same Euler characteristic).
  bool run(std::size_t target_faces, std::size_t& changed) {
    std::vector<int> left;  // points the first pass could not repair
    for (std::size_t v = 0; v < pts_.size(); ++v) {
      if (over_budget()) return false;
      const int vi = static_cast<int>(v);
      if (vertex_ok(vi)) continue;
      std::vector<int> best;
      double best_gain = HUGE_VAL;
      std::vector<std::array<int, 4>> best_key;
      const auto consider = [&](const std::vector<int>& set) {
        // The surface's Euler characteristic V - F/2 (closed, edge-manifold) must not change: the
        // points brought to the surface, two faces each.
        std::vector<int> verts;
        for (int t : set)
          for (int x : dt_.tets[uz(t)]) verts.push_back(x);
        std::sort(verts.begin(), verts.end());
        verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
        long long off = 0;
        for (int x : verts) off += on_surface(x) ? 0 : 1;
        const double before = area_of(set);
        const long long f0 = free_faces_of(set);
        for (int t : set) toggle(t);
        bool ok = free_faces_of(set) - f0 == 2 * off;
        for (int x : verts) ok = ok && vertex_ok(x);
        const double gain = area_of(set) - before;
        for (int t : set) toggle(t);
        if (!ok) return;
        std::vector<std::array<int, 4>> key;
        for (int t : set) {
          std::array<int, 4> k = dt_.tets[uz(t)];
          std::sort(k.begin(), k.end());
          key.push_back(k);
        }
        std::sort(key.begin(), key.end());
        if (best.empty() || gain < best_gain || (gain == best_gain && key < best_key)) {
          best = set;
          best_gain = gain;
          best_key = key;
        }
      };
      for (int t : at_.of(vi)) consider({t});
      // Two that share a face (a pair of the point's own tetrahedra once).
      if (best.empty())
        for (int t : at_.of(vi))
          for (int m : dt_.neighbors[uz(t)])
            if (m >= 0 && in_[uz(m)] == in_[uz(t)] && (m > t || !contains(at_.of(vi), m))) consider({t, m});
      // Deeper: a channel of tetrahedra in the point's state, from one at the point to one with
      // a free face (breadth first through their faces, at most kChannel long).
      if (best.empty() && !on_surface(static_cast<int>(v))) {
        bool buried = false;
        for (int t : at_.of(vi)) buried = buried || in_[uz(t)];
        std::unordered_map<int, int> parent;  // tetrahedron -> the one it was reached from (-1: at v)
        std::vector<int> layer;
        for (int t : at_.of(vi))
          if ((in_[uz(t)] != 0) == buried) {
            parent.emplace(t, -1);
            layer.push_back(t);
          }
        for (int depth = 1; depth <= kChannel && best.empty() && !layer.empty(); ++depth) {
          std::vector<int> next;
          for (int t : layer)
            for (int m : dt_.neighbors[uz(t)]) {
              if (m < 0 || (in_[uz(m)] != 0) != buried || parent.count(m)) continue;
              parent.emplace(m, t);
              next.push_back(m);
            }
          std::sort(next.begin(), next.end());
          for (int m : next) {
            bool touches = false;
            for (int i = 0; i < 4; ++i) touches = touches || free_face(m, i);
            if (!touches) continue;
            std::vector<int> path;
            for (int x = m; x >= 0; x = parent[x]) path.push_back(x);
            consider(path);
          }
          layer = std::move(next);
        }
      }
      if (best.empty()) {
        left.push_back(static_cast<int>(v));
        continue;
      }
      for (int t : best) toggle(t);
      changed += best.size();
    }
    return (left.empty() || local_search(left, target_faces, changed)) && nfree_ == target_faces;
  }

 private:
  static bool contains(VertexTets::Range r, int x) { return std::find(r.begin(), r.end(), x) != r.end(); }
  int face(int t, int i) const { return face_id_[uz(t)][uz(i)]; }
  void toggle(int t) {
    const int d = in_[uz(t)] ? -1 : 1;
    in_[uz(t)] = static_cast<char>(!in_[uz(t)]);
    for (int i = 0; i < 4; ++i) {
      int& c = count_[uz(face(t, i))];
      nfree_ -= c == 1 ? 1 : 0;
      c += d;
      nfree_ += c == 1 ? 1 : 0;
    }
  }
  bool free_face(int t, int i) const { return count_[uz(face(t, i))] == 1; }
  bool on_surface(int x) {
    work_ += at_.of(x).size();
    for (int t : at_.of(x))
      for (int i = 0; i < 4; ++i)
        if (dt_.tets[uz(t)][uz(i)] != x && free_face(t, i)) return true;
    return false;
  }
  // The free faces at x: their edges opposite x form one cycle (each free face once: from the
  // tetrahedron in the body; a face on the convex hull has no other side).
  bool vertex_ok(int x) {
    work_ += at_.of(x).size();
    std::vector<std::array<int, 2>> link;
    for (int t : at_.of(x)) {
      if (!in_[uz(t)]) continue;
      for (int i = 0; i < 4; ++i) {
        const auto& v = dt_.tets[uz(t)];
        if (v[uz(i)] == x || !free_face(t, i)) continue;
        std::array<int, 2> e{};
        int k = 0;
        for (int l = 0; l < 3; ++l) {
          const int y = v[uz(kFaceOut[i][l])];
          if (y == x) continue;
          if (part_of_ && (*part_of_)[uz(y)] != (*part_of_)[uz(x)]) return false;  // a face across two parts
          e[uz(k++)] = y;
        }
        link.push_back(e);
      }
    }
    return detail::link_is_one_cycle(link);
  }
  // The points the first pass left: single toggles of a tetrahedron at a bad vertex (one not on
  // the surface or whose link is not one cycle), each time the one that leaves the smallest
  // defect 4 * (bad vertices) + |F - target_faces| (ties: the smaller sorted vertex ids), also
  // when that is no smaller (a point two layers deep needs a step that first pinches a
  // neighbour), under a tabu list (a toggled tetrahedron is not toggled again); at most
  // kSearchSteps per point left. The fill's local search in the engine (carve3.cpp) works alike.
  bool local_search(const std::vector<int>& left, std::size_t target_faces, std::size_t& changed) {
    std::set<int> bad(left.begin(), left.end());
    std::set<int> tabu;
    const auto defect = [&] {
      const long long df = static_cast<long long>(nfree_) - static_cast<long long>(target_faces);
      return 4 * static_cast<long long>(bad.size()) + (df < 0 ? -df : df);
    };
    const auto update = [&](int t) {  // the bad set after t was toggled
      for (int x : dt_.tets[uz(t)]) {
        if (vertex_ok(x))
          bad.erase(x);
        else
          bad.insert(x);
      }
    };
    std::size_t steps = 0;
    const std::size_t max_steps = kSearchSteps * left.size();
    while (defect() > 0 && steps++ < max_steps) {
      if (over_budget()) return false;
      long long best_d = 0;
      int best_t = -1;
      std::array<int, 4> best_key{};
      const std::vector<int> now(bad.begin(), bad.end());
      for (int v : now)
        for (int t : at_.of(v)) {
          if (tabu.count(t)) continue;
          work_ += bad.size();
          const std::set<int> saved = bad;
          toggle(t);
          update(t);
          const long long d = defect();
          toggle(t);
          bad = saved;
          std::array<int, 4> key = dt_.tets[uz(t)];
          std::sort(key.begin(), key.end());
          if (best_t < 0 || d < best_d || (d == best_d && key < best_key)) {
            best_d = d;
            best_t = t;
            best_key = key;
          }
        }
      if (best_t < 0) return false;
      toggle(best_t);
      update(best_t);
      tabu.insert(best_t);
      ++changed;
    }
    return defect() == 0;
  }
  // The free faces among the faces of these tetrahedra (each face once).
  long long free_faces_of(const std::vector<int>& set) {
    std::vector<int> fs;
    for (int t : set)
      for (int i = 0; i < 4; ++i)
        if (free_face(t, i)) fs.push_back(face(t, i));
    std::sort(fs.begin(), fs.end());
    return std::unique(fs.begin(), fs.end()) - fs.begin();
  }
  // The area of the free faces of these tetrahedra.
  double area_of(const std::vector<int>& set) {
    double a = 0;
    for (int t : set)
      for (int i = 0; i < 4; ++i) {
        if (!free_face(t, i)) continue;
        const auto& v = dt_.tets[uz(t)];
        a += triangle_area3(pts_[uz(v[uz(kFaceOut[i][0])])], pts_[uz(v[uz(kFaceOut[i][1])])],
                            pts_[uz(v[uz(kFaceOut[i][2])])]);
      }
    return a;
  }

  const PointSet& pts_;
  const Delaunay3& dt_;
  std::vector<char>& in_;
  const std::vector<int>* part_of_;  // when given, a surface face joins the points of one part only
  const VertexTets at_;
  std::vector<std::array<int, 4>> face_id_;  // per tetrahedron, the id of the face opposite vertex i
  std::vector<int> count_;                   // per face id, its tetrahedra in the body
  std::size_t nfree_ = 0;                    // faces with one body tetrahedron
  std::size_t work_ = 0, work_limit_ = 0;    // the work bound (class comment)
  bool capped_ = false;                       // run() gave up at the bound
};

}  // namespace

// The parts' bodies in the common tetrahedralization (parts_body), the points that body buries
// brought to its surface by dimples (SurfaceRepair::run(): every point on the surface with a disk
// link, a closed 2-manifold through all points oriented out of the body, and the parts' face
// count); kept with as many surfaces as parts (then the same Euler characteristic: the parts'
// topology; validate_surfaces3() checks all). First with every surface face inside one part (each
// point on its own part's surface); where that cannot be had, with faces across parts too (linked
// grid tori: a valid pair of tori with one point on the other's surface, where the fallback makes
// one surface). Both tries share one work bound.
bool repaired_parts_body(const PointSet& pts, const Delaunay3& dt, const Parts& parts, const std::vector<Mesh3Result>& res,
                         std::size_t faces, std::vector<std::array<int, 4>>& body, bool& capped, std::size_t& repaired) {
  std::vector<char> in_body = parts_body(pts, dt, parts, res);
  const std::vector<char> start = in_body;
  std::size_t spent = 0;
  for (const std::vector<int>* own : {&parts.part_of, static_cast<const std::vector<int>*>(nullptr)}) {
    if (!own) in_body = start;
    std::size_t freed = 0;
    SurfaceRepair repair(pts, dt, in_body, own);
    repair.start_after(spent);
    const bool ok = repair.run(faces, freed);
    spent = repair.work();
    capped = repair.capped();
    if (repair.capped()) break;
    if (!ok) continue;
    body.clear();
    for (std::size_t t = 0; t < dt.tets.size(); ++t)
      if (in_body[t]) body.push_back(dt.tets[t]);
    const TriMesh3 surface = body_surface(body);
    UnionFind uf(pts.size());
    for (const auto& f : surface.triangles) {
      uf.join(f[0], f[1]);
      uf.join(f[0], f[2]);
    }
    std::size_t components = 0;
    for (std::size_t v = 0; v < pts.size(); ++v) components += uf.find(static_cast<int>(v)) == static_cast<int>(v);
    if (components == parts.points.size()) {
      repaired = freed;
      return true;
    }
  }
  return false;
}

}  // namespace constrict::detail::surfaces3
