#include "rayform/pipeline/job_outputs.h"

#include "rayform/base/error.h"
#include "rayform/image/output_files.h"
#include "rayform/pipeline/render_job.h"
#include "rayform/render/aov_images.h"

#include <sys/stat.h>

#include <filesystem>
#include <utility>
#include <vector>

namespace rayform {
namespace fs = std::filesystem;
namespace {

// UsageError unless `file` names a file rayform writes, in a folder that exists.
void check_output(const ImageFile& file, const char* what) {
  const std::string& path = file.path;
  if (path.empty()) throw UsageError(std::string(what) + ": no file name given");
  if (!is_writable(file))
    throw UsageError(path + ": cannot write " + what + " images of type '" + fs::path(path).extension().string() +
                     "' (use .png, .bmp, .tga, .jpg, .exr, .hdr or .tif)");
  check_output_folder(path, what);
}

}  // namespace

void check_output_folder(const std::string& path, const std::string& what) {
  fs::path dir = fs::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw UsageError(path + ": cannot write " + what + ": folder '" + dir.string() + "' does not exist");
}

void check_outputs_are_not_inputs(const JobOutputs& outputs, const Scene& scene) {
  struct Existing {
    std::string path;
    dev_t device;
    ino_t inode;
  };
  std::vector<Existing> written;  // the outputs that exist already
  auto add = [&](const ImageFile& f) {
    struct stat st {};
    if (::stat(f.path.c_str(), &st) == 0) written.push_back(Existing{f.path, st.st_dev, st.st_ino});
  };
  add(outputs.color);
  for (const std::optional<ImageFile>* f : {&outputs.depth, &outputs.normals, &outputs.albedo})
    if (*f) add(**f);
  if (written.empty()) return;
  auto check = [&](const std::string& input) {
    struct stat st {};
    if (input.empty() || ::stat(input.c_str(), &st) != 0) return;
    for (const Existing& w : written)
      if (w.device == st.st_dev && w.inode == st.st_ino)
        throw Error(w.path + ": writing it would replace " + input +
                    ", which the scene was read from; choose another output name or folder");
  };
  check(scene.source_path);
  for (const Mesh& m : scene.meshes) check(m.source_path);
  for (const Texture& t : scene.textures) check(t.path);
  if (scene.background.environment.source == Environment::Source::file) check(scene.background.environment.path);
}

JobOutputs parse_job_outputs(const RenderJob& job) {
  JobOutputs out;
  out.color = image_file(job.output);
  if (job.depth) {
    out.depth = image_file(job.depth->file);
    out.depth_min = job.depth->min;
    out.depth_max = job.depth->max;
  }
  if (!job.normals.empty()) out.normals = image_file(job.normals);
  if (!job.albedo.empty()) out.albedo = image_file(job.albedo);
  return out;
}

JobOutputs job_outputs(const RenderJob& job) {
  const JobOutputs out = parse_job_outputs(job);
  check_output(out.color, "colour");
  if (out.depth) {
    check_output(*out.depth, "depth");
    if (!(out.depth_max > out.depth_min))
      throw UsageError("depth range must have MAX > MIN, got " + std::to_string(out.depth_min) + " .. " +
                       std::to_string(out.depth_max));
  }
  if (out.normals) check_output(*out.normals, "normals");
  if (out.albedo) check_output(*out.albedo, "albedo");
  if (job.transparent && !out.color.alpha)
    throw UsageError("--transparent: " + job.output + " cannot hold alpha (write .png, .tga, .exr or .tif)");
  return out;
}

void set_output_options(const JobOutputs& outputs, bool transparent, const ColorOutput& color, RenderOptions& options) {
  options.depth = outputs.depth.has_value();
  options.normals = outputs.normals.has_value();
  options.albedo = outputs.albedo.has_value();
  if (transparent) options.alpha = outputs.color.bits8 ? AlphaMode::straight : AlphaMode::premultiplied;
  options.color_format = render_color_format(color, outputs.color, outputs.albedo ? &*outputs.albedo : nullptr);
}

void write_job_outputs(const JobOutputs& outputs, RenderResult& result, const ColorOutput& color,
                       const LoadedScene& scene) {
  const bool course = scene.format == SceneFormat::course_txt;
  const bool course_2019 = course && scene.dialect == CourseDialect::v2019;
  const bool course_2012 = course && scene.dialect != CourseDialect::v2019;
  OutputFiles files(outputs.color.path);
  files.add_written(outputs.color.path, write_color_temporary(outputs.color, result, ColorPlane::color, color));
  std::vector<std::pair<const ImageFile*, Image>> images;
  if (outputs.depth)
    images.emplace_back(&*outputs.depth, depth_image(result, outputs.depth_min, outputs.depth_max,
                                                     course_2019 ? DepthStyle::near_black : DepthStyle::near_white));
  if (outputs.normals)
    images.emplace_back(&*outputs.normals,
                        normals_image(result, course_2012 ? NormalStyle::absolute : NormalStyle::offset));
  if (outputs.albedo)
    files.add_written(outputs.albedo->path, write_color_temporary(*outputs.albedo, result, ColorPlane::albedo, color));
  for (const auto& [file, image] : images) files.add_written(file->path, write_image_temporary(*file, image));
  files.commit();
}

}  // namespace rayform
