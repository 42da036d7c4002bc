#include "rayform/importers/obj/obj_pbr_material.h"

#include "rayform/base/error.h"
#include "rayform/importers/texture_files.h"

#include <algorithm>
#include <optional>

namespace rayform::obj {

namespace {

// -s / -o of a texture statement: uv' = uv * s + o.
UvTransform transform_of(const tinyobj::texture_option_t& o) {
  UvTransform t;
  t.scale = vec2(o.scale[0], o.scale[1]);
  t.offset = vec2(o.origin_offset[0], o.origin_offset[1]);
  return t;
}

// One channel of a decoded scalar map, as -imfchan names it (r, g, b; else
// the luminance: the mean of r, g and b, or the grey of a grey image).
struct ScalarMap {
  Pixels8 pixels;
  char channel = 'l';
  uint8_t at(int x, int y) const {
    const size_t i = (size_t(y) * size_t(pixels.width) + size_t(x)) * size_t(pixels.channels);
    const int c = pixels.channels;
    if (c >= 3) {
      if (channel == 'r' || channel == 'g' || channel == 'b')
        return pixels.data[i + size_t(channel == 'g' ? 1 : channel == 'b' ? 2 : 0)];
      return uint8_t((int(pixels.data[i]) + pixels.data[i + 1] + pixels.data[i + 2] + 1) / 3);
    }
    return pixels.data[i];
  }
  // The value at (x, y) of a w x h picture, nearest texel when the sizes differ.
  uint8_t sample(int x, int y, int w, int h) const {
    return at(int(int64_t(x) * pixels.width / w), int(int64_t(y) * pixels.height / h));
  }
};

}  // namespace

bool is_pbr_material(const std::set<std::string>& keywords) {
  for (const char* k : {"Pr", "Pm", "map_Pr", "map_Pm"})
    if (keywords.count(k)) return true;
  return false;
}

namespace {

// map_Pr and map_Pm packed as glTF's metallic-roughness texture (G
// roughness, B metallic; R unused, 255), invalid when neither decodes.
int packed_metallic_roughness(const tinyobj::material_t& tm, MtlTextures& textures) {
  const std::string rough_path =
      tm.roughness_texname.empty() ? std::string() : textures.resolve(tm.roughness_texname, "map_Pr");
  const std::string metal_path =
      tm.metallic_texname.empty() ? std::string() : textures.resolve(tm.metallic_texname, "map_Pm");
  if (rough_path.empty() && metal_path.empty()) return invalid;
  const std::string key =
      rough_path + "|" + tm.roughness_texopt.imfchan + "|" + metal_path + "|" + tm.metallic_texopt.imfchan;
  if (auto it = textures.packed.find(key); it != textures.packed.end()) return it->second;
  textures.packed[key] = invalid;
  auto decode = [&](const std::string& path, const std::string& name, char channel,
                    const char* slot) -> std::optional<ScalarMap> {
    if (path.empty()) return std::nullopt;
    Texture t;
    t.name = name;
    t.path = path;
    try {
      return ScalarMap{texture_pixels(t), channel};
    } catch (const Error& e) {
      textures.warn("material '" + tm.name + "': " + slot + " texture '" + name + "' cannot be decoded (" + e.what() +
                    "); the material has no " + slot + " texture");
      return std::nullopt;
    }
  };
  const std::optional<ScalarMap> rough =
      decode(rough_path, tm.roughness_texname, tm.roughness_texopt.imfchan, "map_Pr");
  const std::optional<ScalarMap> metal = decode(metal_path, tm.metallic_texname, tm.metallic_texopt.imfchan, "map_Pm");
  if (!rough && !metal) return invalid;
  auto texels = [](const std::optional<ScalarMap>& m) {
    return m ? int64_t(m->pixels.width) * m->pixels.height : int64_t(0);
  };
  const ScalarMap& larger = texels(rough) >= texels(metal) ? *rough : *metal;
  Texture t;
  t.name = tm.name + "_metallic_roughness";
  t.width = larger.pixels.width;
  t.height = larger.pixels.height;
  t.channels = 3;
  t.pixels.assign(size_t(t.width) * size_t(t.height) * 3, 255);
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      uint8_t* p = &t.pixels[(size_t(y) * size_t(t.width) + size_t(x)) * 3];
      if (rough) p[1] = rough->sample(x, y, t.width, t.height);
      if (metal) p[2] = metal->sample(x, y, t.width, t.height);
    }
  t.srgb = false;
  t.lookup = Texture::Lookup::standard;
  const bool clamp = rough ? tm.roughness_texopt.clamp : tm.metallic_texopt.clamp;
  t.wrap_u = t.wrap_v = clamp ? Texture::Wrap::clamp : Texture::Wrap::repeat;
  t.filter = Texture::Filter::linear;
  return textures.packed[key] = textures.add(std::move(t));
}

}  // namespace

