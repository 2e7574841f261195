// SPDX-License-Identifier: GPL-3.0-or-later
// The yardstick of the speed goals (issue 19; docs/benchmarks.md "Whole process"): reads a text
// point file (x y or x y z per line, whitespace or commas) with fast_float and builds CGAL's
// Delaunay triangulation of it, sequentially, the way a user of CGAL alone would. Prints the
// number of points and of faces / cells, so that the work cannot be optimised away.
// Usage: constrict_yardstick {2|3} FILE
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <fast_float/fast_float.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int main(int argc, char** argv) {
  if (argc != 3 || (std::string(argv[1]) != "2" && std::string(argv[1]) != "3")) {
    std::fprintf(stderr, "usage: constrict_yardstick {2|3} FILE\n");
    return 2;
  }
  const int dim = argv[1][0] - '0';
  std::ifstream in(argv[2], std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "constrict_yardstick: cannot open %s\n", argv[2]);
    return 3;
  }
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<double> c;
  const char* p = text.data();
  const char* end = p + text.size();
  while (p < end) {
    while (p < end && (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r' || *p == '\n')) ++p;
    if (p >= end) break;
    double v = 0;
    const auto r = fast_float::from_chars(p, end, v);
    if (r.ec != std::errc()) {
      std::fprintf(stderr, "constrict_yardstick: not a number at byte %ld\n", static_cast<long>(p - text.data()));
      return 5;
    }
    c.push_back(v);
    p = r.ptr;
  }
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
