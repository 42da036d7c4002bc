// A Scene as a course scene (.txt, docs/course-format.md), in the grammar the
// course's own code reads: blocks in the reference's order, the keys of each
// block in the order it expects, no comments (an [ext] of rayform's reader).
//
// What the files get:
// - PerspectiveCamera (the first camera; a default one framing the scene when
//   the source has none), Lights (a headlight when a non-course source has
//   none), Background (colour, ambient light, cube map faces as PNGs in a
//   folder beside the .txt), Materials (PhongMaterial, one per Scene material,
//   plus a plain white one when shapes without a material follow a
//   MaterialIndex);
// - the node tree as nested Group / Transform { Matrix4f { ... } OBJECT }
//   (16 numbers column by column, the course's Matrix4f convention) with
//   MaterialIndex lines where the material changes; groups and identity
//   transforms with a single object are not written around it;
// - spheres, planes and triangles as themselves; each triangle mesh as an OBJ
//   file beside the .txt (<stem>_<name>.obj) in the course's own OBJ subset
//   (v, vt, f a/b triangles, a final newline: its parser misreads anything
//   more): uvs kept; normals are not a part of the course's meshes (it
//   computes them from the faces by the dialect's rule), so vertices are shared
//   where the source's normals are shared, and a mesh without normals is
//   written with unshared vertices so that the course gives it facets; any
//   remaining difference is reported with its largest angle;
// - textures as 24-bit BMP files beside the .txt (<stem>_<name>.bmp; BMP
//   sources copied byte for byte), a material's uv transform baked into its
//   mesh's uvs.
// Everything the course cannot hold is reported in the messages.
#pragma once

#include "rayform/importers/course_txt/course_dialect.h"
#include "rayform/importers/scene_writer.h"

#include <optional>
#include <string>
#include <vector>

namespace rayform {

struct CourseWriteOptions {
  // Unset: 2012 unless the scene needs 2019 (a point light's falloff, bump
  // maps, a raw camera up vector that is not orthonormal, or meshes whose
  // normals follow the 2019 rule but not the 2012 one).
  std::optional<CourseDialect> dialect;
  std::string side_folder;  // side files there (SaveOptions::side_folder)
};

// Why a course .txt at `path` cannot name side files in `side_folder` (the
// course reads a file name up to white space); "" when it can.
std::string course_side_folder_problem(const std::string& path, const std::string& side_folder);

SaveResult write_course_scene(const Scene& scene, const std::string& path, const CourseWriteOptions& options,
                              std::vector<std::string>* messages);

// The vertex normals the course computes for a mesh (docs/course-format.md:
// the sum over the faces around each position of their face normals, raw
// cross products in 2012, unit ones in 2019, normalised), per vertex of
// `mesh`, where vertices at equal positions are one course position when
// `share` says so (share[i] = index of the representative vertex of i).
std::vector<vec3> course_normals(const Mesh& mesh, const std::vector<uint32_t>& share, CourseDialect dialect);

}  // namespace rayform
