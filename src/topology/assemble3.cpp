// SPDX-License-Identifier: GPL-3.0-or-later
// Stage "assemble" of reconstruct_surfaces3() (detail/surfaces3.hpp; docs/topology.md §"3D"):
// the body of several parts' surfaces in the Delaunay tetrahedralization of all points, by the
// parity of the surfaces around each tetrahedron (inner shells become cavities), and the surfaces'
// roles and parents from the nesting tree of the regions between them. Only combinatorics over
// the tetrahedralization and exact predicates decide; a step that does not hold exactly returns
// false and the ladder (surfaces3.cpp) goes on to its next rung.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "constrict/predicates.hpp"
#include "core/detail/tet_faces.hpp"
#include "core/detail/union_find.hpp"
#include "topology/detail/surfaces3.hpp"
#include "topology/detail/vertex_tets3.hpp"

namespace constrict::detail::surfaces3 {
namespace {

struct FaceKey {
  std::array<int, 3> v;
  bool operator==(const FaceKey& o) const { return v == o.v; }
};
struct FaceHash {
  std::size_t operator()(const FaceKey& k) const {
    std::uint64_t h = 1469598103934665603ULL;
    for (int x : k.v) h = (h ^ static_cast<std::uint32_t>(x)) * 1099511628211ULL;
    return static_cast<std::size_t>(h);
  }
};
FaceKey key_of(int a, int b, int c) {
  std::array<int, 3> v{{a, b, c}};
  std::sort(v.begin(), v.end());
  return {v};
}

// The regions of the tetrahedralization between the surface faces (is_surface(t, i): the face
// opposite vertex i of t): face-connected components not crossing one; region 0 is the exterior
// (the tetrahedra that reach the convex hull through a non-surface face). Returns the count.
template <class IsSurface>
int surface_regions(const Delaunay3& dt, IsSurface&& is_surface, std::vector<int>& region) {
  const std::size_t T = dt.tets.size();
  region.assign(T, -1);
  std::vector<int> queue;
  const auto flood = [&](int r) {
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int t = queue[q];
      for (int i = 0; i < 4; ++i) {
        const int m = dt.neighbors[uz(t)][uz(i)];
        if (m < 0 || is_surface(uz(t), i) || region[uz(m)] >= 0) continue;
        region[uz(m)] = r;
        queue.push_back(m);
      }
    }
    queue.clear();
  };
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i)
      if (dt.neighbors[t][uz(i)] < 0 && !is_surface(t, i) && region[t] < 0) {
        region[t] = 0;
        queue.push_back(static_cast<int>(t));
      }
  flood(0);
  int regions = 1;
  for (std::size_t t = 0; t < T; ++t)
    if (region[t] < 0) {
      region[t] = regions;
      queue.push_back(static_cast<int>(t));
      flood(regions++);
    }
  return regions;
}

}  // namespace

// The body of the part surfaces inside the tetrahedralization of all points: the regions of
// tetrahedra between the surfaces, a tree rooted at the exterior; the body is the regions at odd
// depth. False when a surface face is not a Delaunay face or the regions do not form that tree.
bool assemble_body(const Delaunay3& dt, const std::vector<std::array<int, 3>>& faces, std::vector<std::array<int, 4>>& body) {
  std::vector<std::array<int, 3>> keys;
  keys.reserve(faces.size());
  for (const auto& f : faces) keys.push_back(key_of(f[0], f[1], f[2]).v);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  const std::size_t T = dt.tets.size();
  // Which face of which tetrahedron is a surface face.
  std::vector<std::uint8_t> on_surface(T, 0);  // bit i: face opposite vertex i
  std::size_t found = 0;
  const VertexTets at(dt);
  for (const auto& k : keys)
    at.for_face(k[0], k[1], k[2], [&](int t, int i) {
      on_surface[uz(t)] |= static_cast<std::uint8_t>(1u << i);
      ++found;
    });
  // Every surface face is shared by two tetrahedra, or one on the convex hull.
  std::size_t expect = 0;
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i)
      if (on_surface[t] >> i & 1u) expect += dt.neighbors[t][uz(i)] < 0 ? 2 : 1;
  if (expect != 2 * faces.size() || found > 2 * faces.size()) return false;
  std::vector<int> region;
  const int regions = surface_regions(dt, [&](std::size_t t, int i) { return (on_surface[t] >> i & 1u) != 0; }, region);
  // Region adjacency through surface faces; the depth by breadth-first search from the exterior.
  std::vector<std::vector<int>> adj(uz(regions));
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i) {
      if (!(on_surface[t] >> i & 1u)) continue;
      const int m = dt.neighbors[t][uz(i)];
      const int other = m < 0 ? 0 : region[uz(m)];
      if (other == region[t]) return false;  // a surface with the same region on both sides
      adj[uz(region[t])].push_back(other);
      // (A face on the convex hull is met from its one tetrahedron only: the exterior's side too.
      // Without it a part whose surface is its whole convex hull left the exterior with no way in.)
      if (m < 0) adj[0].push_back(region[t]);
    }
  std::vector<int> depth(uz(regions), -1);
  depth[0] = 0;
  std::vector<int> bfs{0};
  for (std::size_t q = 0; q < bfs.size(); ++q)
    for (int o : adj[uz(bfs[q])]) {
      if (depth[uz(o)] < 0) {
        depth[uz(o)] = depth[uz(bfs[q])] + 1;
        bfs.push_back(o);
      } else if (std::abs(depth[uz(o)] - depth[uz(bfs[q])]) != 1) {
        return false;  // not a tree of nested regions
      }
    }
  for (int d : depth)
    if (d < 0) return false;
  body.clear();
  for (std::size_t t = 0; t < T; ++t)
    if (depth[uz(region[t])] % 2 == 1) body.push_back(dt.tets[t]);
  return true;
}

