// SPDX-License-Identifier: GPL-3.0-or-later
// Exact validation of closed triangle meshes (3D reconstruction output); the volume it reports
// is mesh_volume() (src/core/mesh.cpp).
// Combinatorics are exact; geometric tests use the exact orient3 / orient2 predicates only.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <new>
#include <numeric>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_group.h>

#include "constrict/mesh.hpp"
#include "constrict/predicates.hpp"
#include "core/detail/check_points.hpp"
#include "core/detail/fetch_ahead.hpp"
#include "core/detail/first_index.hpp"
#include "core/detail/surface_components.hpp"

namespace constrict {
namespace {

using P2 = std::array<double, 2>;

P2 proj(const double* p, int drop) {
  if (drop == 0) return {{p[1], p[2]}};
  if (drop == 1) return {{p[2], p[0]}};
  return {{p[0], p[1]}};
}

// A coordinate plane on which the (non-degenerate) triangle abc projects to a proper triangle.
int drop_axis(const double* a, const double* b, const double* c) {
  for (int d : {2, 0, 1}) {
    const P2 pa = proj(a, d), pb = proj(b, d), pc = proj(c, d);
    if (orient2(pa.data(), pb.data(), pc.data()) != 0) return d;
  }
  return 2;  // collinear triangle (excluded by the callers)
}

bool on_collinear_segment2(const P2& p, const P2& q, const P2& r) {  // r collinear with pq
  return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) &&
         std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
}

bool segments_meet2(const P2& p, const P2& q, const P2& r, const P2& s) {
  const int o1 = orient2(p.data(), q.data(), r.data()), o2 = orient2(p.data(), q.data(), s.data());
  const int o3 = orient2(r.data(), s.data(), p.data()), o4 = orient2(r.data(), s.data(), q.data());
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && on_collinear_segment2(p, q, r)) return true;
  if (o2 == 0 && on_collinear_segment2(p, q, s)) return true;
  if (o3 == 0 && on_collinear_segment2(r, s, p)) return true;
  if (o4 == 0 && on_collinear_segment2(r, s, q)) return true;
  return false;
}

bool in_closed_triangle2(const P2& p, const P2& a, const P2& b, const P2& c) {
  const int s = orient2(a.data(), b.data(), c.data());
  return orient2(a.data(), b.data(), p.data()) * s >= 0 && orient2(b.data(), c.data(), p.data()) * s >= 0 &&
         orient2(c.data(), a.data(), p.data()) * s >= 0;
}

// Closed segment pq against the closed triangle abc, all coplanar.
bool coplanar_segment_triangle(const double* p, const double* q, const double* a, const double* b,
                               const double* c) {
  const int d = drop_axis(a, b, c);
  const P2 pp = proj(p, d), pq = proj(q, d), pa = proj(a, d), pb = proj(b, d), pc = proj(c, d);
  return in_closed_triangle2(pp, pa, pb, pc) || in_closed_triangle2(pq, pa, pb, pc) ||
         segments_meet2(pp, pq, pa, pb) || segments_meet2(pp, pq, pb, pc) || segments_meet2(pp, pq, pc, pa);
}

// Closed segment pq against the closed triangle abc (exact).
bool segment_meets_triangle(const double* p, const double* q, const double* a, const double* b,
                            const double* c) {
  const int s1 = orient3(a, b, c, p), s2 = orient3(a, b, c, q);
  if (s1 == s2 && s1 != 0) return false;
  if (s1 == 0 && s2 == 0) return coplanar_segment_triangle(p, q, a, b, c);
  // The segment crosses (or touches) the plane in one point; it is in the closed triangle iff
  // the three edge planes through the line pq agree in sign (zeros allowed).
  const int o1 = orient3(p, q, a, b), o2 = orient3(p, q, b, c), o3 = orient3(p, q, c, a);
  const bool pos = o1 > 0 || o2 > 0 || o3 > 0, neg = o1 < 0 || o2 < 0 || o3 < 0;
  return !(pos && neg);
}

