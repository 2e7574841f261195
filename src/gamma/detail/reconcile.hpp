// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cmath>

namespace constrict::detail {

/// Makes two side values consistent with the exact sign of their sum (spec §2.2), given by an
/// exact in-circle/in-sphere test @p ic of the two apexes realising them: ic == 0 (co-circular /
/// co-spherical) -> equal magnitudes (the larger); ic < 0 (sum > 0) -> the positive value has the
/// strictly larger magnitude; ic > 0 (sum < 0) -> the negative one has. Signs are never changed,
/// so Δ (the larger-magnitude value) always has the exact sign of the sum.
inline void reconcile_side_values(double& ga, double& gb, int ic) {
  auto sgn_mag = [](double g, double mag) { return g > 0 ? mag : (g < 0 ? -mag : 0.0); };
  if (ic == 0) {
    const double mag = std::fmax(std::fabs(ga), std::fabs(gb));
    ga = sgn_mag(ga, mag);
    gb = sgn_mag(gb, mag);
    return;
  }
  double& pos = ga >= gb ? ga : gb;
  double& neg = ga >= gb ? gb : ga;
  if (!(neg < 0 && pos > 0)) return;
  if (ic < 0 && -neg >= pos) neg = -std::nextafter(pos, 0.0);
  if (ic > 0 && pos >= -neg) pos = std::nextafter(-neg, 0.0);
}

}  // namespace constrict::detail
