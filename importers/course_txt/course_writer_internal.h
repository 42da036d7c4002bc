// The course writer, one per file written (write_course_scene), shared by the
// writer's parts; internal to importers/course_txt/, never installed. Its
// members are defined one concept per file:
//   course_writer.cpp        the walk (write) in order, the dialect, side file names, the messages
//   course_write_blocks.cpp  PerspectiveCamera, Lights, Background, Materials and their textures
//   course_write_meshes.cpp  triangle meshes as OBJ files, and the normals the course gives them
//   course_write_nodes.cpp   the node tree as Group / Transform blocks with MaterialIndex lines
#pragma once

#include "rayform/importers/course_txt/course_writer.h"
#include "rayform/importers/writer_context.h"
#include "rayform/scene/scene.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace rayform::course_detail {

// ---- course_write_meshes.cpp ----------------------------------------------------

// Vertices at one position with one normal are one course position; a mesh
// without normals shares nothing (the course then gives each face its own normal).
std::vector<uint32_t> sharing(const Mesh& m);

// Largest angle (degrees) between the mesh's own normals and the course's.
float normal_deviation(const Mesh& m, const std::vector<vec3>& course);

// ---- the writer -----------------------------------------------------------------

class CourseWriter {
 public:
  // Throws rayform::Error naming `path` when the course cannot name files in
  // the side folder (course_side_folder_problem).
  CourseWriter(const Scene& scene, const std::string& path, const CourseWriteOptions& options,
               std::vector<std::string>* messages);

  SaveResult write();

 private:
  // ---- course_writer.cpp --------------------------------------------------------
  void approximate_pbr_materials();
  bool raw_up_matters(const Camera& c) const;
  CourseDialect needed_dialect();
  std::string unique_file(const std::string& base, const std::string& ext);
  void report();

  // ---- course_write_blocks.cpp --------------------------------------------------
  void write_camera(std::ostringstream& o);
  void write_lights(std::ostringstream& o);
  void write_background(std::ostringstream& o);
  void write_materials(std::ostringstream& o);
  std::string texture(int ti);

  // ---- course_write_meshes.cpp --------------------------------------------------
  std::string mesh_file(int mi, int part, int uv_material);

  // ---- course_write_nodes.cpp ---------------------------------------------------
  std::vector<std::pair<int, int>> parts(const Node& n) const;
  bool group_like(const Node& n) const;
  const Node& node(int i) const;
  int children_objects(const Node& n);
  int objects(int i);
  bool leaf_material(int i, int* material);
  void set_material(int m, std::ostringstream& o, const std::string& pad);
  std::string matrix_text(const mat4& m);
  void shape_text(const Node& n, int part, int material, std::ostringstream& o, const std::string& pad);
  void emit(int i, std::ostringstream& o, const std::string& pad);
  void write_group(const Node& n, int sum, std::ostringstream& o, const std::string& pad);
  std::string top_group();

  Scene s_;  // a copy: a default camera or headlight may be added
  CourseWriteOptions options_;
  WriterContext context_;  // the output's path and names, its files, the messages
  CourseDialect dialect_ = CourseDialect::v2012;
  int current_ = -1;
  bool need_default_ = false;
  int depth_ = 0;
  std::vector<int> objects_;  // per node: objects(i), -1 not yet known
  size_t stored_triangles_ = 0;
  float normal_deviation_ = 0.f;
  std::map<int, std::string> textures_;
  std::map<std::tuple<int, int, int>, std::string> mesh_files_;
  std::map<std::string, std::string> mesh_texts_;  // OBJ text -> file
  std::set<std::string> used_files_;
  std::vector<std::string> folders_;
  std::set<std::string> pbr_approximated_;                 // metallic-roughness materials written as Phong
  std::map<std::string, std::set<std::string>> pbr_lost_;  // what of them the course lost: field -> materials
  std::set<std::string> normals_changed_, baked_uvs_, srgb_, half_texel_, repeat_, nearest_, alpha_dropped_;
};

}  // namespace rayform::course_detail
