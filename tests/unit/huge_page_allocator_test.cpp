// The allocator of MeshAccel's nodes and packets (src/accel/huge_page_allocator.h):
// large arrays on whole, advised huge pages; small ones aligned as their type.
#include "rayform/accel/huge_page_allocator.h"
#include "rayform/accel/mesh_accel.h"
#include "rayform/scene/procedural_mesh.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace rayform {
namespace {

#if defined(__linux__)
// The VmFlags of the mapping holding address p in /proc/self/smaps ("" if none).
std::string vm_flags_at(const void* p) {
  const uintptr_t a = reinterpret_cast<uintptr_t>(p);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    // Mapping headers start "lo-hi perms ..." in hex; the other lines are "Name: value".
    if (range >> std::hex >> lo >> dash >> hi && dash == '-' && line.find(':') > line.find(' ')) {
      inside = lo <= a && a < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}
#endif

TEST(HugePageAllocator, LargeArraysSitOnWholeAdvisedHugePages) {
  std::vector<float, HugePageAllocator<float>> v(3 * huge_page_bytes / sizeof(float) + 1, 1.5f);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % huge_page_bytes, 0u);
  EXPECT_EQ(v.front(), 1.5f);
  EXPECT_EQ(v.back(), 1.5f);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // "hg": the mapping was advised MADV_HUGEPAGE (whether the kernel grants
  // huge pages then depends on the system's setting, not on us).
  const std::string flags = vm_flags_at(v.data() + v.size() - 1);
  ASSERT_FALSE(flags.empty()) << "no mapping found in /proc/self/smaps";
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
#endif
}

TEST(HugePageAllocator, SmallArraysKeepTheirTypesAlignment) {
  std::vector<WideBvhNode, HugePageAllocator<WideBvhNode>> nodes(3);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(nodes.data()) % alignof(WideBvhNode), 0u);
  std::vector<TrianglePacket, HugePageAllocator<TrianglePacket>> packets(5);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(packets.data()) % alignof(TrianglePacket), 0u);
  packets.resize(huge_page_bytes / sizeof(TrianglePacket) + 1);  // grows from small to huge
  EXPECT_EQ(reinterpret_cast<uintptr_t>(packets.data()) % huge_page_bytes, 0u);
}

// Sizes near the limit throw: rounding up to whole huge pages must not wrap
// around to a small mapping.
TEST(HugePageAllocator, AbsurdSizesThrowInsteadOfWrapping) {
  using A = HugePageAllocator<TrianglePacket>;
  A a;
  EXPECT_THROW((void)a.allocate(A::max_size() + 1), std::bad_array_new_length);
  EXPECT_THROW((void)a.allocate(A::max_size()), std::bad_alloc);  // 2^63 bytes: no system maps that
}

TEST(HugePageAllocator, MeshAccelOfALargeMeshUsesIt) {
  const Mesh torus = make_bumpy_torus(100000, 1);
  const MeshAccel m = build_mesh_accel(torus.positions, torus.indices);
  ASSERT_GE(m.packets.size() * sizeof(TrianglePacket), huge_page_bytes);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(m.packets.data()) % huge_page_bytes, 0u);
}

}  // namespace
}  // namespace rayform
