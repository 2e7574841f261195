// SPDX-License-Identifier: GPL-3.0-or-later
#include "constrict/memory.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace constrict {
namespace detail {

namespace {

std::string first_line(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::string s;
  std::getline(f, s);
  return s;
}

// A virtio balloon (device id 5) that negotiated free page reporting (feature bit 5,
// VIRTIO_BALLOON_F_REPORTING): sysfs lists a device's features as one '0'/'1' per bit, bit 0 first.
bool reports_free_pages(const std::string& root) {
  std::error_code ec;
  std::filesystem::directory_iterator it(root, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const std::string id = first_line(it->path() / "device");
    if (id != "0x0005") continue;
    const std::string features = first_line(it->path() / "features");
    if (features.size() > 5 && features[5] == '1') return true;
  }
  return false;
}

}  // namespace

void return_free_memory() noexcept {
#if defined(__GLIBC__)
  (void)malloc_trim(0);
#endif
}

bool huge_pages_wanted(const char* no_hugepages_env, const std::string& virtio_devices) noexcept {
  if (no_hugepages_env) return false;
  try {
    return !reports_free_pages(virtio_devices);
  } catch (...) {
    return true;
  }
}

}  // namespace detail

bool huge_pages_enabled() noexcept {
  static const bool on = detail::huge_pages_wanted(std::getenv("CONSTRICT_NO_HUGEPAGES"), "/sys/bus/virtio/devices");
  return on;
}

}  // namespace constrict
