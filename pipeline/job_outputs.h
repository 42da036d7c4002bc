// A render job's image outputs: each path checked and parsed once
// (image/image_file.h) before the scene is read, and written together (all or
// none) with the course's conventions for depth and normal pictures.
#pragma once

#include "rayform/image/image_file.h"
#include "rayform/importers/scene_io.h"
#include "rayform/render/color_output.h"
#include "rayform/render/render.h"

#include <optional>
#include <string>

namespace rayform {

struct RenderJob;

struct JobOutputs {
  ImageFile color;
  std::optional<ImageFile> depth, normals, albedo;
  float depth_min = 0.f, depth_max = 1.f;  // world units mapped to the depth picture's grey range
};

// The job's outputs, checked: a file name, an extension rayform writes, an
// existing folder, a depth range with max > min, alpha where the job is
// transparent. Throws UsageError naming the output.
JobOutputs job_outputs(const RenderJob& job);

// The job's outputs parsed as they are, unchecked (job_render_options).
JobOutputs parse_job_outputs(const RenderJob& job);

// Throws UsageError when the folder `path` is to be written in does not exist.
void check_output_folder(const std::string& path, const std::string& what);

// Throws Error (one line naming both) when an output is one of the files the
// scene was read from (its file, its meshes' files, its textures, its
// environment picture), as the scene writers refuse (OutputFiles::protect):
// the render would replace its own input.
void check_outputs_are_not_inputs(const JobOutputs& outputs, const Scene& scene);

// The RenderOptions the outputs decide: which per-pixel buffers the render
// fills, alpha for a transparent job, and the colour format (8-bit values
// straight from the render loop when the files take them).
void set_output_options(const JobOutputs& outputs, bool transparent, const ColorOutput& color, RenderOptions& options);

// Writes every output (to temporary files, then all renamed into place).
// Depth and normal pictures follow the course's conventions of the scene's
// dialect: 2019's near-black depth and (n + 1)/2 normals, 2012's (and a5's)
// near-white depth and absolute normals; other formats take near-white depth
// and (n + 1)/2 normals.
void write_job_outputs(const JobOutputs& outputs, RenderResult& result, const ColorOutput& color,
                       const LoadedScene& scene);

}  // namespace rayform