// The parts' surfaces made of Delaunay faces of all points where edge flips can: a surface face
// that is not one (the other points of the data are inside all of its empty spheres; seen on
// random samples of nested spheres, where a part's own surface keeps nearly coplanar triangles on
// the diagonals that the other part's points exclude) and the surface face across one of its
// edges are replaced by the two triangles on the quad's other diagonal, when fewer of those are
// not Delaunay faces (so every flip lowers their number) and that diagonal is no surface edge
// yet. Each flip keeps every surface a closed, oriented 2-manifold of the same genus through the
// same points (a tetrahedron added to or taken from one part's body); assemble_body() then checks
// the rest.
// Returns the number of flips (0: faces unchanged); at most `max_flips`, in at most 4 passes.
std::size_t flip_to_delaunay_faces(const Delaunay3& dt, std::vector<std::array<int, 3>>& faces, std::size_t max_flips) {
  const VertexTets at(dt);
  const auto is_delaunay = [&](int a, int b, int c) { return at.is_face(a, b, c); };
  // Directed surface edge (a, b) -> its face (an edge is a surface edge in either direction).
  const auto ekey = [](int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); };
  std::unordered_map<std::uint64_t, int> face_of_edge;
  face_of_edge.reserve(3 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) face_of_edge[ekey(faces[f][uz(k)], faces[f][uz((k + 1) % 3)])] = static_cast<int>(f);
  std::size_t flips = 0;
  for (int pass = 0, changed = 1; changed && pass < 4 && flips < max_flips; ++pass) {
    changed = 0;
    for (std::size_t f = 0; f < faces.size() && flips < max_flips; ++f) {
      if (is_delaunay(faces[f][0], faces[f][1], faces[f][2])) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = faces[f][uz(k)], b = faces[f][uz((k + 1) % 3)], c = faces[f][uz((k + 2) % 3)];
        const auto across = face_of_edge.find(ekey(b, a));
        if (across == face_of_edge.end()) continue;
        const std::size_t g = uz(across->second);
        const auto& tg = faces[g];
        int d = -1;
        for (int v : tg)
          if (v != a && v != b) d = v;
        // (a, b, c) and (b, a, d) -> (a, d, c) and (d, b, c): the quad a d b c, diagonal c d.
        if (d < 0 || d == c || face_of_edge.count(ekey(c, d)) || face_of_edge.count(ekey(d, c))) continue;
        // (Fewer faces that are not Delaunay after the flip: a strip of them goes a flip at a time.)
        const int before = 1 + !is_delaunay(tg[0], tg[1], tg[2]), after = !is_delaunay(a, d, c) + !is_delaunay(d, b, c);
        if (after >= before) continue;
        for (const std::size_t h : {f, g})
          for (int j = 0; j < 3; ++j) face_of_edge.erase(ekey(faces[h][uz(j)], faces[h][uz((j + 1) % 3)]));
        faces[f] = {a, d, c};
        faces[g] = {d, b, c};
        for (const std::size_t h : {f, g})
          for (int j = 0; j < 3; ++j) face_of_edge[ekey(faces[h][uz(j)], faces[h][uz((j + 1) % 3)])] = static_cast<int>(h);
        ++flips;
        changed = 1;
        break;
      }
    }
  }
  return flips;
}

