// SPDX-License-Identifier: GPL-3.0-or-later
// The advancing-front peer of the 3D quality and speed goals (issues 17, 19; docs/reconstruction-3d.md
// §4.9): reads a text point file (x y z per line, whitespace or commas) with fast_float, runs
// CGAL's advancing-front surface reconstruction with its default parameters and writes the
// triangles as OFF over the input points in input order (so `constrict compare` can read it).
// Usage: constrict_afsr FILE.xyz OUT.off
#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstdio>
#include <iterator>
#include <vector>

#include "read_numbers.hpp"

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: constrict_afsr FILE.xyz OUT.off\n");
    return 2;
  }
  std::vector<double> c;
  if (const int rc = read_numbers("constrict_afsr", argv[1], c)) return rc;
  if (c.size() % 3 != 0 || c.size() < 12) {
    std::fprintf(stderr, "constrict_afsr: %s: expected x y z per line, at least 4 points\n", argv[1]);
    return 5;
  }
  const std::size_t n = c.size() / 3;
  std::vector<K::Point_3> pts;
  pts.reserve(n);
  for (std::size_t i = 0; i < n; ++i) pts.emplace_back(c[3 * i], c[3 * i + 1], c[3 * i + 2]);
  std::vector<std::array<std::size_t, 3>> faces;
  CGAL::advancing_front_surface_reconstruction(pts.begin(), pts.end(), std::back_inserter(faces));
  std::FILE* out = std::fopen(argv[2], "w");
  if (!out) {
    std::fprintf(stderr, "constrict_afsr: cannot write %s\n", argv[2]);
    return 4;
  }
  std::fprintf(out, "OFF\n%zu %zu 0\n", n, faces.size());
  for (std::size_t i = 0; i < n; ++i) std::fprintf(out, "%.17g %.17g %.17g\n", c[3 * i], c[3 * i + 1], c[3 * i + 2]);
  for (const auto& f : faces) std::fprintf(out, "3 %zu %zu %zu\n", f[0], f[1], f[2]);
  std::fclose(out);
  std::printf("%zu points, %zu faces\n", n, faces.size());
  return 0;
}
