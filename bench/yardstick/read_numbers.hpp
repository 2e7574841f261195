// SPDX-License-Identifier: GPL-3.0-or-later
// The reader of the bench yardsticks (cgal_delaunay.cpp, cgal_afsr.cpp): every number of a text
// file (whitespace or commas between them) with fast_float, as a user of CGAL alone would read it.
#pragma once

#include <fast_float/fast_float.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

// Returns 0 and the numbers in out, or the exit code after a message on stderr (3: cannot open,
// 5: not a number).
inline int read_numbers(const char* who, const char* path, std::vector<double>& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "%s: cannot open %s\n", who, path);
    return 3;
  }
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const char* p = text.data();
  const char* end = p + text.size();
  while (p < end) {
    while (p < end && (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r' || *p == '\n')) ++p;
    if (p >= end) break;
    double v = 0;
    const auto r = fast_float::from_chars(p, end, v);
    if (r.ec != std::errc()) {
      std::fprintf(stderr, "%s: not a number at byte %ld\n", who, static_cast<long>(p - text.data()));
      return 5;
    }
    out.push_back(v);
    p = r.ptr;
  }
  return 0;
}
