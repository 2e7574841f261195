// SPDX-License-Identifier: GPL-3.0-or-later
/// @file points.hpp
/// @brief The input point set: plain doubles, dimension 2 or 3, indices are input order.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "constrict/status.hpp"

namespace constrict {

/// Points stored interleaved: point i is coords[dim*i .. dim*i+dim-1].
struct PointSet {
  int dim = 2;                  ///< 2 or 3
  std::vector<double> coords;   ///< size dim * size()

  std::size_t size() const noexcept { return dim > 0 ? coords.size() / static_cast<std::size_t>(dim) : 0; }
  const double* operator[](std::size_t i) const noexcept { return coords.data() + static_cast<std::size_t>(dim) * i; }
  double* operator[](std::size_t i) noexcept { return coords.data() + static_cast<std::size_t>(dim) * i; }
};

/// One pair of identical input points (first < second, 0-based input indices).
struct DuplicatePair {
  std::size_t first = 0;
  std::size_t second = 0;
};

/// Result of check_points(): what defects the set has.
struct PointCheck {
  std::vector<DuplicatePair> duplicates;  ///< every duplicate, paired with the first occurrence
};

/// Checks a point set for use by the reconstruction and graph builders.
/// Order of checks: dimension, empty, non-finite, duplicates, too few, collinear/coplanar
/// (exact predicates). Duplicates are reported with the first few index pairs in the message and
/// all pairs in @p report (if given).
/// @param[in] points the input
/// @param[out] report optional; filled with all duplicate pairs
/// @return Ok, or EmptyInput, NonFinite, Duplicate, TooFewPoints, Collinear, Coplanar, InvalidArgument
/// @note O(N log N).
Status check_points(const PointSet& points, PointCheck* report = nullptr);

/// Finds all duplicate points (exact coordinate equality). Each later copy is paired with the first
/// occurrence. O(N log N), deterministic.
std::vector<DuplicatePair> find_duplicates(const PointSet& points);

/// Removes later copies of duplicate points.
/// @param[out] kept_index for each point of the result, its index in the original input
/// @return the merged set (first occurrences, in input order)
PointSet merge_duplicates(const PointSet& points, std::vector<std::size_t>* kept_index);

/// Engines rescale their input when the binary exponent of its largest |coordinate| is beyond
/// ±kRescaleExponent: closer to 1 the double-valued parts (γ magnitudes, circumradii, lengths,
/// grid cells) neither overflow nor underflow.
constexpr int kRescaleExponent = 64;

/// The exponent by which measurements scale data far from 1 in magnitude: @p e when beyond
/// ±kRescaleExponent, else 0 (no scaling).
constexpr int rescale_exponent(int e) noexcept { return e > kRescaleExponent || e < -kRescaleExponent ? e : 0; }

/// Binary exponent e of the largest |coordinate| (std::frexp: max |x| in [2^(e-1), 2^e)); 0 when
/// every coordinate is 0. @pre finite coordinates. O(N).
int max_coordinate_exponent(const PointSet& points) noexcept;
/// The same over the points with @p used[i] set (@p used has one entry per point): a picture or a
/// measurement of the vertices a mesh uses is not rescaled for an unused vertex far off.
int max_coordinate_exponent(const PointSet& points, const std::vector<char>& used) noexcept;

/// A copy of @p points with every coordinate times 2^@p e (std::ldexp: exact unless a result
/// overflows or becomes subnormal). For measurements and pictures of data far from magnitude 1;
/// the engines use exact_power_of_two_scale, which refuses a scaling that would lose bits.
/// @note O(N), deterministic.
PointSet scaled_by_power_of_two(const PointSet& points, int e);

/// A copy of @p in scaled by 2^-e, e = max_coordinate_exponent(in), so that the largest
/// |coordinate| lies in [1/2, 1) -- only when every coordinate scales exactly, i.e.
/// ldexp(ldexp(x, -e), e) == x for each x (scaling up never loses bits; scaling down loses them
/// when a coordinate would become subnormal or zero). An exact power-of-two scaling changes no
/// predicate (orientation, in-circle, in-sphere, duplicates), and a double computed from the copy
/// is the one computed from the input times a power of two wherever neither overflows or
/// underflows: the copy gives the input's combinatorics with scale-free magnitudes.
/// @param[in] in the points
/// @param[out] out the scaled copy (dim and size of @p in); left empty on failure
/// @param[out] exponent e (out = in * 2^-e); 0 on failure
/// @return Ok; NonFinite for a NaN or infinite coordinate; Unsupported when the coordinates span
///         too many orders of magnitude to rescale exactly (the message names the extremes and a
///         coordinate that would lose bits). The caller then keeps the original coordinates (its
///         double-valued parts must cope) or returns this status.
/// @note O(N), deterministic; out may alias nothing in @p in.
Status exact_power_of_two_scale(const PointSet& in, PointSet& out, int& exponent);

}  // namespace constrict
