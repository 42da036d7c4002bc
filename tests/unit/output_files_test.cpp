// OutputFiles (image/output_files.h): a set of files committed together, all
// or nothing. Image writes through it are covered by image_io_test.cpp; the
// scene writers' failures by tests/importers/scene_writer_test.cpp.
#include "rayform/image/output_files.h"
#include "rayform/base/error.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace rayform {
namespace {
namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(OutputFiles, CommitWritesEveryFileMainFirstAndLeavesNoTemporary) {
  auto dir = test::temp_dir("output_files_commit");
  const std::string main = (dir / "scene.gltf").string();
  {
    OutputFiles files(main);
    EXPECT_EQ(files.side_path("scene.bin"), (dir / "scene.bin").string());
    files.add(main, std::string("main"));
    files.add(files.side_path("scene.bin"), std::vector<uint8_t>{1, 2, 3});
    files.add(files.side_path("tex.png"), std::string("old"));
    files.add(files.side_path("tex.png"), std::string("new"));  // replaces
    const std::string written = files.temp_dir() + "/written";
    { std::ofstream(written, std::ios::binary) << "from a temporary"; }
    files.add_written(files.side_path("image.png"), written);
    EXPECT_TRUE(files.has(files.side_path("tex.png")));
    EXPECT_FALSE(files.has(files.side_path("other.png")));
    std::vector<std::string> done = files.commit();
    ASSERT_EQ(done.size(), 4u);
    EXPECT_EQ(done.front(), main);
  }
  EXPECT_EQ(test::files_in(dir), (std::vector<std::string>{"image.png", "scene.bin", "scene.gltf", "tex.png"}));
  EXPECT_EQ(read_text(dir / "scene.gltf"), "main");
  EXPECT_EQ(read_text(dir / "scene.bin"), std::string("\x01\x02\x03"));
  EXPECT_EQ(read_text(dir / "tex.png"), "new");
  EXPECT_EQ(read_text(dir / "image.png"), "from a temporary");
  fs::remove_all(dir);
}

TEST(OutputFiles, AFailedWriteLeavesNoFileAndNoTemporary) {
  auto dir = test::temp_dir("output_files_fail");
  const std::string main = (dir / "scene.gltf").string();
  {
    OutputFiles files(main);
    files.add(files.side_path("scene.bin"), std::string("bin"));
    files.add((dir / "missing" / "tex.png").string(), std::string("png"));  // its folder does not exist
    files.add(main, std::string("main"));
    const std::string written = files.temp_dir() + "/written";
    { std::ofstream(written, std::ios::binary) << "x"; }
    files.add_written(files.side_path("image.png"), written);
    EXPECT_THROW(files.commit(), Error);
  }
  EXPECT_TRUE(fs::is_empty(dir)) << test::files_in(dir).size() << " file(s) left";
  fs::remove_all(dir);
}

TEST(OutputFiles, WithoutCommitNothingIsLeft) {
  auto dir = test::temp_dir("output_files_abandon");
  {
    OutputFiles files((dir / "out.png").string());
    files.add(files.main(), std::string("never written"));
    const std::string written = (dir / ".out.png.partial").string();
    { std::ofstream(written, std::ios::binary) << "x"; }
    files.add_written(files.side_path("depth.png"), written);
    files.temp_dir();
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

// Side files in another folder (convert --out-dir): their paths, and how the
// main file names them, relative to its own folder with '/'.
TEST(OutputFiles, SideFolderPathsAndReferences) {
  const fs::path dir = test::temp_dir("output_files_side");
  const std::string out = (dir / "out" / "model.txt").string();
  EXPECT_EQ(OutputFiles(out).side_path("m.obj"), (dir / "out" / "m.obj").string());
  EXPECT_EQ(OutputFiles(out).side_reference("m.obj"), "m.obj");
  EXPECT_EQ(OutputFiles(out, (dir / "assets").string()).side_path("m.obj"), (dir / "assets" / "m.obj").string());
  EXPECT_EQ(OutputFiles(out, (dir / "assets").string()).side_reference("m.obj"), "../assets/m.obj");
  EXPECT_EQ(OutputFiles(out, (dir / "out" / "sub" / "deep").string()).side_reference("m.obj"), "sub/deep/m.obj");
  EXPECT_EQ(OutputFiles(out, (dir / "out").string()).side_reference("m.obj"), "m.obj");
  EXPECT_EQ(OutputFiles(out, (dir / "out" / "sub" / "..").string()).side_reference("m.obj"), "m.obj");
  // Relative paths, both from the working folder; the main file in it.
  EXPECT_EQ(OutputFiles("model.txt", "assets").side_reference("m.obj"), "assets/m.obj");
  EXPECT_EQ(OutputFiles("out/model.txt", "assets").side_reference("m.obj"), "../assets/m.obj");
  EXPECT_EQ(OutputFiles("model.txt", "assets").side_path("m.obj"), "assets/m.obj");
}

}  // namespace
}  // namespace rayform
