#include "rayform/pipeline/render_job.h"

#include "rayform/base/error.h"
#include "rayform/base/thread_limit.h"
#include "rayform/image/quantize.h"
#include "rayform/pipeline/job_outputs.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render_memory.h"

#include <chrono>
#include <cstdio>
#include <exception>

namespace rayform {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The sampling of a render for a report: "4 spp", or the samples taken per
// pixel on average with adaptive sampling and the 3x3 grid.
std::string sampling_text(const RenderResult& r, const RenderOptions& o) {
  if (!o.grid.on() && !o.target_error) return std::to_string(o.spp) + " spp";
  char text[96];
  const double pixels = double(r.width) * double(r.height);
  std::snprintf(text, sizeof text, "%llu samples, %.2f per pixel%s", static_cast<unsigned long long>(r.samples),
                double(r.samples) / pixels, o.grid.on() ? ", 3x3 grid" : ", adaptive");
  return text;
}

// What load_ready_scene is asked for: the reader's options, and the camera
// the job places (orbit and frame replace the file's cameras with
// orbit_camera's; camera_adjust then moves the camera rendered).
ReadyOptions ready_options(const RenderJob& job) {
  ReadyOptions r;
  r.load = job.load;
  r.camera = job.render.camera;
  if (job.orbit) {
    r.orbit = *job.orbit;
    r.orbit_fov_deg = job.camera_adjust.fov_deg.value_or(default_camera_fov_deg);  // stands back for the fov in effect
  } else if (job.frame) {
    r.frame = true;  // the default camera's place, whatever the fov then makes of it
  }
  r.environment = job.environment;
  if (job.camera_adjust.any())
    r.adjust_camera = [&job](Scene& s) {
      adjust_camera(s, job.render.camera, job.camera_adjust, job.load.limits.instances);
    };
  return r;
}

// The file read with the job's defaults, the background replaced when asked.
ReadyScene load_ready(const RenderJob& job, const JobHooks& hooks) {
  ReadyOptions ready = ready_options(job);
  if (hooks.spread) ready.load.share = &hooks.spread->work_share();
  ReadyScene loaded =
      job.preloaded ? make_scene_ready(*job.preloaded, job.input, ready) : load_ready_scene(job.input, ready);
  if (hooks.warn)
    for (const std::string& w : loaded.warnings) hooks.warn(w);
  if (hooks.note) {
    for (const std::string& n : loaded.notes) hooks.note(n);
    if (job.default_bounces && !loaded.bounces_note.empty()) hooks.note(loaded.bounces_note);
  }
  if (job.background) {
    // Display values: converted to linear where the pictures are seen
    // through sRGB, kept where they are written as they are.
    vec3& b = loaded.scene.background.color;
    b = *job.background;
    loaded.scene.background.color_shown = true;
    if (shown_through_srgb(ColorOutput{loaded.color.scene, job.color}))
      for (int k = 0; k < 3; ++k) b[k] = linear_from_display(b[k]);
  }
  return loaded;
}

// job.render with the default size when asked and what `outputs` decide.
RenderOptions render_options(const RenderJob& job, const JobOutputs& outputs) {
  RenderOptions o = job.render;
  const SceneFormat format = scene_format_from_path(job.input);
  if (job.default_size) {
    const RenderOptions d = default_render_options(format);
    o.width = d.width;
    o.height = d.height;
  }
  set_output_options(outputs, job.transparent, ColorOutput{scene_colors(format), job.color}, o);
  return o;
}

// The scene's defaults where the job keeps them.
void apply_scene_defaults(const RenderJob& job, const ReadyScene& loaded, RenderOptions& ro) {
  if (job.default_bounces) ro.bounces = loaded.render.bounces;
  if (job.default_tone_map) ro.tone_map = loaded.render.tone_map;
}

void check_memory(const RenderJob& job, const RenderOptions& options) {
  if (std::string problem = render_memory_problem(options, available_memory_bytes()); !problem.empty())
    throw Error(job.output + ": " + problem);
}

}  // namespace

