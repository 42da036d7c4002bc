#include "render_job.h"

#include "course_args.h"
#include "messages.h"

#include "progress.h"
#include "rayform/render/aov_images.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render_memory.h"
#include "rayform/image/color.h"
#include "rayform/image/output_files.h"
#include "rayform/image/quantize.h"
#include "rayform/render/render.h"
#include "rayform/scene/error.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/scene/scene_stats.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>
#include <filesystem>
#include <iostream>

namespace rayform::cli {
namespace fs = std::filesystem;
namespace {

// Chooses the camera rendered and applies --look-from/--look-at/--up/--fov
// to it. --orbit and --frame replace the file's cameras with one placed by
// orbit_camera (scene/scene_defaults.h); an asset file without a camera gets
// the default camera. --look-from alone aims at the centre of the scene's
// bounds; an up vector the new direction makes useless is replaced
// (up_not_parallel), an explicit --up parallel to it is an error.
void set_up_camera(const RenderJob& job, Scene& scene, bool asset) {
  auto bounds = [&] { return scene_stats(scene, job.limits.instances).bounds; };
  if (job.orbit) {
    scene.cameras = {orbit_camera(bounds(), *job.orbit, job.fov.value_or(default_camera_fov_deg))};
  } else if (job.frame) {
    scene.cameras.clear();
    add_default_camera(scene);
  } else if (asset && add_default_camera(scene)) {
    note(job.input + " has no camera: added one framing the scene's bounds");
  }
  if (!(job.look_from || job.look_at || job.up || job.fov)) return;
  const int camera = job.render.camera;
  if (camera < 0 || camera >= int(scene.cameras.size()))
    throw UsageError("--camera " + std::to_string(camera) + ": the scene has no such camera to adjust");
  Camera& c = scene.cameras[camera];
  if (job.look_from || job.look_at) {
    const vec3 from = job.look_from.value_or(c.center);
    const vec3 target = job.look_at ? *job.look_at : framing_target(bounds());
    if (target == from)
      throw UsageError(job.look_at ? "--look-at must differ from --look-from"
                                   : "--look-from is the centre of the scene's bounds, where the camera would look: "
                                     "give --look-at");
    c.center = from;
    c.direction = target - from;
    if (!job.up) c.up = up_not_parallel(c.up, c.direction);
  }
  if (job.up) c.up = *job.up;
  if (glm::length(glm::cross(c.direction, c.up)) == 0.f)
    throw UsageError("--up must not be parallel to the view direction");
  if (job.fov) c.fov_deg = *job.fov;
}

void encode_srgb(Image& img) {
  for (float& v : img.pixels) v = linear_to_srgb(std::clamp(v, 0.f, 1.f));
}

// The linear value of the display value v (0..1) for a render encoded as
// sRGB: srgb_to_linear(v), moved by the few float steps needed for its 8-bit
// sRGB encoding to be v's own 8-bit value, quantize_unit(v) (the round trip
// in float can land one step below).
float background_from_display(float v) {
  const uint8_t wanted = quantize_unit(v);
  float linear = srgb_to_linear(v);
  for (int step = 0; step < 64 && quantize_srgb_direct(linear) != wanted; ++step)
    linear = std::nextafter(linear, quantize_srgb_direct(linear) < wanted ? 2.f : -1.f);
  return linear;
}

}  // namespace

void check_output_folder(const std::string& path, const std::string& what) {
  fs::path dir = fs::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw UsageError(path + ": cannot write " + what + ": folder '" + dir.string() + "' does not exist");
}

void check_output_path(const std::string& path, const char* what) {
  if (path.empty()) throw UsageError(std::string(what) + ": no file name given");
  if (!is_writable_image_path(path))
    throw UsageError(path + ": cannot write " + what + " images of type '" + fs::path(path).extension().string() +
                     "' (use .png, .bmp, .tga, .jpg, .exr, .hdr or .tif)");
  check_output_folder(path, what);
}

void check_render_job_memory(const RenderJob& job) {
  RenderOptions outputs = job.render;
  outputs.depth = job.depth.has_value();
  outputs.normals = !job.normals.empty();
  outputs.albedo = !job.albedo.empty();
  if (job.transparent) outputs.alpha = AlphaMode::straight;  // either mode: the same buffers
  if (is_8bit_image_path(job.output)) outputs.color_format = ColorFormat::unit8;
  if (std::string problem = render_memory_problem(outputs, available_memory_bytes()); !problem.empty())
    throw Error(job.output + ": " + problem);
}

void run_render_job(const RenderJob& job) {
  set_quiet(job.quiet);
  check_output_path(job.output, "colour");
  if (job.depth) {
    check_output_path(job.depth->file, "depth");
    if (!(job.depth->max > job.depth->min))
      throw UsageError("depth range must have MAX > MIN, got " + std::to_string(job.depth->min) + " .. " +
                       std::to_string(job.depth->max));
  }
  if (!job.normals.empty()) check_output_path(job.normals, "normals");
  if (!job.albedo.empty()) check_output_path(job.albedo, "albedo");
  if (job.transparent && !is_alpha_image_path(job.output))
    throw UsageError("--transparent: " + job.output + " cannot hold alpha (write .png, .tga, .exr or .tif)");

  if (std::string problem = render_options_problem(job.render); !problem.empty()) throw UsageError(problem);
  check_render_job_memory(job);  // before the scene is read (render() checks it again)
  using clock = std::chrono::steady_clock;
  auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  // --threads bounds the whole job (the BVH build too), not only the render.
  std::optional<tbb::global_control> thread_limit;
  if (job.render.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(job.render.threads));
  // oneTBB starts its worker threads on a process's first parallel loop (0.5 to
  // 1 ms here): start them on a helper thread while the scene loads.
  std::jthread start_workers;
  if (job.render.threads != 1) start_workers = std::jthread([] { tbb::parallel_for(0, 2, [](int) {}); });
  auto t_load = clock::now();
  LoadOptions lo;
  lo.dialect = job.dialect;
  lo.flat_normals = job.flat_normals;
  lo.gltf_scene = job.gltf_scene;
  lo.limits = job.limits;
  lo.access = job.access;
  LoadedScene loaded = load_scene(job.input, lo);
  for (const std::string& w : loaded.warnings) warn(w);
  // Asset files often carry neither camera nor light (a course scene always has
  // a camera, and without lights its ambient light is white).
  // The head-light follows the camera rendered, as the overrides left it.
  const bool asset = loaded.format != SceneFormat::course_txt;
  set_up_camera(job, loaded.scene, asset);
  if (asset && add_headlight(loaded.scene, job.render.camera))
    note(job.input + " has no light: added a head-light along the camera");
  // Whether the scene's colours are linear and encoded as sRGB for display.
  const bool srgb = job.color == RenderJob::ColorEncoding::srgb ||
                    (job.color == RenderJob::ColorEncoding::automatic && loaded.format != SceneFormat::course_txt);
  if (job.background) {
    vec3& b = loaded.scene.background.color;
    b = *job.background;
    if (srgb)
      for (int k = 0; k < 3; ++k) b[k] = background_from_display(b[k]);
  }
  double load_s = seconds_since(t_load);
  auto t_prepare = clock::now();
  PrepareOptions po;
  po.limits = job.limits;
  PreparedScene prepared = prepare_scene(loaded.scene, po);
  double prepare_s = seconds_since(t_prepare);

  bool course_2019 = loaded.format == SceneFormat::course_txt && loaded.dialect == CourseDialect::v2019;
  bool course_2012 = loaded.format == SceneFormat::course_txt && loaded.dialect == CourseDialect::v2012;
  RenderOptions ro = job.render;
  ro.depth = job.depth.has_value();
  ro.normals = !job.normals.empty();
  ro.albedo = !job.albedo.empty();
  if (job.transparent) ro.alpha = is_8bit_image_path(job.output) ? AlphaMode::straight : AlphaMode::premultiplied;
  // 8-bit files get 8-bit values straight from the render loop.
  if (is_8bit_image_path(job.output) && (job.albedo.empty() || is_8bit_image_path(job.albedo)))
    ro.color_format = srgb ? ColorFormat::srgb8 : ColorFormat::unit8;
  Progress progress("rendering", job.quiet);
  if (progress.enabled()) ro.progress = [&](float f) { progress.update(f); };
  auto t_render = clock::now();
  RenderResult result = render(prepared, ro);
  double render_s = seconds_since(t_render);
  progress.finish();
  auto t_write = clock::now();
  if (srgb && ro.color_format == ColorFormat::linear_float) {
    encode_srgb(result.color);
    if (!job.albedo.empty()) encode_srgb(result.albedo);
  }
  // All outputs appear together or not at all.
  OutputFiles files(job.output);
  std::vector<std::pair<std::string, Image>> outputs;
  if (ro.color_format == ColorFormat::linear_float)
    outputs.emplace_back(job.output, job.transparent ? color_with_alpha(result) : std::move(result.color));
  else
    files.add_written(job.output,
                      write_image8_temporary(job.output, job.transparent ? color8_with_alpha(result) : result.color8));
  if (job.depth)
    outputs.emplace_back(job.depth->file, depth_image(result, job.depth->min, job.depth->max,
                                                      course_2019 ? DepthStyle::near_black : DepthStyle::near_white));
  if (!job.normals.empty())
    outputs.emplace_back(job.normals, normals_image(result, course_2012 ? NormalStyle::absolute : NormalStyle::offset));
  if (!job.albedo.empty()) {
    if (ro.color_format == ColorFormat::linear_float) outputs.emplace_back(job.albedo, std::move(result.albedo));
    else files.add_written(job.albedo, write_image8_temporary(job.albedo, result.albedo8));
  }
  for (const auto& [path, image] : outputs) files.add_written(path, write_image_temporary(path, image));
  files.commit();
  if (job.stats)
    std::cerr << "stats: load " << load_s << " s, prepare " << prepare_s << " s, render " << render_s << " s, write "
              << seconds_since(t_write) << " s (" << render_path_name(prepared, ro) << " path, " << ro.width << "x"
              << ro.height << ", " << ro.spp << " spp), accel " << prepared.memory_bytes() / 1024 << " KiB\n";
}

}  // namespace rayform::cli