// The free faces of a body of positively oriented tetrahedra, oriented out of it.
// (Sorted, not hashed: every face with its sorted ids, then the ones met once.)
TriMesh3 body_surface(const std::vector<std::array<int, 4>>& body) {
  struct Occurrence {
    std::array<int, 3> key, face;
  };
  std::vector<Occurrence> all;
  all.reserve(4 * body.size());
  for (const auto& t : body)
    for (const auto& f : kFaceOut) {
      const std::array<int, 3> face{{t[uz(f[0])], t[uz(f[1])], t[uz(f[2])]}};
      all.push_back({key_of(face[0], face[1], face[2]).v, face});
    }
  std::sort(all.begin(), all.end(), [](const Occurrence& a, const Occurrence& b) { return a.key < b.key; });
  TriMesh3 m;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i + 1;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    if (j - i == 1) m.triangles.push_back(all[i].face);
    i = j;
  }
  std::sort(m.triangles.begin(), m.triangles.end());
  return m;
}

// ---- the surfaces of a mesh -----------------------------------------------------------------------

// Components of the mesh (edge-connected through shared vertices: the surfaces are vertex-disjoint),
// their genus, roles and parents. Roles/parents: an outer surface has the body inside it; nesting by
// the region tree when known (several parts), else every surface is outer with no parent.
std::vector<Surface3> split_surfaces(const PointSet& pts, const TriMesh3& mesh) {
  UnionFind uf(pts.size());
  for (const auto& t : mesh.triangles) {
    uf.join(t[0], t[1]);
    uf.join(t[0], t[2]);
  }
  std::vector<int> best(pts.size(), -1);
  for (const auto& t : mesh.triangles)
    for (int v : t) {
      int& b = best[uz(uf.find(v))];
      if (b < 0 || lex_less3(pts[uz(v)], pts[uz(b)])) b = v;
    }
  std::vector<int> roots;
  for (std::size_t v = 0; v < pts.size(); ++v)
    if (best[v] >= 0 && uf.find(static_cast<int>(v)) == static_cast<int>(v)) roots.push_back(static_cast<int>(v));
  std::sort(roots.begin(), roots.end(), [&](int a, int b) { return lex_less3(pts[uz(best[uz(a)])], pts[uz(best[uz(b)])]); });
  std::vector<int> index_of(pts.size(), -1);
  for (std::size_t k = 0; k < roots.size(); ++k) index_of[uz(roots[k])] = static_cast<int>(k);
  std::vector<Surface3> s(roots.size());
  std::vector<long long> edges(roots.size(), 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) s[uz(index_of[uz(uf.find(mesh.triangles[f][0]))])].triangles.push_back(static_cast<int>(f));
  std::vector<char> used(pts.size(), 0);
  for (const auto& t : mesh.triangles)
    for (int v : t) used[uz(v)] = 1;
  for (std::size_t v = 0; v < pts.size(); ++v)
    if (used[v]) s[uz(index_of[uz(uf.find(static_cast<int>(v)))])].points.push_back(static_cast<int>(v));
  for (Surface3& x : s) {
    // Closed manifold: E = 3F/2, χ = V - E + F = V - F/2, genus = (2 - χ)/2.
    const long long F = static_cast<long long>(x.triangles.size()), V = static_cast<long long>(x.points.size());
    x.genus = static_cast<int>((2 - (V - F / 2)) / 2);
  }
  return s;
}