// x coplanar with a, d, e: is x in the closed wedge at a spanned by d and e?
bool in_closed_wedge(const double* a, const double* d, const double* e, const double* x) {
  const int ax = drop_axis(a, d, e);
  const P2 pa = proj(a, ax), pd = proj(d, ax), pe = proj(e, ax), px = proj(x, ax);
  const int s = orient2(pa.data(), pd.data(), pe.data());
  return orient2(pa.data(), pd.data(), px.data()) * s >= 0 && orient2(pa.data(), px.data(), pe.data()) * s >= 0;
}

struct Box {
  double lo[3], hi[3];
};

}  // namespace

bool triangles_intersect_improperly(const PointSet& pts, const std::array<int, 3>& t1,
                                    const std::array<int, 3>& t2) {
  int shared = 0;
  for (int u : t1)
    for (int v : t2) shared += (u == v);
  auto P = [&](int i) { return pts[static_cast<std::size_t>(i)]; };
  if (shared >= 3) return true;
  if (shared == 0) {
    for (int k = 0; k < 3; ++k) {
      if (segment_meets_triangle(P(t1[k]), P(t1[(k + 1) % 3]), P(t2[0]), P(t2[1]), P(t2[2]))) return true;
      if (segment_meets_triangle(P(t2[k]), P(t2[(k + 1) % 3]), P(t1[0]), P(t1[1]), P(t1[2]))) return true;
    }
    return false;
  }
  auto in = [](const std::array<int, 3>& t, int v) { return t[0] == v || t[1] == v || t[2] == v; };
  if (shared == 2) {
    // Common edge uv; c, d the other vertices. Proper unless coplanar and on the same side.
    int u = -1, v = -1, c = -1, d = -1;
    for (int x : t1) {
      if (in(t2, x)) (u < 0 ? u : v) = x; else c = x;
    }
    for (int x : t2)
      if (!in(t1, x)) d = x;
    if (orient3(P(u), P(v), P(c), P(d)) != 0) return false;
    const int ax = drop_axis(P(u), P(v), P(c));
    const P2 pu = proj(P(u), ax), pv = proj(P(v), ax), pc = proj(P(c), ax), pd = proj(P(d), ax);
    return orient2(pu.data(), pv.data(), pc.data()) * orient2(pu.data(), pv.data(), pd.data()) > 0;
  }
  // One shared vertex a: t1 = (a,b,c), t2 = (a,d,e). Any extra common point shows up as the far
  // edge of one triangle meeting the other, or as an edge at a lying in the plane of the other
  // triangle inside its closed wedge at a.
  int a = -1;
  for (int x : t1)
    if (in(t2, x)) a = x;
  int b = -1, c = -1, d = -1, e = -1;
  for (int x : t1)
    if (x != a) (b < 0 ? b : c) = x;
  for (int x : t2)
    if (x != a) (d < 0 ? d : e) = x;
  if (segment_meets_triangle(P(b), P(c), P(a), P(d), P(e))) return true;
  if (segment_meets_triangle(P(d), P(e), P(a), P(b), P(c))) return true;
  for (int x : {b, c})
    if (orient3(P(a), P(d), P(e), P(x)) == 0 && in_closed_wedge(P(a), P(d), P(e), P(x))) return true;
  for (int x : {d, e})
    if (orient3(P(a), P(b), P(c), P(x)) == 0 && in_closed_wedge(P(a), P(b), P(c), P(x))) return true;
  return false;
}

