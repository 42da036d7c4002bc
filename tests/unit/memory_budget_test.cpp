// memory_budget.h: charges add up across textures, meshes and buffers, each
// copy of a charge shares it, the last one gives the bytes back, and passing
// the limit is one line naming what and how much; Limits::memory's name and
// default (limits.h).
#include "rayform/base/error.h"
#include "rayform/base/limits.h"
#include "rayform/base/memory_budget.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <unistd.h>

namespace rayform {
namespace {

TEST(MemoryBudget, ChargesAddUpAndTheLastCopyGivesThemBack) {
  MemoryBudget budget(1000);
  MemoryCharge a = budget.charge(600, "the first texture");
  EXPECT_EQ(budget.used(), 600u);
  {
    MemoryCharge copy = a;
    a = MemoryCharge();
    EXPECT_EQ(budget.used(), 600u);  // still held by the copy
    EXPECT_EQ(copy.bytes(), 600u);
  }
  EXPECT_EQ(budget.used(), 0u);
  MemoryCharge b = budget.charge(1000, "all of it");
  EXPECT_EQ(budget.used(), 1000u);
}

TEST(MemoryBudget, PassingTheLimitIsOneLineNamingWhatAndHowMuch) {
  MemoryBudget budget(1500000000);
  const MemoryCharge held = budget.charge(700000000, "the first texture");
  try {
    budget.charge(805306368, "big2.png: decoding the 16384x16384 texture");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "big2.png: decoding the 16384x16384 texture needs 805 MB, more than the 800 MB left of the memory "
                 "limit of 1.50 GB (raise it with --limit memory=N)");
  }
  EXPECT_EQ(budget.used(), 700000000u);  // the refused charge took nothing
  EXPECT_EQ(budget.problem(800000000, "x"), "");
  budget.set_limit(100);
  EXPECT_EQ(budget.problem(1, "x"),
            "x needs 1 bytes, more than the 0 bytes left of the memory limit of 100 bytes (raise it with --limit "
            "memory=N)");
}

TEST(MemoryBudget, ADefaultLimitGrowsWithTheFilesReadUpToHalfOfPhysicalMemory) {
  MemoryBudget grows(1000), fixed(1000);
  grows.set_limit(1000, true);
  EXPECT_EQ(grows.limit(), 1000u);
  grows.credit_input(10);
  fixed.credit_input(10);
  EXPECT_EQ(grows.limit(), 1000u + 10 * input_expansion);
  EXPECT_EQ(fixed.limit(), 1000u) << "a limit set on the command line does not grow";
  EXPECT_NO_THROW(grows.charge(1000 + 10 * input_expansion, "what the file made room for"));
  EXPECT_THROW(fixed.charge(1001, "more than the fixed limit"), Error);
  // However much is read, at most half of physical memory.
  const uint64_t physical = physical_memory_bytes();
  if (physical == 0) GTEST_SKIP() << "physical memory unknown";
  grows.credit_input(physical);
  EXPECT_EQ(grows.limit(), physical / 2);
}

TEST(MemoryBudget, LimitNamedMemoryDefaultsToASixteenthOfPhysicalMemory) {
  Limits l;
  const uint64_t physical = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGESIZE));
  EXPECT_EQ(l.memory, std::max<uint64_t>(physical / 16, uint64_t(256) << 20));
  EXPECT_EQ(set_limit(l, "memory", "2G"), "");
  EXPECT_EQ(l.memory, 2000000000u);
  // The job's budget starts at the default and grows with the files read
  // (by earlier tests too, when they run in this process).
  const uint64_t before = job_memory().limit();
  EXPECT_GE(before, Limits{}.memory);
  job_memory().credit_input(1);
  EXPECT_EQ(job_memory().limit(), std::min(before + input_expansion, std::max(Limits{}.memory, physical / 2)));
}

}  // namespace
}  // namespace rayform
