// select_in_order (src/base/select_in_order.h): the kept indices numbered as
// one loop over them would number them, across many blocks and none.
#include "rayform/base/select_in_order.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <vector>

namespace rayform {
namespace {

TEST(SelectInOrder, NumbersTheKeptIndicesInIndexOrderAcrossBlocks) {
  const size_t n = 1000003;
  auto keep = [](size_t i) { return i % 7 == 3 || i % 1000 == 0; };
  std::vector<uint32_t> serial;
  for (size_t i = 0; i < n; ++i)
    if (keep(i)) serial.push_back(uint32_t(i));
  std::vector<uint32_t> selected;
  std::atomic<int> sized_calls{0};
  std::atomic<bool> emitted_before_sized{false};
  select_in_order(
      n, 4096, keep,
      [&](size_t total) {
        ++sized_calls;
        selected.assign(total, ~0u);
      },
      [&](size_t i, size_t rank) {
        if (sized_calls == 0) emitted_before_sized = true;
        selected[rank] = uint32_t(i);
      });
  EXPECT_EQ(sized_calls, 1);
  EXPECT_FALSE(emitted_before_sized);
  EXPECT_EQ(selected, serial);
}

TEST(SelectInOrder, NothingKeptOrNothingAtAll) {
  size_t total = 99;
  int emits = 0;
  select_in_order(
      5000, 64, [](size_t) { return false; }, [&](size_t t) { total = t; }, [&](size_t, size_t) { ++emits; });
  EXPECT_EQ(total, 0u);
  EXPECT_EQ(emits, 0);
  total = 99;
  select_in_order(
      0, 64, [](size_t) { return true; }, [&](size_t t) { total = t; }, [&](size_t, size_t) { ++emits; });
  EXPECT_EQ(total, 0u);
  EXPECT_EQ(emits, 0);
}

}  // namespace
}  // namespace rayform
