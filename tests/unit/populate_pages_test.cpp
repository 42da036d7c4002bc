// populate_pages (src/base/populate_pages.h): the pages of a fresh mapping
// present after it, contents unchanged; resize_on_present_pages as resize.
#include "rayform/base/populate_pages.h"

#include "rayform/accel/huge_page_allocator.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace rayform {
namespace {

#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
// How many of the pages of [p, p + bytes) (page aligned) are resident.
size_t resident_pages(void* p, size_t bytes) {
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> in(bytes / page);
  if (mincore(p, bytes, in.data()) != 0) return 0;
  size_t n = 0;
  for (unsigned char c : in) n += c & 1;
  return n;
}

TEST(PopulatePages, MakesTheWholePagesOfAFreshMappingPresentWithTheirContents) {
  const size_t page = size_t(sysconf(_SC_PAGESIZE)), bytes = size_t(9) << 20;  // three tasks' blocks, one partial
  void* m = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(m, MAP_FAILED);
  unsigned char* p = static_cast<unsigned char*>(m);
  ASSERT_EQ(resident_pages(p, bytes), 0u);
  if (madvise(p + bytes - page, page, MADV_POPULATE_WRITE) != 0)
    GTEST_SKIP() << "the kernel refuses MADV_POPULATE_WRITE (before Linux 5.14)";
  ASSERT_EQ(madvise(p + bytes - page, page, MADV_DONTNEED), 0);
  p[5 * page + 7] = 42;  // one page already present, with something in it
  // From inside the first page to inside the last: the partial pages at both ends are left out.
  populate_pages(p + 100, bytes - 200);
  EXPECT_EQ(resident_pages(p + page, bytes - 2 * page), bytes / page - 2);
  EXPECT_EQ(resident_pages(p, page), 0u);
  EXPECT_EQ(resident_pages(p + bytes - page, page), 0u);
  EXPECT_EQ(p[5 * page + 7], 42);
  size_t nonzero = 0;
  for (size_t i = 0; i < bytes; ++i) nonzero += p[i] != 0;
  EXPECT_EQ(nonzero, 1u);
  munmap(m, bytes);
}

TEST(PopulatePages, LeavesLessThanOneTaskBlockAlone) {
  const size_t bytes = size_t(2) << 20;
  void* m = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(m, MAP_FAILED);
  populate_pages(m, bytes);
  EXPECT_EQ(resident_pages(m, bytes), 0u);
  munmap(m, bytes);
}
#endif

TEST(PopulatePages, ResizeOnPresentPagesKeepsTheElementsAndValueInitialisesTheNewOnes) {
  std::vector<uint32_t> v{7, 8, 9};
  resize_on_present_pages(v, size_t(3) << 20);  // 12 MiB of new elements
  ASSERT_EQ(v.size(), size_t(3) << 20);
  EXPECT_EQ(v[0], 7u);
  EXPECT_EQ(v[2], 9u);
  size_t nonzero = 0;
  for (size_t i = 3; i < v.size(); ++i) nonzero += v[i] != 0;
  EXPECT_EQ(nonzero, 0u);
  resize_on_present_pages(v, 2);  // shrinking is resize
  EXPECT_EQ(v, (std::vector<uint32_t>{7, 8}));
  // Any allocator (MeshAccel's arrays use HugePageAllocator, which default-initialises).
  std::vector<float, HugePageAllocator<float>> h(1, 2.5f);
  resize_on_present_pages(h, size_t(2) << 20);
  EXPECT_EQ(h.size(), size_t(2) << 20);
  EXPECT_EQ(h[0], 2.5f);
}

}  // namespace
}  // namespace rayform
