// interrupt_cleanup.h: a process stopped by SIGINT/SIGTERM/SIGHUP removes the
// temporary files and folders it tracks, keeps what it untracked, and still
// ends by that signal. Each case runs in a forked child.
#include "rayform/image/interrupt_cleanup.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace rayform {
namespace {
namespace fs = std::filesystem;

// Runs `body` in a child process; returns its wait status.
template <class F>
int in_child(F&& body) {
  const pid_t pid = fork();
  if (pid == 0) {
    body();
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(InterruptCleanup, TrackedTemporariesAreRemovedOnEachSignal) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const fs::path dir = test::temp_dir("interrupt_" + std::to_string(sig));
    const fs::path tmp = dir / ".out.tmp.png", kept = dir / "kept.png", folder = dir / ".out.tmp.d",
                   inside = folder / "scene.gltf";
    const int status = in_child([&] {
      std::ofstream(tmp) << "partial";
      std::ofstream(kept) << "finished";
      fs::create_directories(folder);
      std::ofstream(inside) << "{";
      track_temporary(tmp.string());
      track_temporary(kept.string());
      untrack_temporary(kept.string());  // renamed into place: no longer a temporary
      track_temporary(folder.string(), /*folder*/ true);
      track_temporary(inside.string());
      std::raise(sig);
      _exit(3);  // not reached: the signal ends the process
    });
    EXPECT_TRUE(WIFSIGNALED(status)) << sig;
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_FALSE(fs::exists(tmp)) << sig;
    EXPECT_FALSE(fs::exists(inside)) << sig;
    EXPECT_FALSE(fs::exists(folder)) << sig;
    EXPECT_TRUE(fs::exists(kept)) << sig;
  }
}

// The interrupt message goes to stderr on a line of its own: after a newline
// when a (progress) line is open, without one otherwise.
TEST(InterruptCleanup, MessageEndsAnOpenLineFirst) {
  for (bool open : {true, false}) {
    const fs::path log = test::temp_dir("interrupt_message") / (open ? "open.log" : "closed.log");
    const int status = in_child([&] {
      FILE* f = std::freopen(log.c_str(), "w", stderr);
      if (!f) _exit(4);
      set_interrupt_message("rayform: interrupted");
      std::fputs("\rrendering  42%", stderr);
      std::fflush(stderr);
      set_interrupt_line_open(open);
      std::raise(SIGINT);
      _exit(3);
    });
    EXPECT_TRUE(WIFSIGNALED(status));
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, open ? "\rrendering  42%\nrayform: interrupted\n" : "\rrendering  42%rayform: interrupted\n");
  }
}

}  // namespace
}  // namespace rayform
