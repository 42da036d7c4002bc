#include "rayform/image/interrupt_cleanup.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>
#include <unistd.h>

namespace rayform {
namespace {

// Fixed slots the handler can read without allocating or locking: `state` is
// 0 (free), 1 (a file), 2 (a folder) or 3 (being written by a thread).
struct Slot {
  std::atomic<int> state{0};
  char path[4096];
};
std::array<Slot, 64> slots;
std::mutex slots_mutex;  // serialises track/untrack (never taken by the handler)

constexpr int signals[] = {SIGINT, SIGTERM, SIGHUP};

// The interrupt message, written by the handler with write(2) (async-signal-safe).
char message[257];
std::atomic<size_t> message_length{0};
std::atomic<bool> line_open{false};

void on_signal(int sig) {
  if (const size_t n = message_length.load(std::memory_order_acquire); n > 0) {
    if (line_open.load()) (void)!::write(STDERR_FILENO, "\n", 1);
    (void)!::write(STDERR_FILENO, message, n);
  }
  for (int pass = 1; pass <= 2; ++pass)  // files first, then their folders
    for (Slot& s : slots)
      if (s.state.load(std::memory_order_acquire) == pass) pass == 1 ? ::unlink(s.path) : ::rmdir(s.path);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : signals) {
      struct sigaction old {};
      sigaction(sig, nullptr, &old);
      if (old.sa_handler == SIG_IGN) continue;  // e.g. nohup: keep ignoring
      struct sigaction sa {};
      sa.sa_handler = &on_signal;
      sigemptyset(&sa.sa_mask);
      sigaction(sig, &sa, nullptr);
    }
  });
}

}  // namespace

void track_temporary(const std::string& path, bool folder) {
  if (path.size() >= sizeof(Slot::path)) return;
  install_handlers();
  std::lock_guard lock(slots_mutex);
  for (Slot& s : slots)
    if (s.state.load() == 0) {
      s.state.store(3);
      std::memcpy(s.path, path.c_str(), path.size() + 1);
      s.state.store(folder ? 2 : 1, std::memory_order_release);
      return;
    }
}

void set_interrupt_message(const std::string& text) {
  install_handlers();
  const size_t n = std::min(text.size(), sizeof message - 2);
  message_length.store(0, std::memory_order_release);
  std::memcpy(message, text.data(), n);
  message[n] = '\n';
  message_length.store(n + 1, std::memory_order_release);
}

void set_interrupt_line_open(bool open) { line_open.store(open); }

void untrack_temporary(const std::string& path) {
  std::lock_guard lock(slots_mutex);
  for (Slot& s : slots) {
    const int state = s.state.load();
    if ((state == 1 || state == 2) && path == s.path) s.state.store(0, std::memory_order_release);
  }
}

}  // namespace rayform
