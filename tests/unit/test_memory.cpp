// SPDX-License-Identifier: GPL-3.0-or-later
// The huge-page decision (constrict/memory.hpp) from a fake sysfs tree of virtio devices.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "constrict/memory.hpp"

namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& s) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << s << "\n";
}

fs::path fresh_root(const std::string& name) {
  const fs::path root = fs::temp_directory_path() / ("constrict_memory_" + name);
  fs::remove_all(root);
  fs::create_directories(root);
  return root;
}

}  // namespace

TEST(HugePages, OffWhereTheBalloonReportsFreePages) {
  using constrict::detail::huge_pages_wanted;
  const fs::path root = fresh_root("reporting");
  write(root / "virtio1" / "device", "0x0002");  // a block device: its feature bits mean other things
  write(root / "virtio1" / "features", "1111111111");
  EXPECT_TRUE(huge_pages_wanted(nullptr, root.string()));
  write(root / "virtio0" / "device", "0x0005");  // a balloon without free page reporting (bit 5)
  write(root / "virtio0" / "features", "0110000100000000000000000000000100000000");
  EXPECT_TRUE(huge_pages_wanted(nullptr, root.string()));
  write(root / "virtio0" / "features", "0110010100000000000000000000000100000000");  // with it
  EXPECT_FALSE(huge_pages_wanted(nullptr, root.string()));
  fs::remove_all(root);
}

TEST(HugePages, VariableAndMissingSysfs) {
  using constrict::detail::huge_pages_wanted;
  EXPECT_TRUE(huge_pages_wanted(nullptr, "/nonexistent/constrict/virtio"));  // no virtio bus: a plain machine
  EXPECT_FALSE(huge_pages_wanted("1", "/nonexistent/constrict/virtio"));
  EXPECT_FALSE(huge_pages_wanted("", "/nonexistent/constrict/virtio"));  // set, even empty
}
