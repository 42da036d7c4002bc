#include "rayform/base/memory_budget.h"

#include "rayform/base/error.h"
#include "rayform/base/limits.h"

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace rayform {

struct MemoryBudget::State {
  std::atomic<uint64_t> used{0};
  std::atomic<uint64_t> limit{0};
  std::atomic<bool> grows{false};
  std::atomic<uint64_t> input{0};  // bytes credited
};

struct MemoryCharge::Held {
  std::shared_ptr<MemoryBudget::State> state;
  uint64_t bytes = 0;
  ~Held() { state->used.fetch_sub(bytes); }
};

uint64_t MemoryCharge::bytes() const { return held_ ? held_->bytes : 0; }

MemoryBudget::MemoryBudget(uint64_t limit) : state_(std::make_shared<State>()) { state_->limit.store(limit); }

uint64_t MemoryBudget::limit() const {
  const uint64_t base = state_->limit.load();
  if (!state_->grows.load()) return base;
  const uint64_t ceiling = std::max(base, physical_memory_bytes() / 2);
  const uint64_t input = state_->input.load();
  const uint64_t room = input > (ceiling - base) / input_expansion ? ceiling - base : input * input_expansion;
  return base + room;
}
void MemoryBudget::set_limit(uint64_t limit, bool grows_with_input) {
  state_->limit.store(limit);
  state_->grows.store(grows_with_input);
}
void MemoryBudget::credit_input(uint64_t bytes) { state_->input.fetch_add(bytes); }
uint64_t MemoryBudget::used() const { return state_->used.load(); }

namespace {
std::string over_message(uint64_t bytes, uint64_t used, uint64_t limit, const std::string& what) {
  const uint64_t left = used < limit ? limit - used : 0;
  return what + " needs " + memory_size_text(bytes) + ", more than the " +
         (used ? memory_size_text(left) + " left of the " : std::string()) + "memory limit of " +
         memory_size_text(limit) + " (raise it with --limit memory=N)";
}
}  // namespace

std::string MemoryBudget::problem(uint64_t bytes, const std::string& what) const {
  const uint64_t used = state_->used.load(), limit = this->limit();
  return used > limit || bytes > limit - used ? over_message(bytes, used, limit, what) : "";
}

MemoryCharge MemoryBudget::charge(uint64_t bytes, const std::string& what) {
  const uint64_t limit = this->limit();
  uint64_t used = state_->used.load();
  do {
    if (used > limit || bytes > limit - used) throw Error(over_message(bytes, used, limit, what));
  } while (!state_->used.compare_exchange_weak(used, used + bytes));
  MemoryCharge c;
  c.held_ = std::make_shared<MemoryCharge::Held>();
  c.held_->state = state_;
  c.held_->bytes = bytes;
  return c;
}

MemoryBudget& job_memory() {
  static MemoryBudget budget(Limits{}.memory);
  static const bool grows = (budget.set_limit(Limits{}.memory, true), true);
  (void)grows;
  return budget;
}

std::string memory_size_text(uint64_t bytes, SizeDigits digits) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  double v = double(bytes);
  int u = 0;
  while (v >= 1000 && u < 6) {
    v /= 1000;
    ++u;
  }
  char buf[32];
  const char* format = u == 0                              ? "%.0f %s"
                       : digits == SizeDigits::one_decimal ? "%.1f %s"
                       : v >= 100                          ? "%.0f %s"
                       : v >= 10                           ? "%.1f %s"
                                                           : "%.2f %s";
  std::snprintf(buf, sizeof buf, format, v, units[u]);
  return buf;
}

}  // namespace rayform
