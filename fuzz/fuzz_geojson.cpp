// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the GeoJSON point reader of read_points() (docs/fuzzing.md).
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constrict_fuzz::fuzz_points(constrict_fuzz::as_view(data, size), "fuzz.geojson", constrict::PointFormat::GeoJson);
  return 0;
}
