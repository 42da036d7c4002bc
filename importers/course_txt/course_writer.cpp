// write_course_scene: one CourseWriter (course_writer_internal.h) per file,
// and its walk (write) in order: the defaults a scene without camera or
// lights gets, the dialect, the blocks, the Group; then the messages on what
// the course could not hold, and the files.
#include "rayform/importers/course_txt/course_writer.h"

#include "rayform/importers/course_txt/course_writer_internal.h"
#include "rayform/image/output_files.h"
#include "rayform/base/error.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/importers/material_approximation.h"
#include "rayform/importers/text_format.h"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <system_error>

namespace rayform {

namespace course_detail {
namespace fs = std::filesystem;

CourseWriter::CourseWriter(const Scene& scene, const std::string& path, const CourseWriteOptions& options,
                           std::vector<std::string>* messages)
    : s_(scene), options_(options), context_(scene, path, options.side_folder, messages) {
  if (std::string problem = course_side_folder_problem(path, options.side_folder); !problem.empty())
    throw Error(path + ": " + problem);
}

SaveResult CourseWriter::write() {
  const bool course_source = fs::path(s_.source_path).extension() == ".txt";
  if (s_.cameras.empty()) {
    add_default_camera(s_);
    context_.note("the source has no camera: added one framing the scene (scene/scene_defaults.h)");
  }
  if (s_.lights.empty() && !course_source) {
    add_headlight(s_);
    context_.note(
        "the source has no light: added a white directional headlight along the view (the course would light a "
        "scene without lights by an ambient light of 1)");
  }
  approximate_pbr_materials();
  dialect_ = options_.dialect ? *options_.dialect : needed_dialect();

  // The Group first: it decides the materials block (a default material).
  std::string group = top_group();
  std::ostringstream o;
  write_camera(o);
  write_lights(o);
  write_background(o);
  write_materials(o);
  o << group;
  report();
  context_.out.add(context_.path, o.str());
  for (const std::string& d : folders_) {
    std::error_code ec;
    fs::create_directories(d, ec);
    if (ec) throw Error(d + ": cannot create folder: " + ec.message());
  }
  return SaveResult{context_.out.commit(), stored_triangles_};
}

// The course's Phong model in place of each metallic-roughness material
// (material_approximation.h), and what that could not hold, by field.
void CourseWriter::approximate_pbr_materials() {
  for (Material& m : s_.materials) {
    if (m.model != Material::Model::metallic_roughness) continue;
    pbr_approximated_.insert(m.name);
    for (const std::string& field : pbr_fields_lost_in_phong(m)) pbr_lost_[field].insert(m.name);
    m = phong_approximation(m);
  }
}

// ---- dialect -------------------------------------------------------------------

bool CourseWriter::raw_up_matters(const Camera& c) const {
  if (c.up_vector != Camera::UpVector::raw) return false;
  vec3 w = glm::normalize(c.direction);
  vec3 v = glm::cross(glm::normalize(glm::cross(w, c.up)), w);
  return glm::length(c.up - v) > 1e-6f;
}

CourseDialect CourseWriter::needed_dialect() {
  // Materials of the 2012 assignment 5 (which has falloff too).
  for (const Material& m : s_.materials)
    if (m.noise.enabled || !m.specular_highlight || !m.back_faces_cast_shadows) {
      context_.note(
          "written in the a5 dialect (materials of the 2012 assignment 5: Noise, no highlight, its shadow rule)");
      return CourseDialect::a5;
    }
  const char* why = nullptr;
  for (const Light& l : s_.lights)
    if (l.kind != Light::Kind::directional && l.falloff > 0.f) why = "point lights with falloff";
  for (const Material& m : s_.materials)
    if (m.bump_texture != invalid) why = "bump maps";
  if (!s_.cameras.empty() && raw_up_matters(s_.cameras[0])) why = "a camera whose raw up vector is not orthonormal";
  if (!why)
    for (const Mesh& m : s_.meshes) {
      if (m.normals.size() != m.positions.size()) continue;
      std::vector<uint32_t> share = sharing(m);
      float d12 = normal_deviation(m, course_normals(m, share, CourseDialect::v2012));
      float d19 = normal_deviation(m, course_normals(m, share, CourseDialect::v2019));
      if (d19 < 1e-2f && d12 >= 1e-2f) why = "mesh normals made by the 2019 rule";
    }
  if (!why) return CourseDialect::v2012;
  context_.note(std::string("written in the 2019 dialect (") + why + ")");
  return CourseDialect::v2019;
}

// ---- side files and messages --------------------------------------------------------

std::string CourseWriter::unique_file(const std::string& base, const std::string& ext) {
  std::string f = base + ext;
  for (int k = 2; used_files_.count(f); ++k) f = base + "_" + std::to_string(k) + ext;
  used_files_.insert(f);
  return f;
}

void CourseWriter::report() {
  context_.note_names(
      "meshes", normals_changed_,
      ": the course computes vertex normals from the faces (its meshes carry none); they differ from the source's "
      "by up to " +
          format_float(std::round(normal_deviation_ * 100.f) / 100.f) + " degrees");
  context_.note_names("materials", baked_uvs_, ": uv transform baked into the uvs of their meshes' OBJ files");
  context_.note_names("textures", srgb_,
                      ": sRGB-encoded texels are read raw (linear) by the course; pixels kept as they are");
  context_.note_names("textures", half_texel_,
                      ": the course samples with texel centres on whole numbers (half a texel off "
                      "the usual convention)");
  context_.note_names("textures", repeat_, ": the course clamps uvs to the image (no repeat or mirror)");
  context_.note_names("textures", nearest_, ": nearest filtering dropped (the course filters bilinearly)");
  context_.note_names("textures", alpha_dropped_, ": alpha dropped (24-bit BMP)");
}

}  // namespace course_detail

std::string course_side_folder_problem(const std::string& path, const std::string& side_folder) {
  // The course reads a file name up to white space.
  if (OutputFiles(path, side_folder).side_reference("").find_first_of(" \t\r\n") == std::string::npos) return {};
  return "a course .txt cannot name files in '" + side_folder + "' (the path to it from the .txt has white space)";
}

SaveResult write_course_scene(const Scene& scene, const std::string& path, const CourseWriteOptions& options,
                              std::vector<std::string>* messages) {
  require_scene_root(scene, path);
  return course_detail::CourseWriter(scene, path, options, messages).write();
}

}  // namespace rayform
