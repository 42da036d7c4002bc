// A WorkShare (rayform/base/work_share.h) among threads of one process,
// for tests of work shared among parts: the exchange is an all-gather over a
// barrier and a slot per part.
#pragma once

#include "rayform/base/work_share.h"

#include <barrier>
#include <cstddef>
#include <utility>
#include <vector>

namespace rayform::test {

// An all-gather among threads: each part leaves its bytes in its slot, waits
// for all, copies every slot, and waits again before the slots are reused.
class ThreadExchange {
 public:
  explicit ThreadExchange(int parts) : parts_(parts), barrier_(parts), slots_(parts), calls_(parts, 0), sent_(parts) {}

  // Part fail_part sends one 0 byte instead of its bytes (what a part of a
  // shared mesh build that failed sends: build_mesh_accel).
  WorkShare share(int part, int fail_part = -1) {
    WorkShare s;
    s.part = part;
    s.parts = parts_;
    s.exchange = [this, part, fail_part](std::vector<std::byte> mine) {
      if (part == fail_part) mine.assign(1, std::byte{0});
      ++calls_[part];
      sent_[part] = mine.size();
      slots_[part] = std::move(mine);
      barrier_.arrive_and_wait();
      std::vector<std::vector<std::byte>> all = slots_;
      barrier_.arrive_and_wait();
      return all;
    };
    return s;
  }
  int calls(int part) const { return calls_[part]; }
  size_t sent(int part) const { return sent_[part]; }

 private:
  int parts_;
  std::barrier<> barrier_;
  std::vector<std::vector<std::byte>> slots_;
  std::vector<int> calls_;
  std::vector<size_t> sent_;
};

}  // namespace rayform::test
