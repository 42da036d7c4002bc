// Replays one regression file through its fuzz target's entry function in an
// ordinary build and checks the expected outcome within a time and memory
// bound (a watchdog thread: the process exits with a message when either is
// passed).
//   rayform_fuzz_replay TARGET FILE EXPECT MAX_SECONDS MAX_MB
// EXPECT: ok | error | clean (ok or error) | confined (ok or error, and
// nothing from outside the scene's folder used). A FILE ending in .repeat is
// expanded first: its first line is "repeat COUNT", then a head, a line
// "--body--", and a body repeated COUNT times (for inputs too big to commit).
#include "fuzz_targets.h"

#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>

namespace {
using namespace rayform::fuzz;

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << "cannot read " << path << "\n";
    std::exit(2);
  }
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string expand_repeat(const std::string& spec) {
  const size_t eol = spec.find('\n');
  const size_t count = std::stoul(spec.substr(7, eol - 7));
  const std::string marker = "--body--\n";
  const size_t body_at = spec.find(marker, eol);
  if (spec.rfind("repeat ", 0) != 0 || body_at == std::string::npos) {
    std::cerr << "bad .repeat file\n";
    std::exit(2);
  }
  const std::string head = spec.substr(eol + 1, body_at - eol - 1);
  const std::string body = spec.substr(body_at + marker.size());
  std::string out;
  out.reserve(head.size() + body.size() * count);
  out += head;
  for (size_t i = 0; i < count; ++i) out += body;
  return out;
}

size_t resident_mb() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * size_t(sysconf(_SC_PAGESIZE)) >> 20;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::cerr << "usage: rayform_fuzz_replay TARGET FILE ok|error|clean|confined MAX_SECONDS MAX_MB\n";
    return 2;
  }
  const FuzzTarget* target = find_fuzz_target(argv[1]);
  const std::string file = argv[2], expect = argv[3];
  const double max_seconds = std::atof(argv[4]);
  const size_t max_mb = std::strtoul(argv[5], nullptr, 10);
  if (!target || (expect != "ok" && expect != "error" && expect != "clean" && expect != "confined")) {
    std::cerr << "unknown target or expectation\n";
    return 2;
  }
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  std::string input = read_all(file);
  if (file.size() > 7 && file.substr(file.size() - 7) == ".repeat") input = expand_repeat(input);
  std::cerr << "replay: " << target->name << " " << file << " (" << input.size() << " bytes), expect " << expect
            << " within " << max_seconds << " s and " << max_mb << " MB\n";

  std::thread([max_seconds, max_mb] {
    const auto start = std::chrono::steady_clock::now();
    for (;;) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const size_t mb = resident_mb();
      if (s > max_seconds || mb > max_mb) {
        std::fprintf(stderr, "FAIL: still running after %.1f s with %zu MB resident (bounds: %.0f s, %zu MB)\n", s, mb,
                     max_seconds, max_mb);
        std::fflush(stderr);
        _exit(1);
      }
    }
  }).detach();

  const auto start = std::chrono::steady_clock::now();
  FuzzOutcome o = target->entry(reinterpret_cast<const uint8_t*>(input.data()), input.size(),
                                FuzzLimits{.max_input_bytes = input.size()});
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "outcome: " << (o.ok ? "ok" : "error") << (o.message.empty() ? "" : ": " + o.message) << "\n"
            << "time: " << s << " s, resident: " << resident_mb() << " MB\n";
  for (const std::string& u : o.outside) std::cerr << "used from outside the scene's folder: " << u << "\n";
  bool pass = true;
  if (expect == "ok") pass = o.ok;
  else if (expect == "error") pass = !o.ok;
  else if (expect == "confined") pass = o.outside.empty();
  std::cerr << (pass ? "PASS" : "FAIL: expected " + expect) << "\n";
  std::fflush(stderr);
  return pass ? 0 : 1;  // the workspace's destructor removes the temporary folder
}
