// Where tests find data: our own files under the source tree, and the
// third-party course data and tools in RAYFORM_SHARED (default ../shared).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace rayform::test {

inline std::filesystem::path source_dir() {
  const char* e = std::getenv("RAYFORM_SOURCE_DIR");
  return e && *e ? e : RAYFORM_SOURCE_DIR;
}

inline std::filesystem::path shared_dir() {
  const char* e = std::getenv("RAYFORM_SHARED");
  return e && *e ? e : RAYFORM_SHARED_DEFAULT;
}

// The command-line program of this build (RAYFORM_BIN overrides it, e.g.
// to run a test against another build).
inline std::string rayform_binary() {
  const char* e = std::getenv("RAYFORM_BIN");
  return e && *e ? e : RAYFORM_BIN_DEFAULT;
}

inline bool shared_available() { return std::filesystem::is_directory(shared_dir() / "course"); }

// A fresh empty folder for one test's outputs.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto p = std::filesystem::temp_directory_path() / ("rayform-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

// The names of the entries of `dir`, sorted.
inline std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace rayform::test

// Skips the test (with the reason) when ../shared is absent; in CI it must be there.
#define RAYFORM_REQUIRE_SHARED()                                                                                    \
  do {                                                                                                              \
    if (!::rayform::test::shared_available()) {                                                                     \
      if (std::getenv("CI")) FAIL() << "RAYFORM_SHARED not found at " << ::rayform::test::shared_dir();             \
      GTEST_SKIP() << "third-party data not found at " << ::rayform::test::shared_dir() << " (set RAYFORM_SHARED)"; \
    }                                                                                                               \
  } while (0)
