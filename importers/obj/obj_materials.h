// The materials of an OBJ file: its `mtllib` libraries found (beside the
// .obj, checked against the file-access rules), read with tinyobjloader
// (MtlLibrary, which the geometry's parse then takes its material ids from),
// and turned into Scene materials and textures: the course's Phong model for
// Kd/Ks/Ns materials, the metallic-roughness model for those of MTL's PBR
// extension (obj_pbr_material.h), and a default grey material for faces
// without a known one. Textures are resolved beside their .mtl and shared
// between materials that name the same file the same way.
#pragma once

#include "rayform/importers/obj/mtl_library.h"
#include "rayform/importers/obj/obj_pbr_material.h"
#include "rayform/importers/referenced_files.h"
#include "rayform/scene/scene.h"

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace rayform::obj {

namespace fs = std::filesystem;

class ObjMaterials {
 public:
  // `path`: the .obj (messages and access checks name it), `dir` its folder;
  // materials and textures are added to `scene`; warnings go to `warn`.
  ObjMaterials(const std::string& path, const fs::path& dir, const FileAccess& access, Scene& scene,
               std::function<void(std::string)> warn);

  // Reads the libraries the `mtllib` lines of the OBJ text name, found by
  // searching the text for the word (not line by line: a mesh file is mostly
  // vertices and faces). Throws rayform::Error for a library the access
  // rules refuse.
  void load_libraries(std::string_view text);
  // The Scene materials of the libraries read, in their order (material id i
  // is scene material i of those added).
  void convert();
  // The material of faces without a known one, added on first use.
  int default_material();
  const MtlLibrary& library() const { return lib_; }

 private:
  void load_mtl(const fs::path& file);
  // The path of a material's texture file, resolved beside its .mtl; "" when
  // it cannot be found (warned about).
  std::string texture_path(const std::string& name, const fs::path& mtl_dir, const std::string& material,
                           const char* slot);
  // A texture of a material: resolved beside its .mtl; missing = warning.
  int texture(const std::string& name, const fs::path& mtl_dir, const std::string& material, const char* slot,
              bool srgb, bool clamp);
  // How the PBR materials of the .mtl in `dir` find their textures.
  MtlTextures& pbr_textures(const fs::path& dir);

  std::string path_;
  fs::path dir_;
  FileAccess access_;
  Scene& scene_;
  std::function<void(std::string)> warn_;
  MtlLibrary lib_;
  std::map<std::string, int> texture_cache_;
  MtlTextures pbr_textures_;      // the PBR materials' textures, packed ones included
  std::string current_material_;  // the material being converted, for messages
  int default_material_ = invalid;
};

}  // namespace rayform::obj
