// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the PLY readers of read_points() and read_mesh() (docs/fuzzing.md).
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = constrict_fuzz::as_view(data, size);
  constrict_fuzz::fuzz_points(input, "fuzz.ply", constrict::PointFormat::Ply);
  constrict_fuzz::fuzz_mesh(input, "fuzz.ply");
  return 0;
}
