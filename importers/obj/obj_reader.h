// Wavefront OBJ + MTL as a Scene, through tinyobjloader (a thin adapter).
//
// What the Scene gets:
// - one root group node named after the file; under it one group node per
//   `o`/`g` section that has faces, holding one shape node of one Mesh;
// - polygons fan/ear-triangulated by tinyobjloader; negative (relative)
//   indices resolved; vertices deduplicated per section over their
//   (position, uv, normal) triple;
// - every MTL material of every `mtllib` (several files per line, names with
//   spaces, '\' separators all accepted), in file order; faces keep their own
//   `usemtl` in Mesh::face_materials when a section uses several; faces
//   without a (known) material use a grey material named "default";
// - Kd Ks Ns Ke and map_Kd (with -s/-o into Material::uv_transform and
//   -clamp into the wrap mode); map_Bump is kept as bump_texture. Colour
//   textures are sRGB, modulate Kd (K = Kd * texel) and use the standard
//   (half-texel) lookup with repeat wrapping;
// - normals as written (normalised); where a corner has none they are
//   generated: smooth, each face weighted by its corner angle, over all faces
//   that share the position (ObjReadOptions::flat: faceted instead);
// - vertex colours (`v x y z r g b`) when every vertex has them.
// No cameras and no lights: see scene/scene_defaults.h.
//
// Missing .mtl files, textures and unknown materials are warnings, not
// failures. Errors (rayform::Error, message "file:line: ..." where a line is
// known): unreadable file, a face index that names no vertex, non-finite
// positions, no faces at all.
#pragma once

#include "rayform/importers/referenced_files.h"
#include "rayform/scene/scene.h"
#include "rayform/base/work_share.h"

#include <cstddef>
#include <string>
#include <vector>

namespace rayform {

struct ObjReadOptions {
  bool flat = false;    // normals missing from the file: faceted instead of smooth
  FileAccess access{};  // .mtl files and textures the file names
  // How the text is parsed: 0 chooses (in chunks at once for large files when
  // more than one thread may run); `serial` in one piece; any other number
  // forces chunks of about that many bytes (tests: the result is the same).
  static constexpr size_t serial = ~size_t(0);
  size_t parse_chunk_bytes = 0;
  // The processes that read the same file at the same time, to share the
  // parse of a large text among them (obj_parallel_parse.h); each then ends
  // with the Scene one reading alone makes. Every part must read the file
  // with the same options. Null or one part: not shared.
  const WorkShare* share = nullptr;
  // With a share, the smooth normals of a mesh of at least this many faces
  // are generated shared among the parts too (obj_smooth_normals.h). Smaller
  // ones each part makes whole, where an exchange would cost about what it
  // saves (the shared BVH builds' threshold, BvhBuildOptions::
  // share_min_triangles; not measured for the normals on their own).
  size_t share_min_faces = size_t(1) << 15;
};

// Reads an OBJ file (and the .mtl files it names). Warnings, if wanted, are
// appended to `warnings`, each naming the file it is about.
Scene read_obj_scene(const std::string& path, const ObjReadOptions& options = {},
                     std::vector<std::string>* warnings = nullptr);

}  // namespace rayform
