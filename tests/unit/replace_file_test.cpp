// replace_file (src/image/replace_file.h): the new content ends up at the
// target whether or not a file was there, nothing is left at the temporary
// name, and targets that are not regular files behave as with rename.
#include "rayform/image/replace_file.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace rayform {
namespace {
namespace fs = std::filesystem;

void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }
std::string get(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(ReplaceFile, ReplacesAnExistingFileOrCreatesAMissingOne) {
  for (const bool existing : {true, false}) {
    const fs::path dir = test::temp_dir(existing ? "replace_existing" : "replace_missing");
    if (existing) put(dir / "out.bmp", "old content, longer than the new");
    put(dir / ".out.tmp", "new");
    std::error_code ec;
    replace_file((dir / ".out.tmp").string(), (dir / "out.bmp").string(), ec);
    EXPECT_FALSE(ec) << ec.message();
    EXPECT_EQ(get(dir / "out.bmp"), "new") << existing;
    EXPECT_FALSE(fs::exists(dir / ".out.tmp")) << existing;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << existing;
  }
}

TEST(ReplaceFile, AFolderInTheWayIsAnErrorAndKeepsBoth) {
  const fs::path dir = test::temp_dir("replace_folder");
  fs::create_directories(dir / "out.bmp");
  put(dir / "out.bmp" / "inside", "x");
  put(dir / ".out.tmp", "new");
  std::error_code ec;
  replace_file((dir / ".out.tmp").string(), (dir / "out.bmp").string(), ec);
  EXPECT_TRUE(ec);
  EXPECT_TRUE(fs::is_directory(dir / "out.bmp"));
  EXPECT_EQ(get(dir / "out.bmp" / "inside"), "x");
  EXPECT_EQ(get(dir / ".out.tmp"), "new");
}

TEST(ReplaceFile, ASymlinkIsReplacedNotFollowed) {
  const fs::path dir = test::temp_dir("replace_symlink");
  put(dir / "elsewhere.bmp", "untouched");
  fs::create_symlink(dir / "elsewhere.bmp", dir / "out.bmp");
  put(dir / ".out.tmp", "new");
  std::error_code ec;
  replace_file((dir / ".out.tmp").string(), (dir / "out.bmp").string(), ec);
  EXPECT_FALSE(ec) << ec.message();
  EXPECT_FALSE(fs::is_symlink(dir / "out.bmp"));
  EXPECT_EQ(get(dir / "out.bmp"), "new");
  EXPECT_EQ(get(dir / "elsewhere.bmp"), "untouched");
}

}  // namespace
}  // namespace rayform
