// A Scene as Wavefront OBJ + MTL (<stem>.obj, <stem>.mtl, textures beside them).
//
// OBJ has no transforms and no node hierarchy: every shape is written in world
// space (transforms baked into the vertices, normals by the inverse transpose,
// winding reversed under mirrors), and each node's shapes become one `o`
// section named after the node (a mesh whose faces use several materials
// stays one section with `usemtl` switches). Spheres are tessellated and
// planes become large quads (shape_tessellation.h); cameras, lights and the
// background are dropped. Each of these is reported in the messages.
//
// What is kept: positions, uvs (`vt`), normals (`vn`; a mesh without normals,
// which the renderer shades with face normals, gets each face's normal, since
// readers would otherwise smooth it), vertex colours (`v x y z r g b`), each
// written once per distinct value; materials as Kd Ks Ns Ke Ni with map_Kd
// (`-s`/`-o` for a uv transform without rotation, baked into the uvs
// otherwise; `-clamp on`; `-colorspace linear` for raw course textures) and
// map_Bump. Textures are copied beside the .obj (<stem>_<name>.<ext>).
#pragma once

#include "rayform/importers/scene_writer.h"

#include <string>
#include <vector>

namespace rayform {

struct ObjWriteOptions {
  int sphere_segments = 64;
  bool flattened = false;   // the caller flattened the scene (no message about the hierarchy)
  std::string side_folder;  // side files there (SaveOptions::side_folder)
};

SaveResult write_obj_scene(const Scene& scene, const std::string& path, const ObjWriteOptions& options,
                           std::vector<std::string>* messages);

}  // namespace rayform
