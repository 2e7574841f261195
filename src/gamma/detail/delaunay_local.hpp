// SPDX-License-Identifier: GPL-3.0-or-later
// Transitional: the ranked/local Delaunay export moved to cgal/detail/delaunay_local.hpp (next to
// its definition in src/cgal/delaunay.cpp). Kept only for src/constrict/constrict2.cpp, which
// still includes this path; remove once that file includes the new one.
#pragma once
#include "cgal/detail/delaunay_local.hpp"
