#include "render_job.h"

#include "progress.h"
#include "render/aov_images.h"
#include "render/prepared_scene.h"
#include "render/render.h"
#include "scene/error.h"

#include <filesystem>
#include <iostream>

namespace rayform::cli {
namespace fs = std::filesystem;

void check_output_path(const std::string& path, const char* what) {
  if (path.empty()) throw Error(std::string(what) + ": no file name given");
  if (!is_writable_image_path(path))
    throw Error(path + ": cannot write " + what + " images of type '" + fs::path(path).extension().string() +
                "' (use .png, .bmp, .tga, .jpg, .exr, .hdr or .tif)");
  fs::path dir = fs::path(path).parent_path();
  if (!dir.empty() && !fs::is_directory(dir)) throw Error(path + ": cannot write " + what + ": folder '" + dir.string() + "' does not exist");
}

void run_render_job(const RenderJob& job) {
  if (job.width <= 0 || job.height <= 0)
    throw Error("image size must be positive, got " + std::to_string(job.width) + " x " + std::to_string(job.height));
  check_output_path(job.output, "colour");
  if (job.depth) {
    check_output_path(job.depth->file, "depth");
    if (!(job.depth->max > job.depth->min))
      throw Error("depth range must have MAX > MIN, got " + std::to_string(job.depth->min) + " .. " + std::to_string(job.depth->max));
  }
  if (!job.normals.empty()) check_output_path(job.normals, "normals");
  if (!job.albedo.empty()) check_output_path(job.albedo, "albedo");

  LoadedScene loaded = load_scene(job.input, LoadOptions{job.dialect});
  for (const std::string& w : loaded.warnings) std::cerr << "warning: " << w << "\n";
  PreparedScene prepared = prepare_scene(loaded.scene);

  RenderOptions ro;
  ro.width = job.width;
  ro.height = job.height;
  ro.camera = job.camera;
  ro.threads = job.threads;
  ro.shadows = job.shadows;
  ro.bounces = job.bounces;
  ro.generic = job.generic;
  ro.depth = job.depth.has_value();
  ro.normals = !job.normals.empty();
  ro.albedo = !job.albedo.empty();
  Progress progress("rendering", job.quiet);
  if (progress.enabled()) ro.progress = [&](float f) { progress.update(f); };
  RenderResult result = render(prepared, ro);
  progress.finish();

  bool course_2019 = loaded.format == SceneFormat::course_txt && loaded.dialect == CourseDialect::v2019;
  bool course_2012 = loaded.format == SceneFormat::course_txt && loaded.dialect == CourseDialect::v2012;
  write_image(job.output, result.color);
  if (job.depth)
    write_image(job.depth->file, depth_image(result, job.depth->min, job.depth->max,
                                             course_2019 ? DepthStyle::near_black : DepthStyle::near_white));
  if (!job.normals.empty())
    write_image(job.normals, normals_image(result, course_2012 ? NormalStyle::absolute : NormalStyle::offset));
  if (!job.albedo.empty()) write_image(job.albedo, result.albedo);
}

}  // namespace rayform::cli