namespace {

int find_root(std::vector<int>& parent, int x) {
  while (parent[static_cast<std::size_t>(x)] != x) {
    parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    x = parent[static_cast<std::size_t>(x)];
  }
  return x;
}

Status fail(MeshCheck& d, std::string reason) {
  d.reason = std::move(reason);
  return {StatusCode::InvalidArgument, d.reason};
}

// The vertex links: at vertex a of face (a,b,c) the link edge is b->c; the link of vertex v is
// link[off[v], off[v + 1]) (empty for points that are not vertices).
struct VertexLinks {
  std::vector<std::size_t> off;
  std::vector<std::array<int, 2>> link;
};

// The checks of validate_mesh3, in order (defined after it); each fills its fields of the
// MeshCheck and returns the first failure.
Status check_faces(const PointSet& pts, const TriMesh3& mesh, MeshCheck& d);
Status check_edges(const TriMesh3& mesh, MeshCheck& d);
VertexLinks vertex_links(const TriMesh3& mesh, std::size_t n);
bool edges_ok_from_links(const VertexLinks& vl, MeshCheck& d);
Status check_vertex_links(VertexLinks& vl, MeshCheck& d);
Status check_all_points(const std::vector<std::size_t>& off, const MeshCheckOptions& options, MeshCheck& d);
std::vector<int> face_union_find(const TriMesh3& mesh, std::size_t n);
Status check_topology(const TriMesh3& mesh, const std::vector<std::size_t>& off, std::vector<int>& parent,
                      const MeshCheckOptions& options, MeshCheck& d);
// The double volume (mesh_volume) and the exact orientation's filter sum, both over the faces.
struct Volume {
  double approx = 0;
  VolumeEstimate estimate;
};
Volume measure_volume(const PointSet& pts, const TriMesh3& mesh, std::vector<int>& parent);
Status check_outward(const PointSet& pts, const TriMesh3& mesh, const Volume& volume, MeshCheck& d);
Status check_self_intersections(const PointSet& pts, const TriMesh3& mesh, MeshCheck& d);

}  // namespace

Status validate_mesh3(const PointSet& pts, const TriMesh3& mesh, MeshCheck* details,
                      const MeshCheckOptions& options) {
  MeshCheck local;
  MeshCheck& d = details ? *details : local;
  d = MeshCheck{};
  if (pts.dim != 3) return fail(d, "validate_mesh3: points must be 3D");
  if (Status f = detail::check_finite(pts, "validate_mesh3"); !f) {
    d.reason = f.message();
    return f;
  }
  const std::size_t n = pts.size();
  const std::size_t nf = mesh.triangles.size();
  d.faces = static_cast<long long>(nf);
  if (nf == 0) return fail(d, "mesh has no faces");
  if (n > 0x7fffffffu) return fail(d, "too many points");

  if (Status s = check_faces(pts, mesh, d); !s) return s;
  // The sequential passes overlap: what reads only the faces runs on the other core while the
  // vertex links are built and checked: the union-find of the faces (for check_topology), and
  // from it the double volume and the orientation filter's sum (for check_outward).
  std::vector<int> parent;
  Volume volume;
  tbb::task_group side;
  const struct Join {
    tbb::task_group& g;
    ~Join() { g.wait(); }
  } join{side};
  bool side_failed = false;  // out of memory there: rethrown here, not from Join's destructor
  side.run([&] {
    try {
      parent = face_union_find(mesh, n);
      volume = measure_volume(pts, mesh, parent);
    } catch (const std::bad_alloc&) {
      side_failed = true;
    }
  });
  VertexLinks links = vertex_links(mesh, n);
  // The edges from the vertex stars, in parallel; only when they fail, the sort of all half-edges
  // (check_edges) decides, and names the first failing edge as it always did.
  if (!edges_ok_from_links(links, d)) {
    if (Status s = check_edges(mesh, d); !s) return s;
  }
  if (Status s = check_vertex_links(links, d); !s) return s;
  if (Status s = check_all_points(links.off, options, d); !s) return s;
  side.wait();
  if (side_failed) throw std::bad_alloc();
  if (Status s = check_topology(mesh, links.off, parent, options, d); !s) return s;
  if (Status s = check_outward(pts, mesh, volume, d); !s) return s;
  if (options.self_intersections) return check_self_intersections(pts, mesh, d);
  return Status::ok();
}

