// SPDX-License-Identifier: GPL-3.0-or-later
/// @file predicates.hpp
/// @brief Exact geometric predicates on plain double coordinates (CGAL's filtered Epick kernel
/// behind the scenes). All return -1, 0 or +1 and are exact for any finite double input.
#pragma once

#include <cstddef>

namespace constrict {

/// Sign of the orientation of (a, b, c): +1 counter-clockwise, -1 clockwise, 0 collinear.
int orient2(const double* a, const double* b, const double* c) noexcept;

/// Sign of orient3d: +1 if d lies on the positive side of plane (a,b,c) (i.e. (a,b,c,d) is a
/// positively oriented tetrahedron, CGAL::orientation == POSITIVE), -1 negative, 0 coplanar.
int orient3(const double* a, const double* b, const double* c, const double* d) noexcept;

/// Position of p relative to the circle with diameter ab: +1 outside, 0 on, -1 inside.
/// Equals sign((a-p).(b-p)).
int diametral_side2(const double* a, const double* b, const double* p) noexcept;

/// Position of p relative to the smallest sphere through the triangle abc (centre in its plane):
/// +1 outside, 0 on, -1 inside. @pre a, b, c not collinear.
int diametral_side3(const double* a, const double* b, const double* c, const double* p) noexcept;

/// In-circle: +1 if d is strictly inside the circle through a, b, c (any orientation of abc),
/// 0 on it, -1 outside. @pre a, b, c not collinear.
int in_circle(const double* a, const double* b, const double* c, const double* d) noexcept;

/// In-circle for a counter-clockwise triangle abc (faster: statically filtered). @pre orient2(a,b,c) > 0.
int in_circle_ccw(const double* a, const double* b, const double* c, const double* d) noexcept;

/// In-sphere for a positively oriented tetrahedron (orient3(a,b,c,d) > 0); statically filtered.
int in_sphere_positive(const double* a, const double* b, const double* c, const double* d,
                       const double* e) noexcept;

/// In-sphere: +1 if e strictly inside the sphere through a, b, c, d, 0 on, -1 outside.
/// @pre a, b, c, d not coplanar.
int in_sphere(const double* a, const double* b, const double* c, const double* d,
              const double* e) noexcept;

/// True iff the three points are collinear (3D input). Exact.
bool collinear3(const double* a, const double* b, const double* c) noexcept;

/// Position of p in the circumcircle plane of triangle abc (3D) when p is coplanar:
/// +1 strictly inside the circumcircle, 0 on it, -1 outside. @pre a,b,c,p coplanar, abc not collinear.
int in_circle_coplanar3(const double* a, const double* b, const double* c, const double* p) noexcept;

/// Sign of the signed volume enclosed by oriented triangles: the sign of the sum over the triangles
/// (a, b, c) of det(a - o, b - o, c - o), o the first point of the first triangle (for a closed
/// surface the sum is 6 x the volume whatever o is). Exact for any finite doubles: a double sum with a
/// conservative error bound first, exact multi-precision arithmetic (CGAL::Mpzf) when the bound
/// does not decide (cancellation, overflow or underflow). +1 for a closed surface oriented outward.
/// @param[in] xyz coordinates, 3 per point; @param[in] tris 3 point indices per triangle
struct VolumeEstimate;
int signed_volume_sign(const double* xyz, const int* tris, std::size_t n_tris,
                       const VolumeEstimate* estimate = nullptr) noexcept;
/// The double sum of signed_volume_sign() (6 x the volume about the first point of the first
/// triangle) and a bound on its error; valid false where the bound does not hold (overflow,
/// underflow). One pass over the triangles, to share between the sign and the checked volume.
struct VolumeEstimate {
  double sum6 = 0, bound6 = 0;
  bool valid = false;
};
VolumeEstimate signed_volume_estimate(const double* xyz, const int* tris, std::size_t n_tris) noexcept;
/// The signed volume of the same triangles, checked: `approx` (mesh_volume()'s double value) when
/// the double sum of signed_volume_sign()'s filter is known to about 2^-10 relatively and has
/// approx's sign; otherwise the exact sum (CGAL::Mpzf) converted to double (within about an ulp)
/// and divided by 6, and *exact is set. The exact case is slow (multi-precision over every
/// triangle): bodies much thinner than they are long (500 near-collinear points: -5.5e-23 in double
/// for an exact +6.2e-35). May throw std::bad_alloc.
double signed_volume_checked(const double* xyz, const int* tris, std::size_t n_tris, double approx,
                             bool* exact = nullptr, const VolumeEstimate* estimate = nullptr);

/// How fat a closed polygon is against its edges: the sign of 2|A| - c·Σ|e_i|^2, A its signed
/// area and e_i its m edges (ring[0] ring[1], ..., ring[m-1] ring[0]). Dimensionless and exact
/// (semi-static filter, then CGAL::Mpzf arithmetic). 2|A|/Σ|e|^2 is about m/(2π) for a round ring
/// of even edges and about w/(2h) for a sliver of width w around a path of steps h (docs/topology.md).
/// @param[in] xy coordinates, 2 per point; @param[in] ring m >= 3 point indices; @param[in] c >= 0
int compare_ring_fatness2(const double* xy, const int* ring, std::size_t m, double c) noexcept;

/// The same for a region given as triangles and its walls: the sign of 2A - c·Σ|w_j|^2, 2A the sum
/// of det(b - a, c - a) over the triangles (a, b, c) (their area twice, for counter-clockwise ones)
/// and w_j the walls (2 point indices each; a wall listed twice counts twice). Exact (semi-static
/// filter, then CGAL::Mpzf arithmetic). Used to tell the interior of a ring from a sliver between
/// the two sides of a noisy band (docs/topology.md, "Open arcs").
/// @param[in] tris 3 point indices per triangle; @param[in] walls 2 point indices per wall; c >= 0
int compare_region_fatness2(const double* xy, const int* tris, std::size_t n_tris, const int* walls, std::size_t n_walls,
                            double c) noexcept;

/// compare_region_fatness2's semi-static filter, accumulated one triangle and one wall at a time
/// (for regions scattered over a triangulation: no need to gather them first).
class RegionFatness2Filter {
 public:
  void add_triangle(const double* a, const double* b, const double* c) noexcept;
  void add_wall(const double* a, const double* b) noexcept;
  /// The sign of 2A - c·Σ|w_j|^2 when the filter decides it; 0 when it cannot (cancellation,
  /// overflow, underflow): then compare_region_fatness2() on the gathered region decides.
  int sign(double c) const noexcept;

