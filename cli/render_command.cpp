#include "commands.h"
#include "course_args.h"
#include "output_names.h"
#include "rayform/pipeline/job_arguments.h"
#include "rayform/distributed/ranks.h"
#include "read_flags.h"
#include "render_batch.h"
#include "run_job.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

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

// "X,Y,Z" -> vector.
vec3 parse_vec3(const std::string& s, const char* option) {
  std::optional<std::vector<float>> v = numbers_from_text(s);
  if (!v || v->size() != 3) throw UsageError(std::string(option) + " expects three numbers X,Y,Z, got '" + s + "'");
  return vec3((*v)[0], (*v)[1], (*v)[2]);
}

// "AZ,EL" or "AZ,EL,DIST" -> orbit, checked by orbit_problem.
Orbit parse_orbit(const std::string& s) {
  std::optional<std::vector<float>> v = numbers_from_text(s);
  if (!v || v->size() < 2 || v->size() > 3)
    throw UsageError("--orbit expects two or three numbers AZ,EL[,DIST], got '" + s + "'");
  Orbit orbit{(*v)[0], (*v)[1], v->size() == 3 ? std::optional<float>((*v)[2]) : std::nullopt};
  if (std::string problem = orbit_problem(orbit); !problem.empty())
    throw UsageError("--orbit AZ,EL[,DIST]: " + problem + ", got '" + s + "'");
  return orbit;
}

// "R,G,B" with each 0..1, or "#RRGGBB" in hexadecimal (00..ff, as colour
// pickers show it) -> display values 0..1 (job_arguments.h).
vec3 parse_background(const std::string& s) {
  const std::optional<vec3> c = background_from_text(s);
  if (!c || !background_problem(*c).empty())
    throw UsageError("--background expects R,G,B with each 0..1 or #RRGGBB, got '" + s + "'");
  return *c;
}

struct RenderArgs {
  RenderJob job;
  Reporting reporting;
  std::vector<std::string> inputs;
  Turntable turntable;
  ReadFlags read;
  std::string size;  // empty: the default for the scene's format
  std::string depth, dialect, filter = "box", sampler = "stratified", color = "auto";
  std::string orbit, look_from, look_at, up, background, tonemap, env;
  float fov = 0.f, env_intensity = 1.f, env_rotate = 0.f;
  // Options whose presence matters (given, even with an empty value).
  CLI::Option *camera = nullptr, *orbit_option = nullptr, *fov_option = nullptr, *background_option = nullptr,
              *bounces = nullptr, *frames = nullptr, *tonemap_option = nullptr, *env_option = nullptr,
              *env_intensity_option = nullptr, *env_rotate_option = nullptr;
};

// The environment the flags ask for: --env FILE, studio or none, and its
// --env-intensity and --env-rotate (which alone change the default's).
std::optional<Environment> parse_environment(const RenderArgs& a) {
  const bool env = a.env_option->count() > 0, intensity = a.env_intensity_option->count() > 0,
             rotate = a.env_rotate_option->count() > 0;
  if (std::string expected = env_intensity_problem(a.env_intensity); intensity && !expected.empty())
    throw UsageError("--env-intensity expects " + expected + ", got '" + a.env_intensity_option->as<std::string>() +
                     "'");
  if (std::string expected = env_rotation_problem(a.env_rotate); rotate && !expected.empty())
    throw UsageError("--env-rotate expects " + expected + ", got '" + a.env_rotate_option->as<std::string>() + "'");
  return environment_from_arguments(env ? std::optional<std::string>(a.env) : std::nullopt,
                                    intensity ? std::optional<float>(a.env_intensity) : std::nullopt,
                                    rotate ? std::optional<float>(a.env_rotate) : std::nullopt);
}