namespace {

// 1. every id in range, three distinct ids per face; 2. no face with collinear vertices (each the
// first failing face, in parallel: detail::first_index).
Status check_faces(const PointSet& pts, const TriMesh3& mesh, MeshCheck& d) {
  const std::size_t n = pts.size();
  const std::size_t nf = mesh.triangles.size();
  const std::size_t first = detail::first_index(nf, [&](std::size_t f) {
    const auto& t = mesh.triangles[f];
    for (int v : t)
      if (v < 0 || static_cast<std::size_t>(v) >= n) return true;
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
  });
  for (std::size_t f = first; f < nf; ++f) {
    const auto& t = mesh.triangles[f];
    for (int v : t)
      if (v < 0 || static_cast<std::size_t>(v) >= n)
        return fail(d, "face " + std::to_string(f) + " has vertex id " + std::to_string(v) + " out of range");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      return fail(d, "face " + std::to_string(f) + " repeats a vertex");
  }
  d.indices_ok = true;
  const std::size_t first_flat = detail::first_index(nf, [&](std::size_t f) {
    // (The passes over the faces read per-vertex entries in input order, at random for a shuffled
    // file: each fetches those of a face a few further on.)
    detail::fetch_ahead(mesh.triangles, f, nf, [&](int v) { __builtin_prefetch(pts[static_cast<std::size_t>(v)]); });
    const auto& t = mesh.triangles[f];
    return collinear3(pts[static_cast<std::size_t>(t[0])], pts[static_cast<std::size_t>(t[1])],
                      pts[static_cast<std::size_t>(t[2])]);
  });
  for (std::size_t f = first_flat; f < nf; ++f) {
    const auto& t = mesh.triangles[f];
    if (collinear3(pts[static_cast<std::size_t>(t[0])], pts[static_cast<std::size_t>(t[1])],
                   pts[static_cast<std::size_t>(t[2])]))
      return fail(d, "face " + std::to_string(f) + " is degenerate (collinear vertices)");
  }
  d.non_degenerate = true;
  return Status::ok();
}

// 3. edges: closed, edge-manifold, consistently oriented (d.edges counts them). The half-edges
// are keyed (min, max) << 1 | direction and sorted; bad_edge is the first edge of the first
// failing property.
Status check_edges(const TriMesh3& mesh, MeshCheck& d) {
  std::vector<std::uint64_t> half;
  half.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto u = static_cast<std::uint64_t>(t[static_cast<std::size_t>(k)]);
      const auto v = static_cast<std::uint64_t>(t[static_cast<std::size_t>((k + 1) % 3)]);
      const std::uint64_t lo = std::min(u, v), hi = std::max(u, v);
      half.push_back((lo << 33) | (hi << 1) | (u < v ? 0u : 1u));
    }
  std::sort(half.begin(), half.end());
  long long n_edges = 0;
  bool closed = true, manifold = true, oriented = true;
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    int fwd = 0;
    while (j < half.size() && (half[j] >> 1) == (half[i] >> 1)) {
      fwd += (half[j] & 1u) == 0;
      ++j;
    }
    const std::size_t cnt = j - i;
    ++n_edges;
    const int u = static_cast<int>(half[i] >> 33), v = static_cast<int>((half[i] >> 1) & 0xffffffffu);
    if (cnt == 1 && closed) { closed = false; d.bad_edge = {{u, v}}; }
    if (cnt > 2 && manifold) { manifold = false; if (closed) d.bad_edge = {{u, v}}; }
    if (cnt == 2 && fwd != 1 && oriented) { oriented = false; if (closed && manifold) d.bad_edge = {{u, v}}; }
    i = j;
  }
  d.edges = n_edges;
  d.closed = closed;
  if (!closed)
    return fail(d, "not closed: edge (" + std::to_string(d.bad_edge[0]) + "," + std::to_string(d.bad_edge[1]) + ") has one face");
  d.edge_manifold = manifold;
  if (!manifold)
    return fail(d, "not edge-manifold: edge (" + std::to_string(d.bad_edge[0]) + "," + std::to_string(d.bad_edge[1]) + ") has more than two faces");
  d.oriented = oriented;
  if (!oriented)
    return fail(d, "not consistently oriented at edge (" + std::to_string(d.bad_edge[0]) + "," + std::to_string(d.bad_edge[1]) + ")");
  return Status::ok();
}

