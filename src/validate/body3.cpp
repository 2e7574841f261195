// SPDX-License-Identifier: GPL-3.0-or-later
// Exact validation of a tetrahedral body against its surfaces (validate_body3, validate_surfaces3;
// topology.hpp): every tetrahedron positive (orient3), every face shared by at most two
// tetrahedra and then from opposite sides, and the faces of one tetrahedron only exactly the
// surface triangles, with the orientation out of the body. The face matching groups the 4T face
// occurrences by their smallest vertex (a counting sort), then sorts each small group (a hash map
// took 1 s at 1.3·10^5 points, a radix sort of all occurrences 0.35 s).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "constrict/mesh.hpp"
#include "constrict/predicates.hpp"
#include "constrict/topology.hpp"

namespace constrict {
namespace {

inline std::size_t uz(int i) { return static_cast<std::size_t>(i); }
constexpr int kFaceOut[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// A face occurrence: its sorted vertices and where it came from (tetrahedron * 4 + face, or
// ~triangle for a surface triangle).
struct Occ {
  std::array<int, 3> v;  // sorted
  std::int64_t from;
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
  for (const auto& t : body) {
    for (int v : t)
      if (v < 0 || uz(v) >= n) return {StatusCode::InvalidArgument, "body tetrahedron with a bad index"};
    if (orient3(points[uz(t[0])], points[uz(t[1])], points[uz(t[2])], points[uz(t[3])]) <= 0)
      return {StatusCode::InvalidArgument, "body tetrahedron not positively oriented"};
  }
  std::vector<Occ> occ;
  occ.reserve(4 * body.size() + mesh.triangles.size());
  for (std::size_t t = 0; t < body.size(); ++t)
    for (int i = 0; i < 4; ++i) {
      const std::array<int, 3> f{{body[t][uz(kFaceOut[i][0])], body[t][uz(kFaceOut[i][1])], body[t][uz(kFaceOut[i][2])]}};
      occ.push_back({sorted3(f), static_cast<std::int64_t>(t * 4 + uz(i))});
    }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int v : mesh.triangles[f])
      if (v < 0 || uz(v) >= n) return {StatusCode::InvalidArgument, "surface triangle with a bad index"};
    occ.push_back({sorted3(mesh.triangles[f]), ~static_cast<std::int64_t>(f)});
  }
  // Group the occurrences by their smallest vertex (a counting sort: one pass), then sort each
  // small group by the other two.
  {
    std::vector<std::size_t> off(n + 1, 0);
    for (const Occ& o : occ) ++off[uz(o.v[0]) + 1];
    for (std::size_t v = 0; v < n; ++v) off[v + 1] += off[v];
    std::vector<Occ> grouped(occ.size());
    std::vector<std::size_t> pos(off.begin(), off.end() - 1);
    for (const Occ& o : occ) grouped[pos[uz(o.v[0])]++] = o;
    occ.swap(grouped);
    for (std::size_t v = 0; v < n; ++v)
      std::sort(occ.begin() + static_cast<std::ptrdiff_t>(off[v]), occ.begin() + static_cast<std::ptrdiff_t>(off[v + 1]),
                [](const Occ& x, const Occ& y) {
                  // (v[0] is the group's: explicit compares, not std::array's memcmp)
                  if (x.v[1] != y.v[1]) return x.v[1] < y.v[1];
                  if (x.v[2] != y.v[2]) return x.v[2] < y.v[2];
                  return x.from < y.from;
                });
  }
  // The orientation of an occurrence relative to its sorted triple, out of its tetrahedron (or as
  // the surface triangle is written).
  const auto oriented = [&](const Occ& o) {
    if (o.from < 0) return mesh.triangles[static_cast<std::size_t>(~o.from)];
    const auto& t = body[static_cast<std::size_t>(o.from / 4)];
    const int i = static_cast<int>(o.from % 4);
    return std::array<int, 3>{{t[uz(kFaceOut[i][0])], t[uz(kFaceOut[i][1])], t[uz(kFaceOut[i][2])]}};
  };
  const auto face_name = [](const std::array<int, 3>& v) {
    return "(" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")";
  };
  for (std::size_t i = 0; i < occ.size();) {
    std::size_t j = i + 1;
    const auto same = [&](const Occ& o) { return o.v[0] == occ[i].v[0] && o.v[1] == occ[i].v[1] && o.v[2] == occ[i].v[2]; };
    while (j < occ.size() && same(occ[j])) ++j;
    int tets = 0, tris = 0;
    for (std::size_t k = i; k < j; ++k) (occ[k].from < 0 ? tris : tets) += 1;
    const auto f = [&] { return face_name(occ[i].v); };  // (only for a message)
    if (tris > 1) return {StatusCode::InvalidArgument, "surface triangle " + f() + " appears twice"};
    if (tets > 2) return {StatusCode::InvalidArgument, "face " + f() + " shared by more than two body tetrahedra"};
    if (tets == 2) {
      if (tris) return {StatusCode::InvalidArgument, "surface triangle " + f() + " lies inside the body"};
      const Occ* a = nullptr;
      const Occ* b = nullptr;
      for (std::size_t k = i; k < j; ++k) (a ? b : a) = &occ[k];
      if (even_order(oriented(*a)) == even_order(oriented(*b)))
        return {StatusCode::InvalidArgument, "face " + f() + " has body tetrahedra on the same side (overlap)"};
    } else if (tets == 1) {
      if (!tris) return {StatusCode::InvalidArgument, "free face " + f() + " of the body is not a surface triangle"};
      const Occ* a = nullptr;
      const Occ* s = nullptr;
      for (std::size_t k = i; k < j; ++k) (occ[k].from < 0 ? s : a) = &occ[k];
      if (even_order(oriented(*a)) != even_order(oriented(*s)))
        return {StatusCode::InvalidArgument, "surface triangle " + f() + " is not oriented out of the body"};
    } else if (tris) {
      return {StatusCode::InvalidArgument, "surface triangle " + f() + " is not a face of the body"};
    }
    i = j;
  }
  return Status::ok();
}

}  // namespace constrict
