// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the STL reader of read_mesh() (docs/fuzzing.md).
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constrict_fuzz::fuzz_mesh(constrict_fuzz::as_view(data, size), "fuzz.stl");
  return 0;
}
