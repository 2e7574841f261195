// SPDX-License-Identifier: GPL-3.0-or-later
// The key of an undirected edge {u, v} of vertex ids: one 64-bit word, (min << 32) | max.
#pragma once

#include <cstdint>
#include <utility>

namespace constrict::detail {

inline std::uint64_t edge_key(int u, int v) {
  if (u > v) std::swap(u, v);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) | static_cast<std::uint32_t>(v);
}

}  // namespace constrict::detail
