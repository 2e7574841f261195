// SPDX-License-Identifier: GPL-3.0-or-later
/// @file memory.hpp
/// @brief Whether the large arrays ask the kernel for transparent huge pages. A speed hint only:
/// no result depends on it (docs/benchmarks.md, "Huge pages").
#pragma once

#include <string>

namespace constrict {

/// True unless the environment variable CONSTRICT_NO_HUGEPAGES is set, or the machine hands its
/// free memory back to the hypervisor (a virtio balloon with free page reporting, as cloud VMs
/// such as Firecracker's have): there a huge page is usually memory the host has taken back, and
/// its first touch cost 1.03-1.23x the whole run against small pages (measured on the 10^6
/// inputs), where elsewhere huge pages saved up to a fourth. Decided once per process.
bool huge_pages_enabled() noexcept;

namespace detail {
/// Hands the allocator's free pages back to the system (glibc's malloc_trim; nothing elsewhere).
/// For the end of a stage whose helper threads allocated: their arenas keep what they freed, and
/// the next stage, allocating on the calling thread, cannot reuse it (the 2D fallback's parallel
/// tests raised the peak of a 10^6 uniform square by 17 MB without it; the call took 6-7 ms).
/// It trims every arena of the process, the host application's too (which only gives memory back).
void return_free_memory() noexcept;
/// The decision of huge_pages_enabled() from its inputs: the variable's value (null: unset) and
/// the root of the virtio devices in sysfs (normally /sys/bus/virtio/devices).
bool huge_pages_wanted(const char* no_hugepages_env, const std::string& virtio_devices) noexcept;
}  // namespace detail

}  // namespace constrict