VertexLinks vertex_links(const TriMesh3& mesh, std::size_t n) {
  VertexLinks vl;
  std::vector<std::size_t>& off = vl.off;
  off.assign(n + 1, 0);
  const std::size_t nf = mesh.triangles.size();
  for (std::size_t f = 0; f < nf; ++f) {
    detail::fetch_ahead(mesh.triangles, f, nf, [&](int v) { __builtin_prefetch(&off[static_cast<std::size_t>(v) + 1], 1); });
    for (int v : mesh.triangles[f]) ++off[static_cast<std::size_t>(v) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) off[i + 1] += off[i];
  vl.link.resize(3 * nf);
  std::vector<std::size_t> fill(off.begin(), off.end() - 1);
  for (std::size_t f = 0; f < nf; ++f) {
    detail::fetch_ahead(mesh.triangles, f, nf, [&](int v) { __builtin_prefetch(&fill[static_cast<std::size_t>(v)], 1); });
    const auto& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k)
      vl.link[fill[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])]++] =
          {{t[static_cast<std::size_t>((k + 1) % 3)], t[static_cast<std::size_t>((k + 2) % 3)]}};
  }
  return vl;
}

// Closed, edge-manifold and consistently oriented, read from the vertex stars: the faces at v
// are (v, x, y) for its link entries (x, y), with the half-edges v->x and y->v, so every edge
// {v, w} has exactly two faces, one each way, iff w occurs exactly once as an x and once as a y
// in v's star. Per vertex, in parallel; the edges are counted at their smaller end. True (and
// d.edges, d.closed, d.edge_manifold, d.oriented set) when every edge passes.
bool edges_ok_from_links(const VertexLinks& vl, MeshCheck& d) {
  const std::size_t n = vl.off.size() - 1;
  std::atomic<bool> ok{true};
  const long long n_edges = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 4096), 0LL,
      [&](const tbb::blocked_range<std::size_t>& r, long long count) {
        std::vector<std::uint64_t> ends;  // w << 1 | (1: y, the half-edge w->v)
        for (std::size_t v = r.begin(); v != r.end() && ok.load(std::memory_order_relaxed); ++v) {
          ends.clear();
          for (std::size_t k = vl.off[v]; k < vl.off[v + 1]; ++k) {
            ends.push_back(static_cast<std::uint64_t>(vl.link[k][0]) << 1);
            ends.push_back(static_cast<std::uint64_t>(vl.link[k][1]) << 1 | 1u);
          }
          std::sort(ends.begin(), ends.end());
          for (std::size_t i = 0; i < ends.size(); i += 2) {
            // Sorted, each w must come as exactly the pair (w, x) (w, y): a third entry of w
            // would start the next pair, whose ends then differ.
            const bool pair = i + 1 < ends.size() && (ends[i] >> 1) == (ends[i + 1] >> 1) && (ends[i] & 1u) == 0 &&
                              (ends[i + 1] & 1u) == 1;
            if (!pair) {
              ok.store(false, std::memory_order_relaxed);
              break;
            }
            if ((ends[i] >> 1) > v) ++count;
          }
        }
        return count;
      },
      [](long long a, long long b) { return a + b; });
  if (!ok.load()) return false;
  d.edges = n_edges;
  d.closed = d.edge_manifold = d.oriented = true;
  return true;
}

// Whether the link edges link[b, e) (sorted here) form one cycle of length e - b.
bool link_is_one_cycle(std::vector<std::array<int, 2>>& link, std::size_t b, std::size_t e) {
  std::sort(link.begin() + static_cast<std::ptrdiff_t>(b), link.begin() + static_cast<std::ptrdiff_t>(e));
  bool ok = true;
  for (std::size_t k = b + 1; k < e && ok; ++k) ok = link[k][0] != link[k - 1][0];
  std::size_t steps = 0;
  int cur = link[b][0];
  if (ok) {
    do {
      auto it = std::lower_bound(link.begin() + static_cast<std::ptrdiff_t>(b),
                                 link.begin() + static_cast<std::ptrdiff_t>(e), std::array<int, 2>{{cur, -1}});
      if (it == link.begin() + static_cast<std::ptrdiff_t>(e) || (*it)[0] != cur) { ok = false; break; }
      cur = (*it)[1];
      ++steps;
    } while (cur != link[b][0] && steps <= e - b);
    ok = ok && cur == link[b][0] && steps == e - b;
  }
  return ok;
}

