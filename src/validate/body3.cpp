// SPDX-License-Identifier: GPL-3.0-or-later
// Exact validation of a tetrahedral body against its surfaces (validate_body3, validate_surfaces3;
// topology.hpp): every tetrahedron positive (orient3), every face shared by at most two
// tetrahedra and then from opposite sides, and the faces of one tetrahedron only exactly the
// surface triangles, with the orientation out of the body. The face matching groups the 4T face
// occurrences, 8-byte keys, by their smallest vertex (a counting sort whose tasks each own a range
// of groups), then sorts each small group (a hash map took 1 s at 1.3·10^5 points, a radix sort
// of all occurrences 0.35 s; atomic counters shared by the tasks 4x the time of owned ranges).
// Every pass runs in parallel; each check reports the first fault in the sequential order (the
// same message at any thread count).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "constrict/mesh.hpp"
#include "constrict/predicates.hpp"
#include "constrict/topology.hpp"
#include "core/detail/big_vector.hpp"
#include "core/detail/fetch_ahead.hpp"
#include "core/detail/first_index.hpp"
#include "core/detail/owned_ranges.hpp"
#include "core/detail/tet_faces.hpp"

namespace constrict {
namespace {

inline std::size_t uz(int i) { return static_cast<std::size_t>(i); }
constexpr std::size_t kGrain = 1 << 14;
using detail::kFaceOut;

// A face occurrence in the group of its smallest vertex, as one key: the other two vertices b < c
// (ids below 2^31), whether it is a body tetrahedron's face (1) or a surface triangle (0), and its
// parity (1 when it runs as an even permutation of the sorted triple, out of its tetrahedron or as
// the triangle is written). Sorted, the occurrences of a face are adjacent, its triangle first.
using Occ = std::uint64_t;
Occ occ_key(std::uint32_t b, std::uint32_t c, bool tet, bool even) {
  return (std::uint64_t{b} << 33) | (std::uint64_t{c} << 2) | (tet ? 2u : 0u) | (even ? 1u : 0u);
}
std::uint64_t face_of(Occ o) { return o >> 2; }
int occ_b(Occ o) { return static_cast<int>(o >> 33); }
int occ_c(Occ o) { return static_cast<int>((o >> 2) & 0x7fffffffu); }
bool is_tet(Occ o) { return (o & 2u) != 0; }
bool is_even(Occ o) { return (o & 1u) != 0; }

// A tetrahedron or a triangle with its (renumbered) vertices ascending; the top bit of entry j is
// the parity of the face opposite vertex j (a tetrahedron) or of the triangle (entry 0).
constexpr std::uint32_t kParity = 0x80000000u;
constexpr std::uint32_t kId = 0x7fffffffu;
struct Tet {
  std::uint32_t s[4];
};
struct Tri {
  std::uint32_t s[3];
};

// Even permutation of the sorted triple? (The orientation of t relative to its sorted form.)
bool even_order(const std::array<int, 3>& t) {
  int inv = (t[0] > t[1]) + (t[0] > t[2]) + (t[1] > t[2]);
  return inv % 2 == 0;
}

std::array<int, 3> sorted3(std::array<int, 3> t) {
  std::sort(t.begin(), t.end());
  return t;
}

}  // namespace

Status validate_body3(const PointSet& points, const TriMesh3& mesh, const std::vector<std::array<int, 4>>& body) {
  const std::size_t n = points.size();
  const auto bad_index = [&](std::size_t t) {
    for (int v : body[t])
      if (v < 0 || uz(v) >= n) return true;
    return false;
  };
  const auto negative = [&](std::size_t t) {
    detail::fetch_ahead(body, t, body.size(), [&](int x) {
      if (x >= 0 && uz(x) < n) __builtin_prefetch(points[uz(x)]);
    });
    const auto& v = body[t];
    return orient3(points[uz(v[0])], points[uz(v[1])], points[uz(v[2])], points[uz(v[3])]) <= 0;
  };
  // (The first tetrahedron with either fault, and then its first fault: the sequential messages.)
  if (const std::size_t t =
          detail::first_index(body.size(), [&](std::size_t i) { return bad_index(i) || negative(i); });
      t < body.size())
    return {StatusCode::InvalidArgument,
            bad_index(t) ? "body tetrahedron with a bad index" : "body tetrahedron not positively oriented"};
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int v : mesh.triangles[f])
      if (v < 0 || uz(v) >= n) return {StatusCode::InvalidArgument, "surface triangle with a bad index"};
  // The checks below see the vertices renumbered by their first appearance in the body (then in
  // the surface): a bijection, so the verdict is the same, and the groups that neighbouring
  // tetrahedra write to lie near each other in memory (the body's own order is spatial; the
  // points' ids, the input order, need not be: 1.4x faster on a shuffled 10^5-point input).
  std::vector<int> label(n, -1), unlabel;
  unlabel.reserve(n);
  const auto see = [&](int v) {
    if (label[uz(v)] < 0) {
      label[uz(v)] = static_cast<int>(unlabel.size());
      unlabel.push_back(v);
    }
  };
  // (The ids are in input order, at random for a shuffled file: each pass over the tetrahedra or
  // triangles fetches the entries of one a few further on first.)
  const auto fetch_label = [&](int v) { __builtin_prefetch(&label[uz(v)]); };
  for (std::size_t t = 0; t < body.size(); ++t) {
    detail::fetch_ahead(body, t, body.size(), fetch_label);
    for (int v : body[t]) see(v);
  }
  for (const auto& t : mesh.triangles)
    for (int v : t) see(v);
  // Each tetrahedron and triangle with its vertices renumbered and ascending (one parallel pass).
  const std::size_t T = body.size(), F = mesh.triangles.size();
  detail::BigArray<Tet> recs;
  detail::BigArray<Tri> tri_recs;
  recs.allocate(T);
  tri_recs.allocate(F);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, T, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      detail::fetch_ahead(body, t, r.end(), fetch_label);
      const auto& b = body[t];
      const int v[4] = {label[uz(b[0])], label[uz(b[1])], label[uz(b[2])], label[uz(b[3])]};
      Tet x{};
      for (int i = 0; i < 4; ++i) {  // (the four are distinct: every tetrahedron is positive)
        const int rank = (v[0] < v[i]) + (v[1] < v[i]) + (v[2] < v[i]) + (v[3] < v[i]);
        const bool even = even_order({{v[kFaceOut[i][0]], v[kFaceOut[i][1]], v[kFaceOut[i][2]]}});
        x.s[rank] = static_cast<std::uint32_t>(v[i]) | (even ? kParity : 0u);
      }
      recs[t] = x;
    }
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, F, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t f = r.begin(); f != r.end(); ++f) {
      detail::fetch_ahead(mesh.triangles, f, r.end(), fetch_label);
      const auto& m = mesh.triangles[f];
      const std::array<int, 3> w{{label[uz(m[0])], label[uz(m[1])], label[uz(m[2])]}};
      const auto v = sorted3(w);
      tri_recs[f] = Tri{{static_cast<std::uint32_t>(v[0]) | (even_order(w) ? kParity : 0u),
                         static_cast<std::uint32_t>(v[1]), static_cast<std::uint32_t>(v[2])}};
    }
  });
  // Group the occurrences by their smallest vertex: the three faces of a tetrahedron through its
  // smallest vertex s0 in s0's group, the one opposite s0 in s1's; a triangle in its smallest
  // vertex's. Counted, then placed, by P tasks that each own a range of groups and read all
  // tetrahedra and triangles (core/detail/owned_ranges.hpp). Then each small group is sorted: a
  // strict total order, so nothing depends on the number of tasks or on the scheduling.
  const std::size_t groups = unlabel.size();
  std::vector<std::size_t> off(groups + 1, 0);
  const auto owned = [&](const auto& pass) {
    detail::for_owned_ranges(groups, T + F, [&](std::size_t lo, std::size_t hi) {
      pass(static_cast<std::uint32_t>(lo), static_cast<std::uint32_t>(hi));
    });
  };
  const auto in = [](std::uint32_t g, std::uint32_t lo, std::uint32_t hi) { return g >= lo && g < hi; };
  owned([&](std::uint32_t lo, std::uint32_t hi) {
    std::size_t* cnt = off.data() + 1;
    for (std::size_t t = 0; t < T; ++t) {
      const std::uint32_t a = recs[t].s[0] & kId, b = recs[t].s[1] & kId;
      if (in(a, lo, hi)) cnt[a] += 3;
      if (in(b, lo, hi)) cnt[b] += 1;
    }
    for (std::size_t f = 0; f < F; ++f) {
      const std::uint32_t a = tri_recs[f].s[0] & kId;
      if (in(a, lo, hi)) cnt[a] += 1;
    }
  });
  for (std::size_t g = 0; g < groups; ++g) off[g + 1] += off[g];
  detail::BigArray<Occ> occ;  // (every slot written below: not zero-filled; huge pages where the system has them)
  occ.allocate(off[groups]);
  {
    std::vector<std::size_t> at(off.begin(), off.end() - 1);  // the next free slot of each group
    owned([&](std::uint32_t lo, std::uint32_t hi) {
      for (std::size_t t = 0; t < T; ++t) {
        const Tet& x = recs[t];
        const std::uint32_t s0 = x.s[0] & kId, s1 = x.s[1] & kId, s2 = x.s[2] & kId, s3 = x.s[3] & kId;
        const auto even = [&](int j) { return (x.s[j] & kParity) != 0; };  // of the face opposite s_j
        if (in(s0, lo, hi)) {
          Occ* o = occ.data() + at[s0];
          at[s0] += 3;
          o[0] = occ_key(s2, s3, true, even(1));
          o[1] = occ_key(s1, s3, true, even(2));
          o[2] = occ_key(s1, s2, true, even(3));
        }
        if (in(s1, lo, hi)) occ[at[s1]++] = occ_key(s2, s3, true, even(0));
      }
      for (std::size_t f = 0; f < F; ++f) {
        const Tri& x = tri_recs[f];
        const std::uint32_t a = x.s[0] & kId;
        if (in(a, lo, hi)) occ[at[a]++] = occ_key(x.s[1], x.s[2], false, (x.s[0] & kParity) != 0);
      }
    });
  }
  recs = {};
  tri_recs = {};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t g = r.begin(); g != r.end(); ++g) std::sort(occ.data() + off[g], occ.data() + off[g + 1]);
  });
  const auto face_name = [&](const std::array<int, 3>& v) {  // in the caller's ids
    const auto u = sorted3({{unlabel[uz(v[0])], unlabel[uz(v[1])], unlabel[uz(v[2])]}});
    return "(" + std::to_string(u[0]) + ", " + std::to_string(u[1]) + ", " + std::to_string(u[2]) + ")";
  };
  // The first fault of the groups of vertex g, or an empty message.
  const auto group_fault = [&](std::size_t g) -> std::string {
    for (std::size_t i = off[g]; i < off[g + 1];) {
      std::size_t j = i + 1;
      while (j < off[g + 1] && face_of(occ[j]) == face_of(occ[i])) ++j;
      int tets = 0, tris = 0;
      for (std::size_t k = i; k < j; ++k) (is_tet(occ[k]) ? tets : tris) += 1;
      const auto f = [&] {
        return face_name({{static_cast<int>(g), occ_b(occ[i]), occ_c(occ[i])}});
      };  // (messages only)
      if (tris > 1) return "surface triangle " + f() + " appears twice";
      if (tets > 2) return "face " + f() + " shared by more than two body tetrahedra";
      if (tets == 2) {
        if (tris) return "surface triangle " + f() + " lies inside the body";
        if (is_even(occ[i]) == is_even(occ[i + 1]))
          return "face " + f() + " has body tetrahedra on the same side (overlap)";
      } else if (tets == 1) {
        if (!tris) return "free face " + f() + " of the body is not a surface triangle";
        // (sorted: the triangle comes first)
        if (is_even(occ[i + 1]) != is_even(occ[i]))
          return "surface triangle " + f() + " is not oriented out of the body";
      } else if (tris) {
        return "surface triangle " + f() + " is not a face of the body";
      }
      i = j;
    }
    return {};
  };
  if (const std::size_t g = detail::first_index(groups, [&](std::size_t v) { return !group_fault(v).empty(); });
      g < groups)
    return {StatusCode::InvalidArgument, group_fault(g)};
  return Status::ok();
}

}  // namespace constrict
