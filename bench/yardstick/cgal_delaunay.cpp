// SPDX-License-Identifier: GPL-3.0-or-later
// The yardstick of the speed goals (issue 19; docs/benchmarks.md "Whole process"): reads a text
// point file (x y or x y z per line, whitespace or commas) with fast_float and builds CGAL's
// Delaunay triangulation of it, sequentially, the way a user of CGAL alone would. Prints the
// number of points and of faces / cells, so that the work cannot be optimised away.
// Usage: constrict_yardstick {2|3} FILE
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "read_numbers.hpp"

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int main(int argc, char** argv) {
  if (argc != 3 || (std::string(argv[1]) != "2" && std::string(argv[1]) != "3")) {
    std::fprintf(stderr, "usage: constrict_yardstick {2|3} FILE\n");
    return 2;
  }
  const int dim = argv[1][0] - '0';
  std::vector<double> c;
  if (const int rc = read_numbers("constrict_yardstick", argv[2], c)) return rc;
  const std::size_t n = c.size() / static_cast<std::size_t>(dim);
  if (dim == 2) {
    std::vector<K::Point_2> pts;
    pts.reserve(n);
    for (std::size_t i = 0; i < n; ++i) pts.emplace_back(c[2 * i], c[2 * i + 1]);
    CGAL::Delaunay_triangulation_2<K> dt(pts.begin(), pts.end());
    std::printf("%zu points, %zu faces\n", n, static_cast<std::size_t>(dt.number_of_faces()));
  } else {
    std::vector<K::Point_3> pts;
    pts.reserve(n);
    for (std::size_t i = 0; i < n; ++i) pts.emplace_back(c[3 * i], c[3 * i + 1], c[3 * i + 2]);
    CGAL::Delaunay_triangulation_3<K> dt(pts.begin(), pts.end());
    std::printf("%zu points, %zu cells\n", n, static_cast<std::size_t>(dt.number_of_finite_cells()));
  }
  return 0;
}