// Roles and parents (several parts): the regions of the tetrahedralization between the surfaces
// form a tree rooted at the exterior; a surface whose inner side is at odd depth bounds a solid
// (outer), at even depth a cavity (inner); its parent is the surface its outer side was entered by.
void nest_surfaces(const Delaunay3& dt, const TriMesh3& mesh, std::vector<Surface3>& s) {
  if (s.size() < 2) return;
  std::unordered_map<FaceKey, int, FaceHash> face_surface;
  for (std::size_t k = 0; k < s.size(); ++k)
    for (int f : s[k].triangles) {
      const auto& t = mesh.triangles[uz(f)];
      face_surface.emplace(key_of(t[0], t[1], t[2]), static_cast<int>(k));
    }
  const std::size_t T = dt.tets.size();
  const auto surf_of = [&](std::size_t t, int i) {
    const auto& v = dt.tets[t];
    const auto& f = kFaceOut[i];
    auto it = face_surface.find(key_of(v[uz(f[0])], v[uz(f[1])], v[uz(f[2])]));
    return it == face_surface.end() ? -1 : it->second;
  };
  // Which faces of each tetrahedron are surface faces (bit i: face i), one lookup per face on both
  // cores (the map is only read); the flood and the sides below read the bits. (Two lookups per
  // face in sequence had been 15 % of an auto run on two concentric spheres of 2·10^5 points.)
  std::vector<std::uint8_t> on_surface(T, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t)
      for (int i = 0; i < 4; ++i)
        if (surf_of(t, i) >= 0) on_surface[t] = static_cast<std::uint8_t>(on_surface[t] | 1u << i);
  });
  std::vector<int> region;
  const int regions = surface_regions(
      dt, [&](std::size_t t, int i) { return (on_surface[t] >> i & 1u) != 0; }, region);
  // Each surface separates two regions; BFS from the exterior orders them (outer side first).
  std::vector<std::array<int, 2>> sides(s.size(), {{-1, -1}});
  for (std::size_t t = 0; t < T; ++t)
    for (int i = 0; i < 4; ++i) {
      if ((on_surface[t] >> i & 1u) == 0) continue;
      const int k = surf_of(t, i);
      const int m = dt.neighbors[t][uz(i)];
      const int a = region[t], b = m < 0 ? 0 : region[uz(m)];
      sides[uz(k)] = {{std::min(a, b), std::max(a, b)}};
    }
  std::vector<std::vector<std::pair<int, int>>> adj(uz(regions));  // (other region, surface)
  for (std::size_t k = 0; k < s.size(); ++k) {
    adj[uz(sides[k][0])].push_back({sides[k][1], static_cast<int>(k)});
    adj[uz(sides[k][1])].push_back({sides[k][0], static_cast<int>(k)});
  }
  std::vector<int> depth(uz(regions), -1), via(uz(regions), -1);  // via: the surface entered through
  depth[0] = 0;
  std::vector<int> bfs{0};
  for (std::size_t q = 0; q < bfs.size(); ++q) {
    const int r = bfs[q];
    for (const auto& [o, k] : adj[uz(r)]) {
      if (depth[uz(o)] >= 0) continue;
      depth[uz(o)] = depth[uz(r)] + 1;
      via[uz(o)] = k;
      bfs.push_back(o);
      // Surface k: outer side r, inner side o.
      s[uz(k)].role = depth[uz(o)] % 2 == 1 ? SurfaceRole::Outer : SurfaceRole::Inner;
      s[uz(k)].parent = via[uz(r)];
    }
  }
}

// Roles and parents (one part: one connected body): an outer surface encloses the body, an inner
// one faces into a cavity -- the exact sign of its enclosed volume; every inner surface's parent
// is the part's one outer surface.
void nest_in_body(const PointSet& pts, const TriMesh3& mesh, std::vector<Surface3>& s) {
  int outer = -1, n_outer = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    std::vector<int> tris;
    tris.reserve(s[k].triangles.size() * 3);
    for (int f : s[k].triangles) tris.insert(tris.end(), mesh.triangles[uz(f)].begin(), mesh.triangles[uz(f)].end());
    const bool out = signed_volume_sign(pts.coords.data(), tris.data(), s[k].triangles.size()) > 0;
    s[k].role = out ? SurfaceRole::Outer : SurfaceRole::Inner;
    if (out) {
      outer = static_cast<int>(k);
      ++n_outer;
    }
  }
  if (n_outer != 1) return;
  for (Surface3& x : s)
    if (x.role == SurfaceRole::Inner) x.parent = outer;
}

// Per-surface smallest gap to another surface's points (double, the report), over Delaunay edges.
void report_gaps(const PointSet& pts, const std::vector<std::array<int, 2>>& edges, const std::vector<int>& nn,
                 std::vector<Surface3>& s) {
  if (s.size() < 2) return;
  std::vector<int> of(pts.size(), -1);
  for (std::size_t k = 0; k < s.size(); ++k)
    for (int v : s[k].points) of[uz(v)] = static_cast<int>(k);
  for (const auto& e : edges) {
    const int a = of[uz(e[0])], b = of[uz(e[1])];
    if (a < 0 || b < 0 || a == b) continue;
    const double g = gap_ratio(pts, nn, e[0], e[1]);
    for (auto [x, y] : {std::pair<int, int>{a, b}, std::pair<int, int>{b, a}})
      if (g < s[uz(x)].gap_spacings || (g == s[uz(x)].gap_spacings && y < s[uz(x)].nearest_surface)) {
        s[uz(x)].gap_spacings = g;
        s[uz(x)].nearest_surface = y;
      }
  }
}

