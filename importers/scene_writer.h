// One entry point over the format writers: a Scene to course .txt, OBJ+MTL or
// glTF/GLB, picked by the output's extension (see docs/convert.md).
//
// Writers never lose anything silently: whatever the target format cannot
// hold (a camera in OBJ, a point light's falloff in the 2012 course dialect,
// a sphere that has to become triangles, ...) is reported as one message,
// naming the output file.
//
// The helpers the writers share have files of their own: shape_tessellation.h,
// scene_flatten.h, text_format.h, texture_files.h and image/output_files.h.
#pragma once

#include "rayform/importers/course_txt/course_dialect.h"
#include "rayform/image/output_files.h"
#include "rayform/scene/scene.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace rayform {

struct SaveOptions {
  // Bake every transform into the geometry: one flat group of shapes in world
  // space (spheres stay spheres under rotations, translations and uniform
  // scales; under other transforms they are tessellated).
  bool flatten = false;
  // glTF: buffers and images inside the .gltf as data URIs (a .glb always
  // holds them in its binary chunk).
  bool embed = false;
  // Longitudes of a tessellated sphere (>= 3); it has segments / 2 bands.
  int sphere_segments = 64;
  // Course output: the dialect to write; unset: a5 for a5 materials (Noise, no
  // highlight), else 2012 unless the scene needs 2019 (falloff, bump maps, a
  // raw camera up vector, 2019 mesh normals).
  std::optional<CourseDialect> dialect;
  // glTF: keep spheres, planes and triangles' analytic form in primitive
  // extras (rayform's reader restores them). false: meshes only, so every
  // reader, rayform's included, sees the tessellation.
  bool shape_extras = true;
  // The folder of the side files (meshes, textures, a .mtl, a .bin), which
  // must exist; empty: beside the output. The output names them by their path
  // relative to its own folder (OutputFiles::side_reference).
  std::string side_folder;
};

struct SaveResult {
  std::vector<std::string> files;  // every file written, the main one first
  size_t stored_triangles = 0;     // triangles stored in the written meshes (instances count once)
};

// Writes `scene` to `path` (.txt, .obj, .gltf, .glb). Messages about what the
// target cannot hold are appended to `messages` (if given), each starting with
// the output's name. Throws rayform::Error naming the file on failure; files
// are written to temporary names and renamed into place, so a failure leaves
// no partial file.
SaveResult save_scene(const Scene& scene, const std::string& path, const SaveOptions& options = {},
                      std::vector<std::string>* messages = nullptr);

// What every writer checks first: throws rayform::Error naming `path` when
// `scene` has no root node (nothing to write).
void require_scene_root(const Scene& scene, const std::string& path);

// What every writer protects (OutputFiles::protect): the files the scene was
// read from (the scene file, its meshes and textures), which an output must
// never replace (`convert s.txt o.txt` would otherwise overwrite the input
// mesh o_teapot.obj with the converted one).
void protect_scene_inputs(const Scene& scene, OutputFiles& out);

}  // namespace rayform