// A job field's name as this command's flag: "look_from" -> "--look-from".
std::string flag_name(const std::string& field) {
  std::string flag = "--" + field;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

// Once the flags are parsed: the job completed from them, checked, and run
// (one picture over every rank under mpirun, or a batch).
void run_render_args(RenderArgs& a) {
  const CLI::Option *camera = a.camera, *orbit = a.orbit_option, *fov = a.fov_option, *background = a.background_option,
                    *bounces = a.bounces, *frames = a.frames;
  a.job.default_size = a.size.empty();
  a.job.default_bounces = bounces->count() == 0;
  a.job.default_tone_map = a.tonemap_option->count() == 0;
  if (!a.job.default_tone_map) a.job.render.tone_map = *tone_map_from_name(a.tonemap);  // checked by the option
  if (!a.job.default_size) parse_size(a.size, &a.job.render.width, &a.job.render.height);
  if (!a.depth.empty()) a.job.depth = parse_depth(a.depth);
  a.job.load.dialect = dialect_from_string(a.dialect);
  // The names are checked by the options (CLI::IsMember of the same lists).
  a.job.render.filter = *filter_from_name(a.filter);
  a.job.render.sampler = *sampler_from_name(a.sampler);
  a.job.color = *encoding_from_name(a.color);
  if (frames->count() > 0 && (camera->count() > 0 || !a.look_from.empty() || !a.look_at.empty()))
    throw UsageError(
        "--frames turns the --orbit camera: it cannot be combined with --camera, --look-from or "
        "--look-at");
  if (orbit->count() > 0) a.job.orbit = parse_orbit(a.orbit);  // given, even as ''
  if (!a.look_from.empty()) a.job.camera_adjust.look_from = parse_vec3(a.look_from, "--look-from");
  if (!a.look_at.empty()) a.job.camera_adjust.look_at = parse_vec3(a.look_at, "--look-at");
  if (std::string conflict = camera_conflict(a.job, camera->count() > 0, flag_name); !conflict.empty())
    throw UsageError(conflict);
  if (!a.up.empty()) a.job.camera_adjust.up = parse_vec3(a.up, "--up");
  if (background->count() > 0) a.job.background = parse_background(a.background);
  a.job.environment = parse_environment(a);
  if (fov->count() > 0) {
    if (std::string expected = fov_problem(a.fov); !expected.empty())
      throw UsageError("--fov expects " + expected + ", got '" + fov->as<std::string>() + "'");
    a.job.camera_adjust.fov_deg = a.fov;
  }
  apply_read_flags(a.read, a.job.load);
  a.reporting.quiet = quiet_requested(a.read);
  // The one check of the render parameters (render.h), under this command's flag names.
  if (std::string problem = render_options_problem(a.job.render); !problem.empty()) throw UsageError("--" + problem);
  if (a.inputs.size() > 1 || a.turntable.frames > 1) {
    // A batch: each render on one rank (all in this process without mpirun).
    const BatchJobs jobs = batch_jobs(a.job, a.inputs, a.turntable);
    if (int status = run_render_batch(jobs, a.turntable.frames > 1, a.reporting); status != 0)
      throw distributed::ReportedElsewhere("renders failed");
    return;
  }
  // One picture (over every rank under mpirun); a template names it as a batch would.
  a.job.input = a.inputs[0];
  a.job = batch_jobs(a.job, a.inputs, a.turntable)[0];
  run_job(a.job, a.reporting, true);
}

}  // namespace

std::optional<CourseDialect> dialect_from_string(const std::string& d) {
  if (d == "2012") return CourseDialect::v2012;
  if (d == "2019") return CourseDialect::v2019;
  if (d == "a5") return CourseDialect::a5;
  return std::nullopt;
}