// Are the parts' bounding boxes pairwise disjoint (exact comparisons of coordinates)? Then their
// bodies, each inside its own convex hull, cannot meet.
bool boxes_apart(const PointSet& pts, const Parts& parts) {
  std::vector<std::array<double, 6>> box;
  for (const auto& ids : parts.points) {
    std::array<double, 6> b{{HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
    for (int v : ids)
      for (int c = 0; c < 3; ++c) {
        b[uz(c)] = std::min(b[uz(c)], pts[uz(v)][c]);
        b[uz(c + 3)] = std::max(b[uz(c + 3)], pts[uz(v)][c]);
      }
    box.push_back(b);
  }
  for (std::size_t a = 0; a < box.size(); ++a)
    for (std::size_t b = a + 1; b < box.size(); ++b) {
      bool apart = false;
      for (int c = 0; c < 3 && !apart; ++c)
        apart = box[a][uz(c + 3)] < box[b][uz(c)] || box[b][uz(c + 3)] < box[a][uz(c)];
      if (!apart) return false;
    }
  return true;
}

// Is every pair of parts strictly on the two sides of a plane (so their convex hulls, which hold
// their bodies, are disjoint)? Rotated parts whose bounding boxes overlap, as rotated flat-faced
// parts a few spacings apart are. Tried: the plane normal to the line between the two centroids
// and the coordinate planes. Decided in double with a bound on the rounding of the dot products
// (each |u.p - fl(u.p)| <= 4 eps sum |u_i p_i|): a gap above both sets' bounds separates them for
// sure; otherwise the answer is "no" (never a wrong "yes").
bool planes_apart(const PointSet& pts, const Parts& parts) {
  const std::size_t k = parts.points.size();
  std::vector<std::array<double, 3>> centroid(k, {0, 0, 0});
  for (std::size_t a = 0; a < k; ++a) {
    for (int v : parts.points[a])
      for (int c = 0; c < 3; ++c) centroid[a][uz(c)] += pts[uz(v)][c];
    for (int c = 0; c < 3; ++c) centroid[a][uz(c)] /= static_cast<double>(parts.points[a].size());
  }
  constexpr double kRound = 4 * std::numeric_limits<double>::epsilon();
  // The smallest and largest u.p over a part, and the largest rounding bound of those products.
  struct Extent {
    double lo = HUGE_VAL, hi = -HUGE_VAL, bound = 0;
  };
  const auto extent = [&](std::size_t a, const std::array<double, 3>& u) {
    Extent e;
    for (int v : parts.points[a]) {
      const double* p = pts[uz(v)];
      const double d = u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
      e.lo = std::min(e.lo, d);
      e.hi = std::max(e.hi, d);
      // (plus the absolute error of products in the subnormal range)
      e.bound = std::max(e.bound, kRound * (std::fabs(u[0] * p[0]) + std::fabs(u[1] * p[1]) + std::fabs(u[2] * p[2])) +
                                      4 * std::numeric_limits<double>::denorm_min());
    }
    return e;
  };
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) {
      const std::array<double, 3> d = {centroid[b][0] - centroid[a][0], centroid[b][1] - centroid[a][1],
                                       centroid[b][2] - centroid[a][2]};
      bool apart = false;
      for (const std::array<double, 3>& u : {d, std::array<double, 3>{1, 0, 0}, std::array<double, 3>{0, 1, 0},
                                             std::array<double, 3>{0, 0, 1}}) {
        if (!std::isfinite(u[0] + u[1] + u[2])) continue;
        const Extent ea = extent(a, u), eb = extent(b, u);
        const double margin = 2 * (ea.bound + eb.bound);
        if (eb.lo - ea.hi > margin || ea.lo - eb.hi > margin) {
          apart = true;
          break;
        }
      }
      if (!apart) return false;
    }
  return true;
}

}  // namespace constrict::detail::surfaces3