// 4. vertex-manifold: the link of every vertex is one cycle (d.vertices counts the vertices).
Status check_vertex_links(VertexLinks& vl, MeshCheck& d) {
  const std::size_t n = vl.off.size() - 1;
  // Every link on its own, in parallel (each sorts its own range); then the first failing vertex.
  std::vector<char> bad(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v)
      if (vl.off[v] != vl.off[v + 1]) bad[v] = !link_is_one_cycle(vl.link, vl.off[v], vl.off[v + 1]);
  });
  long long n_vertices = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (vl.off[v] == vl.off[v + 1]) continue;
    ++n_vertices;
    if (bad[v]) {
      d.bad_vertex = static_cast<int>(v);
      return fail(d, "not vertex-manifold: the link of vertex " + std::to_string(v) + " is not one cycle");
    }
  }
  d.vertex_manifold = true;
  d.vertices = n_vertices;
  return Status::ok();
}

// 5. points used: every input point is a vertex (an error only when options require it).
Status check_all_points(const std::vector<std::size_t>& off, const MeshCheckOptions& options, MeshCheck& d) {
  const std::size_t n = off.size() - 1;
  d.all_points = static_cast<std::size_t>(d.vertices) == n;
  if (!d.all_points) {
    for (std::size_t v = 0; v < n; ++v)
      if (off[v] == off[v + 1]) { d.missing_point = static_cast<int>(v); break; }
    if (options.require_all_points)
      return fail(d, "point " + std::to_string(d.missing_point) + " is not a vertex (" +
                         std::to_string(n - static_cast<std::size_t>(d.vertices)) + " points missing)");
  }
  return Status::ok();
}

// The union-find of the vertices along the face edges (ids in range: check_faces).
std::vector<int> face_union_find(const TriMesh3& mesh, std::size_t n) {
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const std::size_t nf = mesh.triangles.size();
  for (std::size_t f = 0; f < nf; ++f) {
    detail::fetch_ahead(mesh.triangles, f, nf, [&](int v) { __builtin_prefetch(&parent[static_cast<std::size_t>(v)], 1); });
    const auto& t = mesh.triangles[f];
    const int r0 = find_root(parent, t[0]);
    for (int k = 1; k < 3; ++k) {
      const int r = find_root(parent, t[static_cast<std::size_t>(k)]);
      if (r != r0) parent[static_cast<std::size_t>(r)] = r0;
    }
  }
  return parent;
}

// 6. one component (parent: face_union_find), χ = 2, F = 2V - 4.
Status check_topology(const TriMesh3& mesh, const std::vector<std::size_t>& off, std::vector<int>& parent,
                      const MeshCheckOptions& options, MeshCheck& d) {
  const std::size_t n = off.size() - 1;
  const std::size_t nf = mesh.triangles.size();
  int comps = 0;
  for (std::size_t v = 0; v < n; ++v)
    if (off[v] != off[v + 1] && find_root(parent, static_cast<int>(v)) == static_cast<int>(v)) ++comps;
  d.components = comps;
  d.one_component = comps == 1;
  d.euler = d.vertices - d.edges + static_cast<long long>(nf);
  if (d.one_component && d.euler % 2 == 0 && d.euler <= 2) d.genus = static_cast<int>((2 - d.euler) / 2);
  if (options.any_topology) {
    // χ = Σ (2 - 2 g_i) over the closed components: 2c - χ is twice the total genus.
    const long long twice_genus = 2LL * comps - d.euler;
    if (twice_genus < 0 || twice_genus % 2 != 0)
      return fail(d, "Euler characteristic " + std::to_string(d.euler) + " impossible for " + std::to_string(comps) +
                         " closed surfaces");
    d.genus = static_cast<int>(twice_genus / 2);
    d.euler_ok = d.face_count_ok = true;
    return Status::ok();
  }
  if (!d.one_component) return fail(d, "mesh has " + std::to_string(comps) + " components");
  d.euler_ok = d.euler == 2;
  if (!d.euler_ok)
    return fail(d, "Euler characteristic " + std::to_string(d.euler) + " (genus " + std::to_string(d.genus) + "), expected 2");
  d.face_count_ok = static_cast<long long>(nf) == 2 * d.vertices - 4;
  if (!d.face_count_ok) return fail(d, "face count " + std::to_string(nf) + " != 2V-4");
  return Status::ok();
}

