#include "course_args.h"
#include "commands.h"
#include "rayform/pipeline/job_arguments.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <algorithm>
#include <set>

namespace rayform::cli {
namespace {

const std::set<std::string> course_flags = {"-input",   "-size",    "-output",       "-depth",   "-normals",
                                            "-dialect", "-bounces", "-shadows",      "-threads", "-quiet",
                                            "-albedo",  "-jitter",  "-filter",       "-spp",     "-stats",
                                            "-generic", "-sampler", "-target-error", "-max-spp"};

struct Args {
  const std::vector<std::string>& v;
  size_t i = 0;
  std::string take(const std::string& flag, const char* what) {
    if (i >= v.size()) throw UsageError(flag + " expects " + what);
    return v[i++];
  }
  int integer(const std::string& flag, const char* what) {
    std::string s = take(flag, what);
    char* end = nullptr;
    errno = 0;
    long x = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || errno == ERANGE || x < -1000000000 || x > 1000000000)
      throw UsageError(flag + " expects " + what + ", got '" + s + "'");
    return int(x);
  }
  float real(const std::string& flag, const char* what) {
    std::string s = take(flag, what);
    char* end = nullptr;
    double x = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || !std::isfinite(x))
      throw UsageError(flag + " expects " + what + ", got '" + s + "'");
    return float(x);
  }
};

}  // namespace

bool is_course_command_line(const std::vector<std::string>& args) {
  // Any single-dash word first (modern options are --long or -x) is the
  // course style, so that a misspelt course flag is named as unknown.
  if (args.empty()) return false;
  const std::string& a = args[0];
  return course_flags.count(a) > 0 || (a.size() > 2 && a[0] == '-' && a[1] != '-');
}

CourseCommand parse_course_command_line(const std::vector<std::string>& v) {
  CourseCommand command;
  RenderJob& job = command.job;
  bool has_input = false, has_output = false, has_size = false, has_bounces = false;
  Args a{v};
  while (a.i < v.size()) {
    std::string f = v[a.i++];
    if (f == "-input") {
      job.input = a.take(f, "a scene file");
      has_input = true;
    } else if (f == "-output") {
      job.output = a.take(f, "an image file");
      has_output = true;
    } else if (f == "-size") {
      job.render.width = a.integer(f, "a width and a height in pixels");
      job.render.height = a.integer(f, "a width and a height in pixels");
      has_size = true;
    } else if (f == "-depth") {
      DepthOutput d;
      d.min = a.real(f, "MIN MAX FILE");
      d.max = a.real(f, "MIN MAX FILE");
      d.file = a.take(f, "MIN MAX FILE");
      job.depth = d;
    } else if (f == "-normals") job.normals = a.take(f, "an image file");
    else if (f == "-albedo") job.albedo = a.take(f, "an image file");
    else if (f == "-dialect") {
      std::string d = a.take(f, "2012, 2019 or a5");
      job.load.dialect = dialect_from_string(d);
      if (!job.load.dialect) throw UsageError("-dialect expects 2012, 2019 or a5, got '" + d + "'");
    } else if (f == "-bounces") {
      job.render.bounces = a.integer(f, "a number of bounces");
      has_bounces = true;
    } else if (f == "-shadows") job.render.shadows = true;
    else if (f == "-jitter") job.render.grid.jitter = true;
    else if (f == "-filter") job.render.grid.gaussian = true;
    else if (f == "-sampler") {
      const std::string names = quoted_names(sampler_names(), "");
      std::string s = a.take(f, names.c_str());
      const std::optional<PixelSampler> sampler = sampler_from_name(s);
      if (!sampler) throw UsageError("-sampler expects " + names + ", got '" + s + "'");
      job.render.sampler = *sampler;
    } else if (f == "-target-error") {
      job.render.target_error = a.real(f, "a positive error per channel");
    } else if (f == "-max-spp") {
      job.render.max_spp = a.integer(f, "a number of samples per pixel");
    } else if (f == "-spp") {
      job.render.spp = a.integer(f, "a number of samples per pixel");
    } else if (f == "-threads") {
      job.render.threads = a.integer(f, "a number of threads");
    } else if (f == "-quiet" || f == "--quiet") command.reporting.quiet = true;
    else if (f == "-stats") command.reporting.stats = true;
    else if (f == "-generic") job.render.generic = true;
    else throw UsageError("unknown option '" + f + "'");
  }
  if (!has_input) throw UsageError("missing -input SCENE");
  if (!has_output) throw UsageError("missing -output IMAGE");
  if (!has_size) throw UsageError("missing -size WIDTH HEIGHT");
  job.default_size = false;  // -size is required
  job.default_bounces = !has_bounces;
  // The one check of the render parameters (render.h), under the course's flag names.
  if (std::string problem = render_options_problem(job.render); !problem.empty()) throw UsageError("-" + problem);
  return command;
}

}  // namespace rayform::cli
