// One render from the command line: load, prepare, render, write outputs.
// Shared by the course-compatible flags and the `render` subcommand.
#pragma once

#include "rayform/importers/scene_ready.h"
#include "rayform/render/color_output.h"
#include "rayform/render/mesh_accel_cache.h"
#include "rayform/render/render.h"
#include "rayform/scene/scene_defaults.h"

#include <memory>
#include <optional>
#include <string>

namespace rayform::cli {

struct DepthOutput {
  float min = 0.f, max = 1.f;
  std::string file;
};

struct RenderJob {
  std::string input;
  std::string output;
  // Size, camera, threads, shadows, bounces, spp, filter, generic: filled by
  // the command line, handed to render() as they are (the size replaced by
  // the default when default_size). The output flags (depth/normals/albedo)
  // and the colour format are set from the outputs below.
  RenderOptions render;
  std::optional<DepthOutput> depth;
  std::string normals;  // empty: not written
  std::string albedo;   // empty: not written
  std::optional<CourseDialect> dialect;
  // No --size: the library's default for the scene's format (default_render_options).
  bool default_size = false;
  // No --bounces: the default of the scene's format and dialect, known once
  // it is read (default_render_options: 4 for the course's a5, else 0).
  bool default_bounces = false;
  // Output transfer function (--color): automatic lets render/color_output.h choose.
  ColorEncoding color = ColorEncoding::automatic;
  // Camera and background overrides (any format). --frame and --orbit
  // replace the file's cameras (scene/scene_defaults.h); the others then
  // adjust the camera rendered.
  bool frame = false;
  std::optional<Orbit> orbit;
  std::optional<vec3> look_from, look_at, up;
  std::optional<float> fov;
  // Display values 0..1, as a colour picker gives them: for a scene rendered
  // with sRGB encoding converted to linear (background_from_display), so that
  // an 8-bit output shows these values; for raw (course) scenes as they are.
  std::optional<vec3> background;
  // The colour output with alpha 0 on the background (is_alpha_image_path):
  // straight alpha in 8-bit files (PNG, TGA), premultiplied in float files
  // (EXR, TIFF); see AlphaMode (render.h).
  bool transparent = false;
  bool quiet = false;
  bool stats = false;         // print timings and counts on stderr
  bool flat_normals = false;  // OBJ: missing normals faceted
  int gltf_scene = -1;        // glTF: scene index (-1: default)
  Limits limits;              // what the scene may claim (--limit), for loading and preparing
  FileAccess access;          // --confine
  // Under mpirun, render the one frame with every rank (distributed_frame.h;
  // every rank loads and prepares the scene, rank 0 writes the outputs).
  // False for the renders of a batch, each on one rank (render_batch.h).
  bool spread_frame = true;
  // The scene as loaded from `input` with this job's reading options
  // (load_job_scene), when the caller loaded it already: a turntable's
  // frames on one rank load the file once (render_batch.h).
  std::shared_ptr<const LoadedScene> preloaded;
  // BVHs kept from the previous frame of `preloaded` (render/mesh_accel_cache.h;
  // its source is preloaded->scene): a turntable's frames on one rank build
  // their meshes' BVHs once.
  std::shared_ptr<MeshAccelCache> mesh_cache;
};

// `job.input` as run_render_job reads it (before its camera and lights are
// placed), for RenderJob::preloaded. Throws rayform::Error.
LoadedScene load_job_scene(const RenderJob& job);

// Runs the job; throws rayform::Error with a message for the user. Under
// mpirun with spread_frame, collective: every rank runs the same job.
void run_render_job(const RenderJob& job);

// The options handed to render(): job.render with the default size when none
// was given, the outputs asked for and the colour buffer they need. Throws
// rayform::Error for an input of unknown format.
RenderOptions job_render_options(const RenderJob& job);

// Throws rayform::Error when the job's outputs need more memory than the
// machine has (render_memory.h); run_render_job's first check.
void check_render_job_memory(const RenderJob& job);

// Checks an output path before any work is done (known extension, folder
// exists); throws UsageError (exit status 2).
void check_output_path(const std::string& path, const char* what);
// Throws UsageError when the folder `path` is to be written in does not exist.
void check_output_folder(const std::string& path, const std::string& what);

}  // namespace rayform::cli
