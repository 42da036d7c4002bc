// A conversion's argument checks and its dialect (pipeline/convert_checks.h),
// as `rayform convert` and rayform.convert use them.
#include "rayform/pipeline/convert_checks.h"
#include "rayform/importers/course_txt/course_writer.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;

TEST(ConvertChecks, OutputIsNotTheInputAndHasAKnownExtension) {
  const fs::path dir = test::temp_dir("convert_checks_output");
  const std::string in = (dir / "m.obj").string();
  { std::ofstream(in) << "v 0 0 0\n"; }
  EXPECT_EQ(convert_output_problem(in, (dir / "m.glb").string()), "");
  EXPECT_EQ(convert_output_problem(in, (dir / "new.txt").string()), "");  // need not exist
  EXPECT_EQ(convert_output_problem(in, in), in + ": the output is the input file; choose another name");
  // The same file by another spelling.
  const std::string other = (dir / "." / "m.obj").string();
  EXPECT_EQ(convert_output_problem(in, other), other + ": the output is the input file; choose another name");
  const std::string ply = (dir / "m.ply").string();
  EXPECT_EQ(convert_output_problem(in, ply),
            ply + ": unknown scene format '.ply': expected .txt (course), .obj, .gltf or .glb");
}

TEST(ConvertChecks, SideFolder) {
  const fs::path dir = test::temp_dir("convert_checks_side");
  fs::create_directories(dir / "assets");
  fs::create_directories(dir / "with space");
  { std::ofstream(dir / "afile") << "x"; }
  const std::string assets = (dir / "assets").string();
  EXPECT_EQ(side_folder_problem((dir / "m.obj").string(), assets, false, "--embed"), "");
  EXPECT_EQ(side_folder_problem((dir / "m.gltf").string(), assets, false, "--embed"), "");
  EXPECT_EQ(side_folder_problem((dir / "m.txt").string(), assets, false, "--embed"), "");
  const std::string missing = (dir / "nothere").string(), file = (dir / "afile").string();
  EXPECT_EQ(side_folder_problem((dir / "m.obj").string(), missing, false, "--embed"),
            "folder '" + missing + "' does not exist");
  EXPECT_EQ(side_folder_problem((dir / "m.obj").string(), file, false, "--embed"),
            "folder '" + file + "' does not exist");
  EXPECT_EQ(side_folder_problem((dir / "m.GLB").string(), assets, false, "--embed"),
            "a .glb holds everything in one file: there are no side files");
  EXPECT_EQ(side_folder_problem((dir / "m.gltf").string(), assets, true, "--embed"),
            "with --embed the .gltf holds everything: there are no side files");
  EXPECT_EQ(side_folder_problem((dir / "m.gltf").string(), assets, true, "embed=True"),
            "with embed=True the .gltf holds everything: there are no side files");
  const std::string spaced = (dir / "with space").string();
  EXPECT_EQ(side_folder_problem((dir / "m.txt").string(), spaced, false, "--embed"),
            course_side_folder_problem((dir / "m.txt").string(), spaced));
  EXPECT_EQ(side_folder_problem((dir / "m.txt").string(), spaced, false, "--embed")
                .rfind("a course .txt cannot name files in '", 0),
            0u);
  EXPECT_EQ(side_folder_problem((dir / "m.obj").string(), (dir / "with space").string(), false, "--embed"), "");
}

TEST(ConvertChecks, DialectAskedElseTheCourseInputs) {
  LoadedScene course;
  course.format = SceneFormat::course_txt;
  course.dialect = CourseDialect::a5;
  LoadedScene gltf;
  gltf.format = SceneFormat::gltf;
  gltf.dialect = CourseDialect::a5;  // not a course scene: not used
  EXPECT_EQ(convert_dialect(std::nullopt, course), CourseDialect::a5);
  EXPECT_EQ(convert_dialect(CourseDialect::v2019, course), CourseDialect::v2019);
  EXPECT_EQ(convert_dialect(std::nullopt, gltf), std::nullopt);
  EXPECT_EQ(convert_dialect(CourseDialect::v2012, gltf), CourseDialect::v2012);
}

}  // namespace
}  // namespace rayform
