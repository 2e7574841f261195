// SPDX-License-Identifier: GPL-3.0-or-later
// Exact evaluation of the 3D apex magnitude for sliver triangles (gamma/detail/apex3.hpp). The
// double formula loses every digit when abc is a few ulps from collinear: e1 x e2 cancels, so the
// circumradius and the plane distance are noise (issue 20, fuzz finding
// tests/data/regression/gamma3_sliver_near_collinear_oracle_inexact.xyz). Implemented in
// src/cgal/exact_apex3.cpp with exact rationals; no CGAL type appears here.
#pragma once

namespace constrict::detail {

/// |γ(abc; p)| from the exact power ρ of p with respect to the diametral sphere of abc, the exact
/// distance h of p from the plane abc and the exact circumradius r of abc: each is one rounding
/// from its rational value, then mag = ρ² / (S (S + t)), t = 2 h r, S = √(t² + ρ²), a few ulps.
/// @pre a, b, c not collinear; p not on the diametral sphere (the sign is decided by the caller).
double exact_apex_magnitude3(const double* a, const double* b, const double* c, const double* p) noexcept;

}  // namespace constrict::detail
