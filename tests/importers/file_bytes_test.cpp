// FileBytes: a regular file mapped, an empty one, a FIFO read to the end, a
// missing file named in the error.
#include "rayform/importers/file_bytes.h"
#include "rayform/base/error.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

namespace rayform {
namespace {

namespace fs = std::filesystem;

fs::path temporary_folder() {
  fs::path dir = fs::temp_directory_path() / ("rayform_file_bytes_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

TEST(FileBytes, RegularFileEmptyFileAndFifo) {
  const fs::path dir = temporary_folder();
  std::string text;
  for (int i = 0; i < 100000; ++i) text += "v " + std::to_string(i) + " 0 0\n";
  std::ofstream(dir / "a.obj", std::ios::binary) << text;
  std::ofstream(dir / "empty.obj", std::ios::binary).flush();
  {
    FileBytes bytes((dir / "a.obj").string(), "OBJ file");
    EXPECT_EQ(bytes.view(), text);
    FileBytes moved = std::move(bytes);
    EXPECT_EQ(moved.view(), text);
    EXPECT_TRUE(bytes.view().empty());
  }
  EXPECT_TRUE(FileBytes((dir / "empty.obj").string(), "OBJ file").view().empty());

  const fs::path fifo = dir / "pipe.obj";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << text; });
  const FileBytes piped(fifo.string(), "OBJ file");
  writer.join();
  EXPECT_EQ(piped.view(), text);

  try {
    FileBytes((dir / "missing.obj").string(), "OBJ file");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "missing.obj").string() + ": cannot open OBJ file");
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rayform