Material pbr_material(const tinyobj::material_t& tm, const std::set<std::string>& keywords, vec3 base, int base_texture,
                      MtlTextures& textures) {
  auto has = [&](const char* k) { return keywords.count(k) > 0; };
  Material m;
  m.name = tm.name;
  m.model = Material::Model::metallic_roughness;
  m.double_sided = true;
  m.two_sided_lighting = true;  // OBJ has no culling: both sides are lit alike
  PbrMaterial& p = m.pbr;
  p.base_color = vec4(base, 1.f);
  if (base_texture != invalid) p.base_color_texture = TextureSlot{base_texture, 0, transform_of(tm.diffuse_texopt)};

  const int packed = packed_metallic_roughness(tm, textures);
  // Without a texture, a statement left out is the extension's default 0.
  p.roughness = packed != invalid && !tm.roughness_texname.empty() ? 1.f : tm.roughness;
  p.metallic = packed != invalid && !tm.metallic_texname.empty() ? 1.f : tm.metallic;
  if (packed != invalid)
    p.metallic_roughness_texture =
        TextureSlot{packed, 0, transform_of(tm.roughness_texname.empty() ? tm.metallic_texopt : tm.roughness_texopt)};

  const int emissive_texture = textures.file_texture(tm.emissive_texname, "map_Ke", true, tm.emissive_texopt.clamp);
  p.emissive =
      has("Ke") ? vec3(tm.emission[0], tm.emission[1], tm.emission[2]) : vec3(emissive_texture != invalid ? 1.f : 0.f);
  if (emissive_texture != invalid)
    p.emissive_texture = TextureSlot{emissive_texture, 0, transform_of(tm.emissive_texopt)};

  const bool norm = !tm.normal_texname.empty();
  const tinyobj::texture_option_t& normal_opt = norm ? tm.normal_texopt : tm.bump_texopt;
  const int normal_texture = textures.file_texture(norm ? tm.normal_texname : tm.bump_texname,
                                                   norm ? "norm" : "map_Bump", false, normal_opt.clamp);
  if (normal_texture != invalid) {
    p.normal_texture = TextureSlot{normal_texture, 0, transform_of(normal_opt)};
    p.normal_scale = normal_opt.bump_multiplier;
  }

  if (tm.dissolve < 1.f) {
    p.alpha_mode = PbrMaterial::AlphaMode::blend;
    p.base_color.a = std::clamp(float(tm.dissolve), 0.f, 1.f);
  }
  if (!tm.alpha_texname.empty()) {
    if (tm.alpha_texname == tm.diffuse_texname && base_texture != invalid) {
      p.alpha_mode = PbrMaterial::AlphaMode::blend;
    } else {
      textures.warn("material '" + tm.name + "': map_d '" + tm.alpha_texname +
                    "' is not map_Kd's file (whose alpha channel would be the opacity); ignored");
    }
  }
  if (has("Ni") && (tm.ior == 0.f || tm.ior >= 1.f)) p.ior = tm.ior;
  p.clearcoat = std::clamp(float(tm.clearcoat_thickness), 0.f, 1.f);
  p.clearcoat_roughness = std::clamp(float(tm.clearcoat_roughness), 0.f, 1.f);
  if (tm.sheen > 0.f) {
    p.sheen_color = vec3(std::min(float(tm.sheen), 1.f));
    p.sheen_roughness = mtl_sheen_roughness;
  }
  std::string unused;
  for (auto [name, texname] :
       {std::pair{"map_Ps", &tm.sheen_texname}, std::pair{"map_Ka", &tm.ambient_texname},
        std::pair{"map_Ks", &tm.specular_texname}, std::pair{"map_Ns", &tm.specular_highlight_texname},
        std::pair{"disp", &tm.displacement_texname}, std::pair{"refl", &tm.reflection_texname}})
    if (!texname->empty()) unused += (unused.empty() ? "" : ", ") + std::string(name);
  if (norm && !tm.bump_texname.empty()) unused += std::string(unused.empty() ? "" : ", ") + "map_Bump (norm is used)";
  if (!unused.empty())
    textures.warn("material '" + tm.name + "': " + unused + " not used by the metallic-roughness model; ignored");
  return m;
}

}  // namespace rayform::obj
