#include "rayform/base/thread_limit.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <thread>

namespace rayform {

std::shared_ptr<void> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(threads));
}

std::shared_ptr<void> start_worker_threads() {
  return std::make_shared<std::jthread>([] { tbb::parallel_for(0, 2, [](int) {}); });
}

}  // namespace rayform