// mesh_volume over the surfaces of the union-find (not a second one), with the filter's sum in
// the same pass.
Volume measure_volume(const PointSet& pts, const TriMesh3& mesh, std::vector<int>& parent) {
  Volume v;
  v.approx = detail::mesh_volume_of_surfaces(
      pts, mesh, detail::number_surfaces(pts.size(), mesh, [&](int x) { return find_root(parent, x); }), &v.estimate);
  return v;
}

// 7. outward: the sign decides, exactly (the double volume can overflow, underflow or cancel).
Status check_outward(const PointSet& pts, const TriMesh3& mesh, const Volume& volume, MeshCheck& d) {
  const int* tris = mesh.triangles.empty() ? nullptr : mesh.triangles[0].data();
  const int sign = signed_volume_sign(pts.coords.data(), tris, mesh.triangles.size(), &volume.estimate);
  // A body much thinner than it is long can cancel the double sum (near-collinear points:
  // -5.5e-23 for an exact 6.2e-35); the exact value then.
  d.volume = signed_volume_checked(pts.coords.data(), tris, mesh.triangles.size(), volume.approx, &d.volume_exact,
                                   &volume.estimate);
  d.outward = sign > 0;
  if (!d.outward) return fail(d, "orientation is inward (signed volume " + std::to_string(d.volume) + ")");
  return Status::ok();
}

std::vector<Box> face_boxes(const PointSet& pts, const TriMesh3& mesh) {
  const std::size_t nf = mesh.triangles.size();
  std::vector<Box> box(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      box[f].lo[k] = box[f].hi[k] = pts[static_cast<std::size_t>(mesh.triangles[f][0])][k];
      for (int j = 1; j < 3; ++j) {
        const double x = pts[static_cast<std::size_t>(mesh.triangles[f][static_cast<std::size_t>(j)])][k];
        box[f].lo[k] = std::min(box[f].lo[k], x);
        box[f].hi[k] = std::max(box[f].hi[k], x);
      }
    }
  }
  return box;
}

// 8. self-intersections: sweep over the faces' x-extents, exact test of the pairs whose boxes
// meet; reports the first intersecting pair of the sweep.
Status check_self_intersections(const PointSet& pts, const TriMesh3& mesh, MeshCheck& d) {
  d.self_intersection_checked = true;
  const std::size_t nf = mesh.triangles.size();
  const std::vector<Box> box = face_boxes(pts, mesh);
  std::vector<std::size_t> order(nf);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return box[a].lo[0] != box[b].lo[0] ? box[a].lo[0] < box[b].lo[0] : a < b;
  });
  std::vector<std::size_t> active;
  for (std::size_t f : order) {
    std::size_t w = 0;
    for (std::size_t g : active)
      if (box[g].hi[0] >= box[f].lo[0]) active[w++] = g;
    active.resize(w);
    for (std::size_t g : active) {
      if (box[g].hi[1] < box[f].lo[1] || box[f].hi[1] < box[g].lo[1] || box[g].hi[2] < box[f].lo[2] ||
          box[f].hi[2] < box[g].lo[2])
        continue;
      if (triangles_intersect_improperly(pts, mesh.triangles[g], mesh.triangles[f])) {
        d.intersecting_faces = {{static_cast<int>(std::min(f, g)), static_cast<int>(std::max(f, g))}};
        return fail(d, "faces " + std::to_string(d.intersecting_faces[0]) + " and " +
                           std::to_string(d.intersecting_faces[1]) + " intersect");
      }
    }
    active.push_back(f);
  }
  d.no_self_intersections = true;
  return Status::ok();
}

}  // namespace

}  // namespace constrict
