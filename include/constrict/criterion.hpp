// SPDX-License-Identifier: GPL-3.0-or-later
/// @file criterion.hpp
/// @brief Selection criteria of the constriction engines (which removable boundary simplex goes
/// next). The engines (reconstruct2(), reconstruct3()) keep their removability rules, heap,
/// fallbacks and validation; only the key changes. Formulas, sources and measured comparison:
/// docs/comparison-methods.md.
#pragma once

#include <string>

namespace constrict {

/// Criterion of the constriction (Constrict2Options::criterion, Constrict3Options::criterion).
/// Every key is "larger is removed first"; ties are broken by the engines' stable vertex ids.
enum class Criterion {
  /// Veltkamp (seed paper §4.1, §4.2): largest sum of 1 - γ over the boundary segments of the
  /// simplex. In 3D the two-face key follows Constrict3Options::two_face_key (Sum = paper).
  Gamma,
  /// Boissonnat's minimal area change (seed paper §2.6, [Boissonnat 84b]): smallest
  /// (Σ area interior faces - Σ area boundary faces) / (Σ area all faces); in 2D the "area" of a
  /// face is the length of the triangle side. Key = -ratio.
  MinAreaChange,
  /// The criterion of [Boissonnat 84a] as seed paper §6 describes it: the same as γ for a
  /// simplex with one boundary segment, but a tetrahedron with two boundary faces is ranked by
  /// one face (the larger 1 - γ) instead of the sum. Identical to Gamma in 2D.
  Boissonnat,
};

/// Name used by the CLI and reports: "gamma", "min-area-change", "boissonnat".
const char* criterion_name(Criterion c) noexcept;

/// Parses a name of criterion_name().
/// @return false (and leaves @p out unchanged) for an unknown name
bool criterion_from_name(const std::string& name, Criterion& out) noexcept;

/// Minimal-area-change ratio of a triangle (2D) removed through its boundary edge ab with apex y:
/// (|ay| + |yb| - |ab|) / (|ay| + |yb| + |ab|), in [0, 1) (double arithmetic).
/// @pre a, b, y distinct
double area_change_ratio2(const double* a, const double* b, const double* y) noexcept;

/// Minimal-area-change ratio of a tetrahedron (3D) given the areas of its four faces and which of
/// them are on the boundary: (Σ interior - Σ boundary) / Σ all, in (-1, 1).
/// @param[in] areas face areas (any order)
/// @param[in] on_boundary on_boundary[i] true iff face i is a boundary face
double area_change_ratio3(const double areas[4], const bool on_boundary[4]) noexcept;

/// Area of the triangle abc (3D, double arithmetic).
double triangle_area3(const double* a, const double* b, const double* c) noexcept;

/// 2D criterion key of removing triangle (a, b, y) through its boundary edge a->b (the body on
/// its left, y the apex): 1 - γ(ab; y) for Gamma and Boissonnat, -area_change_ratio2() for
/// MinAreaChange. Larger keys are removed first.
double criterion_key2(Criterion c, const double* a, const double* b, const double* y) noexcept;

}  // namespace constrict
