// checked_write.h: bytes written whole, or a failure with the system's reason
// (a full device is /dev/full here: every write fails with ENOSPC).
#include "rayform/image/checked_write.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace rayform {
namespace {
namespace fs = std::filesystem;

TEST(CheckedWrite, WritesEveryByte) {
  const fs::path dir = test::temp_dir("checked_write");
  std::string data(3'000'000, 'x');
  for (size_t i = 0; i < data.size(); i += 7) data[i] = char(i);
  std::string error;
  ASSERT_TRUE(write_file_checked((dir / "a.bin").string(), data.data(), data.size(), &error)) << error;
  std::ifstream in(dir / "a.bin", std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), data);
  EXPECT_TRUE(sync_file((dir / "a.bin").string(), &error)) << error;
}

TEST(CheckedWrite, AFullDeviceIsAnError) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  std::string error;
  const std::string data(100, 'x');
  EXPECT_FALSE(write_file_checked("/dev/full", data.data(), data.size(), &error));
  EXPECT_EQ(error, "write: No space left on device");
}

TEST(CheckedWrite, AMissingFolderIsAnError) {
  const fs::path dir = test::temp_dir("checked_write_missing");
  std::string error;
  EXPECT_FALSE(write_file_checked((dir / "no" / "a.bin").string(), "x", 1, &error));
  EXPECT_EQ(error, "open: No such file or directory");
  EXPECT_FALSE(sync_file((dir / "none.bin").string(), &error));
}

}  // namespace
}  // namespace rayform
