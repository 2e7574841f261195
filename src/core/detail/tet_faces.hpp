// SPDX-License-Identifier: GPL-3.0-or-later
// The faces of a tetrahedron by local vertex, oriented outward: shared by the 3D engine, the
// auto topology and the body validator.
#pragma once

namespace constrict::detail {

// Face opposite local vertex i of a positively oriented tetrahedron, oriented outward (the
// tetrahedron's vertex i lies on its negative side).
constexpr int kFaceOut[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

}  // namespace constrict::detail
