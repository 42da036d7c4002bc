#include "render_job.h"

#include "course_args.h"
#include "rayform/distributed/distributed_frame.h"
#include "messages.h"
#include "rayform/distributed/rank_work_share.h"
#include "rayform/distributed/ranks.h"

#include "progress.h"
#include "rayform/render/aov_images.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render_memory.h"
#include "rayform/image/color.h"
#include "rayform/image/output_files.h"
#include "rayform/image/quantize.h"
#include "rayform/render/render.h"
#include "rayform/base/error.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/scene/scene_stats.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>
#include <filesystem>
#include <iostream>

namespace rayform::cli {
namespace fs = std::filesystem;
namespace {

// The sampling of a render for --stats: "4 spp", or the samples taken per
// pixel on average with adaptive sampling and the 3x3 grid.
std::string samples_text(const RenderResult& r, const RenderOptions& o) {
  if (!o.grid.on() && !o.target_error) return std::to_string(o.spp) + " spp";
  char text[96];
  const double pixels = double(r.width) * double(r.height);
  std::snprintf(text, sizeof text, "%llu samples, %.2f per pixel%s", static_cast<unsigned long long>(r.samples),
                double(r.samples) / pixels, o.grid.on() ? ", 3x3 grid" : ", adaptive");
  return text;
}

// Applies --look-from/--look-at/--up/--fov to the camera rendered, once the
// file's camera, the default camera or the --frame/--orbit one is in place
// (load_ready_scene). --look-from alone aims at the centre of the scene's
// bounds; an up vector the new direction makes useless is replaced
// (up_not_parallel), an explicit --up parallel to it is an error.
void adjust_camera(const RenderJob& job, Scene& scene) {
  const int camera = job.render.camera;
  if (camera < 0 || camera >= int(scene.cameras.size()))
    throw UsageError("--camera " + std::to_string(camera) + ": the scene has no such camera to adjust");
  Camera& c = scene.cameras[camera];
  if (job.look_from || job.look_at) {
    const vec3 from = job.look_from.value_or(c.center);
    const vec3 target = job.look_at ? *job.look_at : framing_target(scene_stats(scene, job.limits.instances).bounds);
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

// What load_ready_scene is asked for: the reader's options, and the camera
// the command line places (--frame and --orbit replace the file's cameras
// with orbit_camera's; the others then adjust the camera rendered).
ReadyOptions ready_options(const RenderJob& job) {
  ReadyOptions r;
  r.load.dialect = job.dialect;
  r.load.flat_normals = job.flat_normals;
  r.load.gltf_scene = job.gltf_scene;
  r.load.limits = job.limits;
  r.load.access = job.access;
  r.camera = job.render.camera;
  if (job.orbit) {
    r.orbit = *job.orbit;
    r.orbit_fov_deg = job.fov.value_or(default_camera_fov_deg);  // --orbit stands back for the fov in effect
  } else if (job.frame) {
    r.orbit = Orbit{};  // the default camera's place, whatever --fov then makes of it
  }
  if (job.look_from || job.look_at || job.up || job.fov) r.adjust_camera = [&job](Scene& s) { adjust_camera(job, s); };
  return r;
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

// Every rank of a spread frame has loaded and prepared the scene, or none
// goes on: a rank that failed reports its error when rank 0 did not fail
// (rank 0 reports its own; the others would say the same), rank 0 says that
// another failed, and every rank stops with status 1.
void agree_scene_ready(const std::exception_ptr& failure) {
  const std::vector<bool> ok = distributed::gather_flags(!failure);
  const distributed::Ranks& r = distributed::ranks();
  if (failure && r.root()) std::rethrow_exception(failure);
  if (failure && ok[0]) {
    try {
      std::rethrow_exception(failure);
    } catch (const std::exception& e) {
      throw Error("rank " + std::to_string(r.rank) + ": " + e.what());  // printed by main on any rank
    }
  }
  if (failure) throw distributed::ReportedElsewhere("rank 0 reports the error");
  if (std::find(ok.begin(), ok.end(), false) == ok.end()) return;
  const int other = int(std::find(ok.begin(), ok.end(), false) - ok.begin());
  if (r.root())
    throw Error("rank " + std::to_string(other) +
                " of the MPI job could not load or prepare the scene (its message "
                "above): nothing written");
  throw distributed::ReportedElsewhere("another rank failed");
}

// The ranks of a spread frame read one file before any shared work: a large
// OBJ's parse is exchanged among them, and a rank that could not open the
// file (a path missing on its node) or read another copy would leave the
// others waiting in that exchange. Each rank gives the file's size (or
// -errno when it cannot open it); unless all agree, every rank fails its
// load, rank 0 naming the first rank that differs. Ranks that all fail alike
// go on to the load, which fails on each before any exchange and says why.
//
// The agreement comes as late as it can: before the load's first exchange,
// or after the load when it makes none (agree() is called at both places and
// acts once), so that what comes before (mapping the file, scanning a large
// OBJ's chunks) overlaps MPI's start (ranks.h). A rank whose load fails
// before its first exchange agrees after it, as every rank then does.
class InputAgreement {
 public:
  explicit InputAgreement(std::string input) : input_(std::move(input)) {
    if (const int fd = ::open(input_.c_str(), O_RDONLY | O_CLOEXEC); fd < 0) {
      seen_ = -errno;
    } else {
      struct stat st {};
      seen_ = ::fstat(fd, &st) == 0 ? (long long)st.st_size : -errno;
      ::close(fd);
    }
  }

  // Collective, the first time.
  void agree() {
    if (std::exchange(agreed_, true)) return;
    const std::vector<long long> all = distributed::gather_numbers(seen_);
    const auto other = std::find_if(all.begin(), all.end(), [&](long long s) { return s != all[0]; });
    if (other == all.end()) return;
    auto what = [](long long s) {
      return s < 0 ? std::string("cannot open it (") + std::strerror(int(-s)) + ")"
                   : "reads " + std::to_string(s) + " bytes";
    };
    if (!distributed::ranks().root()) throw distributed::ReportedElsewhere("rank 0 reports the error");
    throw Error(input_ + ": rank " + std::to_string(other - all.begin()) + " of the MPI job " + what(*other) +
                ", rank 0 " + what(all[0]) + ": every rank must read the same file; nothing written");
  }

 private:
  std::string input_;
  long long seen_ = 0;
  bool agreed_ = false;
};

}  // namespace

LoadedScene load_job_scene(const RenderJob& job) { return load_scene(job.input, ready_options(job).load); }

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

RenderOptions job_render_options(const RenderJob& job) {
  RenderOptions o = job.render;
  const SceneFormat format = scene_format_from_path(job.input);
  if (job.default_size) {
    const RenderOptions d = default_render_options(format);
    o.width = d.width;
    o.height = d.height;
  }
  o.depth = job.depth.has_value();
  o.normals = !job.normals.empty();
  o.albedo = !job.albedo.empty();
  if (job.transparent) o.alpha = is_8bit_image_path(job.output) ? AlphaMode::straight : AlphaMode::premultiplied;
  // 8-bit files get 8-bit values straight from the render loop.
  o.color_format = render_color_format(ColorOutput{scene_colors(format), job.color}, job.output, job.albedo);
  return o;
}

void check_render_job_memory(const RenderJob& job) {
  if (std::string problem = render_memory_problem(job_render_options(job), available_memory_bytes()); !problem.empty())
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
  // Under mpirun every rank loads the scene (sharing a large OBJ's parse) and
  // prepares it (sharing the BVH builds of large meshes), then renders a share
  // of the frame.
  const distributed::Ranks& rank = distributed::ranks();
  const bool spread = job.spread_frame && rank.distributed();
  std::optional<InputAgreement> input;
  WorkShare share_ranks;
  if (spread) {
    input.emplace(job.input);
    share_ranks = distributed::rank_work_share();
    share_ranks.exchange = [exchange = share_ranks.exchange, &input](std::vector<std::byte> mine) {
      input->agree();
      return exchange(std::move(mine));
    };
  }
  // Warnings, notes and progress from rank 0 only: the others would repeat them.
  const bool quiet = job.quiet || (spread && !rank.root());
  auto t_load = clock::now();
  ReadyScene loaded;
  PreparedScene prepared;
  double load_s = 0.0, prepare_s = 0.0;
  std::exception_ptr failure;
  try {
    // A spread frame's ranks share the load's work (a large OBJ's parse):
    // every rank must call this, as each does. Batches do not share.
    ReadyOptions ready = ready_options(job);
    if (spread) ready.load.share = &share_ranks;
    loaded = job.preloaded ? make_scene_ready(*job.preloaded, job.input, ready) : load_ready_scene(job.input, ready);
    if (!quiet) {
      for (const std::string& w : loaded.warnings) warn(w);
      for (const std::string& n : loaded.notes) note(n);
    }
    if (job.background) {
      // Display values: converted to linear where the pictures are seen
      // through sRGB, kept where they are written as they are.
      vec3& b = loaded.scene.background.color;
      b = *job.background;
      if (shown_through_srgb(ColorOutput{loaded.color.scene, job.color}))
        for (int k = 0; k < 3; ++k) b[k] = background_from_display(b[k]);
    }
    if (input) input->agree();
    load_s = seconds_since(t_load);
  } catch (...) {
    if (!spread) throw;
    failure = std::current_exception();
    try {
      input->agree();  // a different file is the cause, when it is one
    } catch (...) {
      failure = std::current_exception();
    }
  }
  // The shared builds in prepare are collective: the ranks go on to them only
  // when every one of them has loaded the scene.
  bool all_loaded = !failure;
  if (spread) {
    const std::vector<bool> loaded_ok = distributed::gather_flags(!failure);
    all_loaded = std::find(loaded_ok.begin(), loaded_ok.end(), false) == loaded_ok.end();
  }
  PrepareOptions po;
  po.limits = job.limits;
  if (spread) po.share = &share_ranks;
  po.cache = job.mesh_cache.get();
  if (all_loaded) {
    try {
      auto t_prepare = clock::now();
      prepared = prepare_scene(loaded.scene, po);
      prepare_s = seconds_since(t_prepare);
    } catch (...) {
      if (!spread) throw;
      failure = std::current_exception();
    }
  }
  if (spread) agree_scene_ready(failure);
  const ColorOutput color{loaded.color.scene, job.color};

  // Depth and normal images: 2019's conventions, or 2012's (also for a5).
  bool course_2019 = loaded.format == SceneFormat::course_txt && loaded.dialect == CourseDialect::v2019;
  bool course_2012 = loaded.format == SceneFormat::course_txt && loaded.dialect != CourseDialect::v2019;
  RenderOptions ro = job_render_options(job);
  if (job.default_bounces) ro.bounces = loaded.render.bounces;
  Progress progress("rendering", quiet || !rank.root());
  if (progress.enabled()) ro.progress = [&](float f) { progress.update(f); };
  auto t_render = clock::now();
  distributed::FrameShare share;
  RenderResult result = spread ? distributed::render_frame_over_ranks(prepared, ro, &share) : render(prepared, ro);
  double render_s = seconds_since(t_render);
  progress.finish();
  if (spread && job.stats) {
    // Each rank's share, so that imbalance shows (before rank 0 writes: the others wait for nothing after this).
    std::ostringstream line;
    line << "stats: rank " << rank.rank << " of " << rank.size << ": " << share.tiles << " of " << tile_grid(ro).count()
         << " tiles, load " << load_s << " s, prepare " << prepare_s << " s, render " << share.render_s << " s (CPU "
         << share.render_cpu_s << " s), gather " << share.gather_s << " s\n";
    for (const std::string& text : distributed::gather_text(line.str())) std::cerr << text;
  }
  if (spread && !rank.root()) return;  // rank 0 writes the outputs
  auto t_write = clock::now();
  // All outputs appear together or not at all.
  OutputFiles files(job.output);
  files.add_written(job.output, write_color_temporary(job.output, result, ColorPlane::color, color));
  std::vector<std::pair<std::string, Image>> outputs;
  if (job.depth)
    outputs.emplace_back(job.depth->file, depth_image(result, job.depth->min, job.depth->max,
                                                      course_2019 ? DepthStyle::near_black : DepthStyle::near_white));
  if (!job.normals.empty())
    outputs.emplace_back(job.normals, normals_image(result, course_2012 ? NormalStyle::absolute : NormalStyle::offset));
  if (!job.albedo.empty())
    files.add_written(job.albedo, write_color_temporary(job.albedo, result, ColorPlane::albedo, color));
  for (const auto& [path, image] : outputs) files.add_written(path, write_image_temporary(path, image));
  files.commit();
  if (job.stats)
    std::cerr << "stats: load " << load_s << " s, prepare " << prepare_s << " s, render " << render_s << " s, write "
              << seconds_since(t_write) << " s (" << render_path_name(prepared, ro) << " path, " << ro.width << "x"
              << ro.height << ", " << samples_text(result, ro) << "), accel " << prepared.memory_bytes() / 1024
              << " KiB\n";
  if (job.mesh_cache) keep_mesh_accels(prepared, po.bvh, *job.mesh_cache);  // for the next frame
}

}  // namespace rayform::cli