void add_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  RenderJob& job = a->job;
  CLI::App* render = app.add_subcommand("render", "Render a scene to an image");
  render
      ->add_option("scene", a->inputs,
                   "Scene files (.txt, .obj, .gltf, .glb); several render as a batch, each output named by -o's "
                   "{stem}")
      ->required();
  render
      ->add_option("-o,--output", job.output,
                   "Colour image (png, bmp, tga, jpg, exr, ...); in a batch a template: {stem} is the input's name "
                   "without folder and extension, {frame} the --frames number (0000, 0001, ...)")
      ->required();
  auto size_text = [](SceneFormat f) {
    const RenderOptions d = default_render_options(f);
    return std::to_string(d.width) + "x" + std::to_string(d.height);
  };
  render->add_option("--size", a->size,
                     "Image size WIDTHxHEIGHT (default: " + size_text(SceneFormat::obj) + " for OBJ and glTF, " +
                         size_text(SceneFormat::course_txt) + " for course scenes)");
  render->add_option("--depth", a->depth, "Depth image MIN:MAX:FILE");
  render->add_option("--normals", job.normals, "Normals image");
  render->add_option("--albedo", job.albedo, "Unlit surface colour image");
  render->add_option("--dialect", a->dialect, "Course dialect: 2012, 2019 or a5 (default: detected)")
      ->check(CLI::IsMember({"2012", "2019", "a5"}));
  CLI::Option* camera = render->add_option("--camera", job.render.camera, "Camera index");
  render->add_option("--threads", job.render.threads, "Worker threads (0: all)");
  render->add_flag("--shadows", job.render.shadows, "Shadow rays to every light");
  CLI::Option* bounces = render->add_option(
      "--bounces", job.render.bounces,
      "Reflection/refraction depth (default: " + std::to_string(course_a5_default_bounces) +
          " for course a5 scenes; for files with physically based (metallic-roughness) materials " +
          std::to_string(pbr_default_bounces) + ", or " + std::to_string(transmission_default_bounces) +
          " when one of them uses transmission; else 0); at most " + std::to_string(max_bounces) +
          ", a larger N renders as " + std::to_string(max_bounces) + " with a note");
  render->add_option("--spp", job.render.spp, "Samples per pixel (anti-aliasing)");
  render->add_option("--filter", a->filter, "Pixel filter for --spp > 1")
      ->check(CLI::IsMember(filter_names()))
      ->capture_default_str();
  render
      ->add_option("--sampler", a->sampler,
                   "Sub-pixel positions: stratified (jittered strata) or random (independent uniform, also at 1 spp)")
      ->check(CLI::IsMember(sampler_names()))
      ->capture_default_str();
  render->add_option("--target-error", job.render.target_error,
                     "Adaptive sampling: rounds of stratified samples per pixel (" +
                         std::to_string(adaptive_first_round_samples) + ", then up to " +
                         std::to_string(adaptive_round_samples) + ", then " + std::to_string(adaptive_round_samples) +
                         " more) until the standard error of its mean is below E in every channel "
                         "(in the output encoding), or --max-spp (replaces --spp)");
  render->add_option("--max-spp", job.render.max_spp, "Most samples per pixel of --target-error")
      ->capture_default_str();
  render
      ->add_option("--color", a->color,
                   "Colour encoding: auto (course scenes raw; OBJ and glTF sRGB in 8-bit files, linear and unclamped "
                   "in float files: exr, hdr, tif), raw (as computed), srgb (encoded, clamped to 0..1)")
      ->check(CLI::IsMember(encoding_names()))
      ->capture_default_str();
  render
      ->add_option("--exposure", job.render.exposure_ev,
                   "Exposure in stops: colour (and the background) scaled by 2^EV before the tone map, in every "
                   "colour output, float files too (default 0)")
      ->type_name("EV");
  a->tonemap_option =
      render
          ->add_option("--tonemap", a->tonemap,
                       "Tone map of 8-bit colour outputs (float files stay linear): khr-neutral (Khronos PBR Neutral: "
                       "colours kept, highlights compressed), aces (Hill's ACES filmic fit) or none (clamped) "
                       "(default: khr-neutral for files with physically based materials, else none)")
          ->check(CLI::IsMember(tone_map_names()));
  render->add_flag("--frame", job.frame,
                   "Ignore the file's cameras: the default camera, framing the scene's bounds from the +z side (from "
                   "above at 45 degrees when they are flat in the xz plane, from the +x side when flat in yz)");
  CLI::Option* orbit =
      render
          ->add_option("--orbit", a->orbit,
                       "Ignore the file's cameras: look at the bounds' centre, up +y, from azimuth AZ (degrees about "
                       "+y, counter-clockwise seen from above; 0: the +z side, 90: the +x side), elevation EL "
                       "(degrees above the horizontal plane, -90 < EL < 90) and distance DIST (default: the model "
                       "fits)")
          ->type_name("AZ,EL[,DIST]");
  CLI::Option* frames =
      render
          ->add_option("--frames", a->turntable.frames,
                       "Turntable: N pictures around the model, the --orbit camera (default 0,0) turned about +y by "
                       "--turntable/N degrees each; -o names them with {frame}")
          ->check(CLI::PositiveNumber);
  render
      ->add_option("--turntable", a->turntable.sweep_deg,
                   "Degrees the --frames pictures span (default 360: a loop whose last frame is one step short "
                   "of the first)")
      ->needs(frames);
  render
      ->add_option("--look-from", a->look_from,
                   "Camera position (without --look-at: looking at the centre of the scene's bounds)")
      ->type_name("X,Y,Z");
  render->add_option("--look-at", a->look_at, "Point the camera looks at")->type_name("X,Y,Z");
  render
      ->add_option("--up", a->up,
                   "Camera up vector (default: the camera's; +y, or -z/+z looking straight down/up, when that is "
                   "parallel to a new view direction)")
      ->type_name("X,Y,Z");
  CLI::Option* fov = render->add_option("--fov", a->fov, "Camera opening angle in degrees (0 < DEG < 180)");
  CLI::Option* background =
      render
          ->add_option(
              "--background", a->background,
              "Background colour as a colour picker gives it: R,G,B with each 0..1 (0.5,0.5,1) or #RRGGBB with "
              "0-255 values in hexadecimal (#8080ff); the 8-bit output shows exactly these values")
          ->type_name("R,G,B|#RRGGBB");
  a->env_option =
      render
          ->add_option("--env", a->env,
                       "Environment light for physically based materials, also seen where rays leave the scene: an "
                       "equirectangular HDR picture (.exr, .hdr, .pfm; linear, +y up, +x at its centre), 'studio' "
                       "(built in) or 'none' (default: studio for files with such materials and no light of their "
                       "own, which then get no light rig; else none)")
          ->type_name("FILE|studio|none");
  a->env_intensity_option =
      render->add_option("--env-intensity", a->env_intensity, "Scale of the environment's radiance (default 1)")
          ->type_name("K");
  a->env_rotate_option =
      render
          ->add_option("--env-rotate", a->env_rotate,
                       "Turn the environment about +y by DEG degrees (counter-clockwise seen from above)")
          ->type_name("DEG");
  render->add_flag("--transparent", job.transparent,
                   "Background as alpha 0 (surfaces 1, edges between) in the colour output: .png/.tga with straight "
                   "alpha, .exr/.tif premultiplied");
  render->add_flag("--flat", job.load.flat_normals, "OBJ: faceted normals where the file has none (default smooth)");
  render->add_option("--gltf-scene", job.load.gltf_scene, "glTF: index of the scene to render (default: the file's)");
  add_read_flags(*render, a->read);
  render->add_flag("--generic", job.render.generic, "Force the general render path (no feature specialisation)");
  render->add_flag("--stats", a->reporting.stats,
                   "Print load/prepare/render/write times and accelerator memory on stderr");
  a->camera = camera;
  a->orbit_option = orbit;
  a->fov_option = fov;
  a->background_option = background;
  a->bounces = bounces;
  a->frames = frames;
  render->callback([a] { run_render_args(*a); });
}

}  // namespace rayform::cli