 private:
  double area_ = 0, area_perm_ = 0, edges_ = 0;
  std::size_t terms_ = 0;
};

/// Compares the distances from p: sign(|p-q|^2 - |p-r|^2): -1 if q is nearer to p than r, 0 if
/// equally near, +1 if farther. Exact (CGAL's filtered compare_distance_to_point).
int compare_distance2(const double* p, const double* q, const double* r) noexcept;

/// A gap against a local spacing: the sign of k·|p-q|^2 - t^2·(|a_0-b_0|^2 + ... + |a_{k-1}-b_{k-1}|^2),
/// i.e. whether the distance pq is at least t times the root mean square of the k lengths a_i b_i.
/// Exact for any finite doubles (semi-static filter, then CGAL::Mpzf arithmetic). @pre k >= 1
/// @param[in] a, b the k segments' endpoints (2D points)
/// @param[in] t the factor (finite, >= 0)
int compare_gap2(const double* p, const double* q, const double* const* a, const double* const* b, int k,
                 double t) noexcept;

/// The 3D version of compare_gap2(): sign of k·|p-q|^2 - t^2·Σ|a_i-b_i|^2 over 3D points. Exact.
/// @pre k >= 1, t finite and >= 0
int compare_gap3(const double* p, const double* q, const double* const* a, const double* const* b, int k,
                 double t) noexcept;

/// The 3D version of compare_distance2(): sign(|p-q|^2 - |p-r|^2). Exact.
int compare_distance3(const double* p, const double* q, const double* r) noexcept;

}  // namespace constrict
