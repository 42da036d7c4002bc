// rayform: the command-line program. A thin layer over src/ and importers/:
// the course's own flags verbatim, and subcommands built with CLI11.
#include "course_args.h"
#include "render_job.h"
#include "scene/error.h"
#include "scene/scene_stats.h"
#include "scene_io.h"

#include <CLI/CLI.hpp>

#include <iostream>

#ifndef RAYFORM_VERSION
#define RAYFORM_VERSION "unknown"
#endif

namespace rayform::cli {
namespace {

const char* examples = R"(
Examples:
  Course command line (verbatim, single dash, any order):
    rayform -input scene01_plane.txt -size 200 200 -output 1.bmp -depth 8 12 d.bmp -normals n.bmp
    rayform -input scene06_bunny_1k.txt -size 200 200 -output b.png -dialect 2019
  Subcommands:
    rayform render scene.txt -o out.png --size 640x480 --depth 8:12:depth.png --normals normals.png
    rayform info scene.txt
)";

// "WxH" -> width, height.
void parse_size(const std::string& s, int* w, int* h) {
  size_t x = s.find_first_of("xX");
  try {
    size_t n1 = 0, n2 = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    *w = std::stoi(s.substr(0, x), &n1);
    *h = std::stoi(s.substr(x + 1), &n2);
    if (n1 != x || n2 != s.size() - x - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw UsageError("--size expects WIDTHxHEIGHT, e.g. 640x480, got '" + s + "'");
  }
  if (*w <= 0 || *h <= 0) throw UsageError("--size expects a positive width and height, got '" + s + "'");
}

// "MIN:MAX:FILE" -> depth output.
DepthOutput parse_depth(const std::string& s) {
  size_t a = s.find(':'), b = a == std::string::npos ? a : s.find(':', a + 1);
  if (b == std::string::npos) throw UsageError("--depth expects MIN:MAX:FILE, got '" + s + "'");
  DepthOutput d;
  try {
    size_t n1 = 0, n2 = 0;
    d.min = std::stof(s.substr(0, a), &n1);
    d.max = std::stof(s.substr(a + 1, b - a - 1), &n2);
    if (n1 != a || n2 != b - a - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw UsageError("--depth expects MIN:MAX:FILE with numbers MIN and MAX, got '" + s + "'");
  }
  d.file = s.substr(b + 1);
  return d;
}

int run(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (is_course_command_line(args)) {
    run_render_job(parse_course_command_line(args));
    return 0;
  }

  CLI::App app{"rayform " RAYFORM_VERSION ": a fast and accurate ray caster for course .txt, OBJ and glTF scenes"};
  app.set_version_flag("--version", "rayform " RAYFORM_VERSION);
  app.footer(examples);
  app.require_subcommand(1);

  RenderJob job;
  std::string size = "200x200", depth, dialect;
  CLI::App* render = app.add_subcommand("render", "Render a scene to an image");
  render->add_option("scene", job.input, "Scene file (.txt)")->required();
  render->add_option("-o,--output", job.output, "Colour image (png, bmp, tga, jpg, exr, ...)")->required();
  render->add_option("--size", size, "Image size WIDTHxHEIGHT")->capture_default_str();
  render->add_option("--depth", depth, "Depth image MIN:MAX:FILE");
  render->add_option("--normals", job.normals, "Normals image");
  render->add_option("--albedo", job.albedo, "Unlit surface colour image");
  render->add_option("--dialect", dialect, "Course dialect (default: detected)")->check(CLI::IsMember({"2012", "2019"}));
  render->add_option("--camera", job.camera, "Camera index")->check(CLI::NonNegativeNumber);
  render->add_option("--threads", job.threads, "Worker threads (0: all)")->check(CLI::NonNegativeNumber);
  render->add_flag("--generic", job.generic, "Force the general render path (no feature specialisation)");
  render->add_flag("-q,--quiet", job.quiet, "No progress on stderr");

  std::string info_scene, info_dialect;
  CLI::App* info = app.add_subcommand("info", "Print counts and bounds of a scene");
  info->add_option("scene", info_scene, "Scene file")->required();
  info->add_option("--dialect", info_dialect, "Course dialect (default: detected)")->check(CLI::IsMember({"2012", "2019"}));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  auto to_dialect = [](const std::string& d) -> std::optional<CourseDialect> {
    if (d == "2012") return CourseDialect::v2012;
    if (d == "2019") return CourseDialect::v2019;
    return std::nullopt;
  };
  if (render->parsed()) {
    parse_size(size, &job.width, &job.height);
    if (!depth.empty()) job.depth = parse_depth(depth);
    job.dialect = to_dialect(dialect);
    run_render_job(job);
  } else if (info->parsed()) {
    LoadedScene loaded = load_scene(info_scene, LoadOptions{to_dialect(info_dialect)});
    for (const std::string& w : loaded.warnings) std::cerr << "warning: " << w << "\n";
    std::cout << "scene:       " << info_scene << "\n";
    if (loaded.format == SceneFormat::course_txt)
      std::cout << "format:      course .txt, dialect " << (loaded.dialect == CourseDialect::v2019 ? "2019" : "2012") << "\n";
    std::cout << format_scene_stats(scene_stats(loaded.scene));
  }
  return 0;
}

}  // namespace
}  // namespace rayform::cli

int main(int argc, char** argv) {
  try {
    return rayform::cli::run(argc, argv);
  } catch (const rayform::cli::UsageError& e) {
    std::cerr << "rayform: " << e.what() << "\n(run 'rayform --help' for usage)\n";
    return 2;
  } catch (const rayform::Error& e) {
    std::cerr << "rayform: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "rayform: error: " << e.what() << "\n";
    return 1;
  }
}
