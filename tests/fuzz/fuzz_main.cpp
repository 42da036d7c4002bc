// libFuzzer driver of one target, named at compile time (RAYFORM_FUZZ_TARGET).
#include "fuzz_targets.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <memory>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // One core per fuzzer: oneTBB (BVH builds) runs in the calling thread.
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  if (!rayform::fuzz::find_fuzz_target(RAYFORM_FUZZ_TARGET)) {
    std::fprintf(stderr, "no fuzz target '%s'\n", RAYFORM_FUZZ_TARGET);
    std::abort();
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const rayform::fuzz::FuzzTarget* target = rayform::fuzz::find_fuzz_target(RAYFORM_FUZZ_TARGET);
  (void)target->entry(data, size, rayform::fuzz::FuzzLimits{});
  return 0;
}
