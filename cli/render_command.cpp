#include "commands.h"
#include "course_args.h"
#include "render_job.h"

#include <memory>

namespace rayform::cli {
namespace {

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

struct RenderArgs {
  RenderJob job;
  std::string size = "200x200", depth, dialect;
};

}  // namespace

std::optional<CourseDialect> dialect_from_string(const std::string& d) {
  if (d == "2012") return CourseDialect::v2012;
  if (d == "2019") return CourseDialect::v2019;
  return std::nullopt;
}

void add_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  RenderJob& job = a->job;
  CLI::App* render = app.add_subcommand("render", "Render a scene to an image");
  render->add_option("scene", job.input, "Scene file (.txt)")->required();
  render->add_option("-o,--output", job.output, "Colour image (png, bmp, tga, jpg, exr, ...)")->required();
  render->add_option("--size", a->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  render->add_option("--depth", a->depth, "Depth image MIN:MAX:FILE");
  render->add_option("--normals", job.normals, "Normals image");
  render->add_option("--albedo", job.albedo, "Unlit surface colour image");
  render->add_option("--dialect", a->dialect, "Course dialect (default: detected)")->check(CLI::IsMember({"2012", "2019"}));
  render->add_option("--camera", job.camera, "Camera index")->check(CLI::NonNegativeNumber);
  render->add_option("--threads", job.threads, "Worker threads (0: all)")->check(CLI::NonNegativeNumber);
  render->add_flag("--generic", job.generic, "Force the general render path (no feature specialisation)");
  render->add_flag("-q,--quiet", job.quiet, "No progress on stderr");
  render->callback([a] {
    parse_size(a->size, &a->job.width, &a->job.height);
    if (!a->depth.empty()) a->job.depth = parse_depth(a->depth);
    a->job.dialect = dialect_from_string(a->dialect);
    run_render_job(a->job);
  });
}

}  // namespace rayform::cli
