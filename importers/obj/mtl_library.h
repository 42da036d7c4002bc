// The materials of an OBJ's .mtl files, read before tinyobjloader reads the
// OBJ itself (private to the OBJ reader: includes tiny_obj_loader.h).
#pragma once

#include <tiny_obj_loader.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace rayform::obj {

// The materials of every .mtl an OBJ names, in the order read.
struct MtlLibrary {
  std::vector<tinyobj::material_t> materials;
  std::map<std::string, int> names;
  std::vector<std::filesystem::path> dirs;  // per material: folder of its .mtl (textures resolve there)
  // Per material: the statements its .mtl gave ("Kd", "Pr", "map_Pm", ...),
  // since tinyobjloader fills the ones absent with defaults and does not say.
  std::vector<std::set<std::string>> keywords;
  bool has(size_t material, const char* keyword) const { return keywords[material].count(keyword) > 0; }
};

// Scans MTL text for the statements (a line's first word) each material
// gives, by material name, following tinyobjloader's reading of `newmtl`:
// the name is the rest of the line.
std::map<std::string, std::set<std::string>> mtl_keywords(const std::string& text);

// Hands tinyobjloader the materials read beforehand from every mtllib (its
// own reader would take only the first file of a line and no spaces or '\').
class PreloadedMaterials : public tinyobj::MaterialReader {
 public:
  explicit PreloadedMaterials(const MtlLibrary& lib) : lib_(lib) {}
  bool operator()(const std::string&, std::vector<tinyobj::material_t>* materials, std::map<std::string, int>* names,
                  std::string*, std::string*) override {
    if (!given_) {
      *materials = lib_.materials;
      *names = lib_.names;
      given_ = true;
    }
    return true;
  }

 private:
  const MtlLibrary& lib_;
  bool given_ = false;
};

}  // namespace rayform::obj