LoadedScene load_job_scene(const RenderJob& job) { return load_scene(job.input, job.load); }

RenderOptions job_render_options(const RenderJob& job) { return render_options(job, parse_job_outputs(job)); }

void check_render_job_memory(const RenderJob& job) { check_memory(job, job_render_options(job)); }

ReadyScene load_job_ready(const RenderJob& job, const JobHooks& hooks) { return load_ready(job, hooks); }

RenderOptions job_render_options(const RenderJob& job, const ReadyScene& ready) {
  RenderOptions o = job_render_options(job);
  apply_scene_defaults(job, ready, o);
  return o;
}

JobReport run_render_job(const RenderJob& job, const JobHooks& hooks) {
  const JobOutputs outputs = job_outputs(job);
  if (std::string problem = render_options_problem(job.render); !problem.empty()) throw UsageError(problem);
  RenderOptions ro = render_options(job, outputs);
  check_memory(job, ro);  // before the scene is read (render() checks it again)
  // The thread bound holds for the whole job (the BVH builds too), not only the render.
  const std::shared_ptr<void> thread_limit = limit_threads(job.render.threads);
  const std::shared_ptr<void> workers = job.render.threads != 1 ? start_worker_threads() : nullptr;
  FrameSpread* const spread = hooks.spread;
  JobReport report;
  ReadyScene loaded;
  PreparedScene prepared;
  std::exception_ptr failure;
  const auto t_load = Clock::now();
  try {
    loaded = load_ready(job, hooks);
    check_outputs_are_not_inputs(outputs, loaded.scene);
    if (spread) {
      if (std::exception_ptr disagreement = spread->after_load(nullptr)) std::rethrow_exception(disagreement);
    }
    report.load_s = seconds_since(t_load);
  } catch (...) {
    if (!spread) throw;
    failure = spread->after_load(std::current_exception());
  }
  // A spread frame's shared BVH builds are collective: the processes go on to
  // them only when every one of them has loaded the scene.
  const bool all_loaded = spread ? spread->all_loaded(!failure) : true;
  PrepareOptions po;
  po.limits = job.load.limits;
  if (spread) po.share = &spread->work_share();
  po.cache = job.mesh_cache.get();
  if (all_loaded) {
    try {
      const auto t_prepare = Clock::now();
      prepared = prepare_scene(loaded.scene, po);
      report.prepare_s = seconds_since(t_prepare);
    } catch (...) {
      if (!spread) throw;
      failure = std::current_exception();
    }
  }
  if (spread) spread->agree_ready(failure);

  apply_scene_defaults(job, loaded, ro);
  if (ro.bounces > max_bounces && hooks.note)
    hooks.note("bounces " + std::to_string(ro.bounces) + ": reflections and refractions are traced " +
               std::to_string(max_bounces) + " deep at most; rendering " + std::to_string(max_bounces));
  ro.progress = hooks.progress;
  if (hooks.render_started) hooks.render_started();
  const auto t_render = Clock::now();
  RenderResult result = spread ? spread->render(prepared, ro) : render(prepared, ro);
  report.render_s = seconds_since(t_render);
  if (hooks.render_done) hooks.render_done();
  if (spread) {
    spread->after_render(report.load_s, report.prepare_s);
    if (!spread->writer()) return report;
  }
  const auto t_write = Clock::now();
  write_job_outputs(outputs, result, ColorOutput{loaded.color.scene, job.color}, loaded);
  report.wrote = true;
  report.write_s = seconds_since(t_write);
  report.render_path = render_path_name(prepared, ro);
  report.width = ro.width;
  report.height = ro.height;
  report.sampling = sampling_text(result, ro);
  report.accel_bytes = prepared.memory_bytes();
  if (job.mesh_cache) keep_mesh_accels(prepared, po.bvh, *job.mesh_cache);  // for the next frame
  return report;
}

}  // namespace rayform
