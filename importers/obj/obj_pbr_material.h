// MTL's physically based extension (the Exocortex proposal tinyobjloader
// parses: Pr, Pm, Ps, Pc, Pcr, map_Pr, map_Pm, norm) as a Scene material of
// Model::metallic_roughness (private to the OBJ reader: includes
// tiny_obj_loader.h). A material that gives none of Pr, Pm, map_Pr, map_Pm
// stays the Phong material of Kd/Ks/Ns.
//
// The mapping (each texture on uv set 0, OBJ's uvs being the Scene's):
//   base colour  Kd (1 when absent and map_Kd is given, else 0.8) x map_Kd (sRGB)
//   roughness    Pr, metallic Pm; with map_Pr / map_Pm the texel replaces the
//                value (factor 1), as Blender reads them; the two maps are
//                packed into one texture (G roughness, B metallic, glTF's
//                layout), each read from the channel its -imfchan names
//                (r, g, b; else the luminance)
//   emissive     Ke (1 when absent and map_Ke is given) x map_Ke (sRGB)
//   normal       norm, else map_Bump / bump (Blender writes normal maps so), -bm the scale
//   alpha        d < 1: BLEND with alpha d; map_d when it is map_Kd's file (its alpha channel)
//   ior          Ni; clearcoat Pc, roughness Pcr; sheen Ps as a grey sheen
//                colour of roughness 0.5 (Blender's default: MTL has none)
#pragma once

#include "rayform/scene/scene.h"

#include <tiny_obj_loader.h>

#include <functional>
#include <map>
#include <set>
#include <string>

namespace rayform::obj {

// MTL gives no sheen roughness: the reader takes Blender's Principled BSDF default.
inline constexpr float mtl_sheen_roughness = 0.5f;

// Whether the material's statements (MtlLibrary::keywords) use the extension.
bool is_pbr_material(const std::set<std::string>& keywords);

// How the reader finds a material's textures.
struct MtlTextures {
  // The path of texture file `name` of slot `slot` ("map_Pr"), "" when it
  // cannot be found (warned about).
  std::function<std::string(const std::string& name, const char* slot)> resolve;
  // The Scene texture of a file (cached by path and options).
  std::function<int(const std::string& name, const char* slot, bool srgb, bool clamp)> file_texture;
  // Adds a texture of decoded pixels to the Scene.
  std::function<int(Texture)> add;
  std::function<void(const std::string&)> warn;
  // Packed metallic-roughness textures made so far, by their sources.
  std::map<std::string, int> packed;
};

// The Model::metallic_roughness material of `tm` (which is_pbr_material),
// whose base colour `base` and texture `base_texture` (map_Kd) the reader
// found as for its Phong materials.
Material pbr_material(const tinyobj::material_t& tm, const std::set<std::string>& keywords, vec3 base, int base_texture,
                      MtlTextures& textures);

}  // namespace rayform::obj
