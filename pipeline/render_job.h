// One render job: a scene file in, image files out. load -> defaults ->
// prepare -> render -> write, with the defaults a good first picture needs
// (scene_ready.h) and every output parsed once (job_outputs.h). The command
// line and programs embedding rayform run the same job; a caller plugs in
// what it needs through JobHooks (messages, progress) and FrameSpread (one
// frame over several processes: the distributed layer).
//
//   RenderJob job;
//   job.input = "duck.glb";
//   job.output = "duck.png";
//   JobReport report = run_render_job(job);
#pragma once

#include "rayform/importers/scene_io.h"
#include "rayform/pipeline/camera_adjust.h"
#include "rayform/pipeline/frame_spread.h"
#include "rayform/pipeline/scene_ready.h"
#include "rayform/render/color_output.h"
#include "rayform/render/mesh_accel_cache.h"
#include "rayform/render/render.h"
#include "rayform/scene/scene_defaults.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace rayform {

// A depth picture: hit distances from `min` to `max` (world units) mapped to
// grey by the course's convention of the scene's dialect (job_outputs.h).
struct DepthOutput {
  float min = 0.f, max = 1.f;
  std::string file;
};

struct RenderJob {
  std::string input;
  LoadOptions load;  // how `input` is read (its `share` is set by run_render_job under a FrameSpread)
  // The colour picture; its extension decides the format (and with it the
  // encoding and whether alpha can be written).
  std::string output;
  std::optional<DepthOutput> depth;
  std::string normals;  // empty: not written
  std::string albedo;   // empty: not written
  // Size, camera, threads, shadows, bounces, sampling: handed to render() as
  // they are, but for the size when default_size and the bounces when
  // default_bounces. The per-pixel outputs and the colour format follow the
  // outputs above (job_render_options).
  RenderOptions render;
  // The scene format's default size (default_render_options: 512x512 for
  // assets, the course's 200x200 for course scenes), not render's.
  bool default_size = true;
  // The default bounces of the scene's format, dialect and materials, known
  // once it is read (default_render_options: 4 for the course's a5, 4 for
  // metallic-roughness materials, 8 when one transmits, else 0), not render's.
  bool default_bounces = true;
  // The tone map of the scene's materials, known once it is read
  // (default_render_options: khr_neutral for metallic-roughness materials,
  // else none), not render's. render.exposure_ev has no such default: 0.
  bool default_tone_map = true;
  ColorEncoding color = ColorEncoding::automatic;  // the output's transfer function (color_output.h)
  // The camera: `orbit` replaces the file's cameras with one orbiting the
  // scene's bounds, `frame` with the default camera (default_orbit);
  // `camera_adjust` then moves the camera rendered.
  bool frame = false;
  std::optional<Orbit> orbit;
  // The environment to light and show the scene with (ReadyOptions::environment).
  std::optional<Environment> environment;
  CameraAdjust camera_adjust;
  // Display values 0..1, as a colour picker gives them: for a scene whose
  // pictures are seen through sRGB converted to linear (linear_from_display,
  // image/quantize.h), so that an 8-bit output shows exactly these values;
  // for raw (course) scenes as they are.
  std::optional<vec3> background;
  // The colour output with alpha 0 on the background: straight alpha in
  // 8-bit files (PNG, TGA), premultiplied in float files (EXR, TIFF);
  // AlphaMode (render.h).
  bool transparent = false;
  // The scene as loaded from `input` with `load` (load_job_scene), when the
  // caller loaded it already: a turntable's frames load the file once.
  std::shared_ptr<const LoadedScene> preloaded;
  // BVHs kept from the previous frame of `preloaded` (its source is
  // preloaded->scene): a turntable's frames build their meshes' BVHs once.
  std::shared_ptr<MeshAccelCache> mesh_cache;
};

// What a caller hears of a job while it runs (the library prints nothing).
struct JobHooks {
  std::function<void(const std::string&)> warn;  // the reader's warnings
  std::function<void(const std::string&)> note;  // what the defaults added
  // The render's progress: render_started before its first tile, progress
  // with the fraction of tiles done (from worker threads, serialised),
  // render_done after the last.
  std::function<void()> render_started;
  std::function<void(float)> progress;
  std::function<void()> render_done;
  // Not null: the frame is spread over processes, and every one of them runs
  // the same job (collective; frame_spread.h).
  FrameSpread* spread = nullptr;
};

// What a job did, for a report (the command line's --stats).
struct JobReport {
  bool wrote = false;  // this process wrote the outputs (under a FrameSpread, its writer alone)
  double load_s = 0, prepare_s = 0, render_s = 0, write_s = 0;
  std::string render_path;  // render_path_name
  int width = 0, height = 0;
  std::string sampling;      // "4 spp", or the samples taken with adaptive sampling or the 3x3 grid
  uint64_t accel_bytes = 0;  // the prepared scene's acceleration structures
};

// Runs the job. Throws UsageError for options that do not combine or an
// output the job cannot write (before anything is read), rayform::Error for
// input, render and write errors. Nothing is written unless every output is.
JobReport run_render_job(const RenderJob& job, const JobHooks& hooks = {});

// `job.input` as run_render_job reads it, before the defaults place a camera
// and lights: for RenderJob::preloaded. Throws rayform::Error.
LoadedScene load_job_scene(const RenderJob& job);

// The options handed to render(): job.render with the default size when
// asked, the per-pixel outputs asked for and the colour format they need.
// Throws rayform::Error for an input of unknown format.
RenderOptions job_render_options(const RenderJob& job);

// Throws rayform::Error when the job's outputs need more memory than the
// machine has (render_memory.h).
void check_render_job_memory(const RenderJob& job);

// For a caller that renders in memory (the Python module, python/) what
// run_render_job does before it prepares: `job.input` (or job.preloaded)
// read with the job's camera, environment and background, the warnings and
// notes handed to `hooks`. Throws rayform::Error.
ReadyScene load_job_ready(const RenderJob& job, const JobHooks& hooks = {});

// The options run_render_job hands to render() for `job` once its scene is
// `ready`: job_render_options with the scene's default bounces and tone map
// where the job keeps them (RenderJob::default_bounces, default_tone_map).
RenderOptions job_render_options(const RenderJob& job, const ReadyScene& ready);

}  // namespace rayform
