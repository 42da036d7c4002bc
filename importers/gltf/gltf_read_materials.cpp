// The glTF reader's materials and textures (GltfReader,
// gltf_reader_internal.h): glTF materials as Scene metallic-roughness
// materials through gltf_material.h, every texture reference of the core and
// the material extensions as a TextureSlot (texCoord, KHR_texture_transform),
// textures with their image source (core, EXT_texture_webp,
// KHR_texture_basisu's fallback) and sampler, sRGB for colour and linear for
// data (one Scene texture per glTF texture and use).
#include "rayform/importers/gltf/gltf_file_access.h"
#include "rayform/importers/gltf/gltf_material.h"
#include "rayform/importers/gltf/gltf_reader_internal.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>

namespace rayform::gltf_detail {
namespace fs = std::filesystem;

namespace {

std::vector<float> numbers(const tinygltf::Value& v) {
  std::vector<float> out;
  if (!v.IsArray()) return out;
  for (size_t i = 0; i < v.ArrayLen(); ++i) {
    const tinygltf::Value& e = v.Get(int(i));
    out.push_back(e.IsNumber() ? float(e.GetNumberAsDouble()) : std::numeric_limits<float>::quiet_NaN());
  }
  return out;
}

}  // namespace

// The slot of texture reference `info` (named `where`): its Scene texture
// (invalid when the image could not be loaded, warned about), texCoord and
// KHR_texture_transform (whose texCoord overrides the reference's). Sets other
// than TEXCOORD_0 and TEXCOORD_1 are not read: such a reference is warned
// about and left unused.
TextureSlot GltfReader::texture_slot(const tinygltf::TextureInfo& info, bool srgb, const std::string& where) {
  TextureSlot r;
  r.texcoord = info.texCoord;
  if (r.texcoord < 0) fail(where + ".texCoord: " + std::to_string(r.texcoord) + " is negative");
  std::string texcoord_where = where + ".texCoord";
  auto it = info.extensions.find("KHR_texture_transform");
  if (it != info.extensions.end()) {
    const tinygltf::Value& t = it->second;
    const std::string tw = where + ".extensions.KHR_texture_transform";
    if (!t.IsObject()) fail(tw + ": expected an object");
    vec2 offset(0.f), scale(1.f);
    float rotation = 0.f;
    if (t.Has("offset")) {
      std::vector<float> o = numbers(t.Get("offset"));
      if (o.size() != 2 || !std::isfinite(o[0]) || !std::isfinite(o[1])) fail(tw + ".offset: expected 2 numbers");
      offset = vec2(o[0], o[1]);
    }
    if (t.Has("scale")) {
      std::vector<float> s = numbers(t.Get("scale"));
      if (s.size() != 2 || !std::isfinite(s[0]) || !std::isfinite(s[1])) fail(tw + ".scale: expected 2 numbers");
      scale = vec2(s[0], s[1]);
    }
    if (t.Has("rotation")) {
      const tinygltf::Value& rv = t.Get("rotation");
      if (!rv.IsNumber() || !std::isfinite(rv.GetNumberAsDouble())) fail(tw + ".rotation: expected a number");
      rotation = float(rv.GetNumberAsDouble());
    }
    if (t.Has("texCoord")) {
      const tinygltf::Value& tc = t.Get("texCoord");
      if (!tc.IsNumber() || tc.GetNumberAsInt() < 0) fail(tw + ".texCoord: expected an index >= 0");
      r.texcoord = tc.GetNumberAsInt();  // overrides the textureInfo's
      texcoord_where = tw + ".texCoord";
    }
    r.transform = gltf_uv_transform_to_scene(offset, rotation, scale);
  }
  if (r.texcoord > 1) {
    if (info.index < 0 || size_t(info.index) >= model_.textures.size())
      fail(where + ".index: texture " + std::to_string(info.index) + " does not exist (the file has " +
           std::to_string(model_.textures.size()) + " textures)");
    warn(texcoord_where + ": TEXCOORD_" + std::to_string(r.texcoord) +
         " is not read (only TEXCOORD_0 and TEXCOORD_1 are); the texture is not used");
    return TextureSlot{};
  }
  r.texture = texture(info.index, srgb, where);
  return r;
}

// A texture reference inside an extension (a JSON object tinygltf leaves
// unparsed) as a core textureInfo: index, texCoord, extensions.
tinygltf::TextureInfo GltfReader::texture_info(const tinygltf::Value& v, const std::string& where) {
  if (!v.IsObject() || !v.Has("index") || !v.Get("index").IsNumber())
    fail(where + ": expected an object with an \"index\"");
  tinygltf::TextureInfo info;
  info.index = v.Get("index").GetNumberAsInt();
  if (v.Has("texCoord")) {
    const tinygltf::Value& tc = v.Get("texCoord");
    if (!tc.IsNumber()) fail(where + ".texCoord: expected an index >= 0");
    info.texCoord = tc.GetNumberAsInt();
  }
  if (v.Has("extensions")) {
    const tinygltf::Value& e = v.Get("extensions");
    if (!e.IsObject()) fail(where + ".extensions: expected an object");
    for (const std::string& key : e.Keys()) info.extensions[key] = e.Get(key);
  }
  return info;
}

// Every texture reference of glTF material `gm` (named `mw`) in its
// PbrMaterial slot (gltf_material_textures). The specular-glossiness
// workflow, when present, replaces the core base colour and
// metallic-roughness textures.
void GltfReader::read_texture_slots(const tinygltf::Material& gm, const std::string& mw, PbrMaterial& pbr) {
  auto as_info = [](int index, int texcoord, const tinygltf::ExtensionMap& extensions) {
    tinygltf::TextureInfo info;
    info.index = index;
    info.texCoord = texcoord;
    info.extensions = extensions;
    return info;
  };
  const bool specular_glossiness = gm.extensions.count("KHR_materials_pbrSpecularGlossiness") > 0;
  const tinygltf::PbrMetallicRoughness& core = gm.pbrMetallicRoughness;
  const std::string pw = mw + ".pbrMetallicRoughness";
  if (core.baseColorTexture.index != -1 && !specular_glossiness)
    pbr.base_color_texture = texture_slot(core.baseColorTexture, true, pw + ".baseColorTexture");
  if (core.metallicRoughnessTexture.index != -1 && !specular_glossiness)
    pbr.metallic_roughness_texture =
        texture_slot(core.metallicRoughnessTexture, false, pw + ".metallicRoughnessTexture");
  const tinygltf::NormalTextureInfo& n = gm.normalTexture;
  if (n.index != -1)
    pbr.normal_texture = texture_slot(as_info(n.index, n.texCoord, n.extensions), false, mw + ".normalTexture");
  const tinygltf::OcclusionTextureInfo& o = gm.occlusionTexture;
  if (o.index != -1)
    pbr.occlusion_texture = texture_slot(as_info(o.index, o.texCoord, o.extensions), false, mw + ".occlusionTexture");
  if (gm.emissiveTexture.index != -1)
    pbr.emissive_texture = texture_slot(gm.emissiveTexture, true, mw + ".emissiveTexture");
  for (const GltfMaterialTexture& t : gltf_material_textures()) {
    if (!*t.extension) continue;
    auto it = gm.extensions.find(t.extension);
    if (it == gm.extensions.end() || !it->second.IsObject() || !it->second.Has(t.key)) continue;
    const std::string where = mw + ".extensions." + t.extension + "." + t.key;
    pbr.*t.slot = texture_slot(texture_info(it->second.Get(t.key), where), t.srgb, where);
  }
}

// Scene texture for glTF texture ti, its texels sRGB-encoded colour or linear
// data as `srgb` says, or invalid when its image could not be loaded (warned
// about). A texture used both ways becomes two Scene textures.
int GltfReader::texture(int ti, bool srgb, const std::string& where) {
  if (ti < 0 || size_t(ti) >= model_.textures.size())
    fail(where + ".index: texture " + std::to_string(ti) + " does not exist (the file has " +
         std::to_string(model_.textures.size()) + " textures)");
  std::array<int, 2>& converted = textures_[size_t(ti)];
  const size_t kind = srgb ? 1 : 0;
  if (converted[kind] != -2) return converted[kind];
  converted[kind] = invalid;
  // Read the other way already: the same pixels and sampler.
  if (const int other = converted[1 - kind]; other != -2) {
    if (other == invalid) return invalid;
    Texture copy = scene_.textures[size_t(other)];
    copy.srgb = srgb;
    scene_.textures.push_back(std::move(copy));
    converted[kind] = int(scene_.textures.size()) - 1;
    return converted[kind];
  }
  const tinygltf::Texture& t = model_.textures[size_t(ti)];
  const std::string tw = idx("textures", ti);
  const int source = texture_source(t, tw);
  if (source < 0) {
    warn(tw + ": no image this reader can use (source missing); untextured");
    return invalid;
  }
  const tinygltf::Image& img = model_.images[size_t(source)];
  const std::string iw = idx("images", source);
  if (img.image.empty() || img.width <= 0 || img.height <= 0) {
    warn(iw + (img.uri.empty() || is_data_uri(img.uri) ? "" : " ('" + img.uri + "')") +
         ": not loaded; materials using it are untextured");
    return invalid;
  }
  if (img.bits != 8 || img.component < 1 || img.component > 4 ||
      img.image.size() != size_t(img.width) * size_t(img.height) * size_t(img.component)) {
    warn(iw + ": unexpected pixel layout from the image decoder; materials using it are untextured");
    return invalid;
  }
  Texture tex;
  tex.name = !img.name.empty() ? img.name : (!img.uri.empty() && !is_data_uri(img.uri) ? img.uri : iw);
  if (!img.uri.empty() && !is_data_uri(img.uri))
    tex.path = (fs::path(path_).parent_path() / percent_decode(img.uri)).lexically_normal().string();
  tex.width = img.width;
  tex.height = img.height;
  tex.channels = img.component;
  tex.pixels = img.image;
  tex.srgb = srgb;
  tex.lookup = Texture::Lookup::standard;
  if (t.sampler >= 0) {
    if (size_t(t.sampler) >= model_.samplers.size())
      fail(tw + ".sampler: sampler " + std::to_string(t.sampler) + " does not exist (the file has " +
           std::to_string(model_.samplers.size()) + " samplers)");
    const tinygltf::Sampler& s = model_.samplers[size_t(t.sampler)];
    const std::string sw = idx("samplers", t.sampler);
    tex.wrap_u = wrap(s.wrapS, sw + ".wrapS");
    tex.wrap_v = wrap(s.wrapT, sw + ".wrapT");
    tex.filter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Texture::Filter::nearest : Texture::Filter::linear;
  } else {
    tex.wrap_u = tex.wrap_v = Texture::Wrap::repeat;  // the specification's default sampler
    tex.filter = Texture::Filter::linear;
  }
  scene_.textures.push_back(std::move(tex));
  converted[kind] = int(scene_.textures.size()) - 1;
  return converted[kind];
}

// The Scene texture rayform's extras name by glTF texture `ti`: the one
// already read (as colour, else as data), else a new colour texture.
int GltfReader::texture_for_extras(int ti) {
  if (ti >= 0 && size_t(ti) < textures_.size() && textures_[size_t(ti)][1] == -2 && textures_[size_t(ti)][0] != -2)
    return textures_[size_t(ti)][0];
  return texture(ti, true, idx("textures", ti));
}

// The image texture `t` (named `tw`) is drawn with: EXT_texture_webp's
// source when it decoded, else the core `source`; KHR_texture_basisu's
// KTX2 image cannot be decoded, so its core `source` stands in for it, and
// without one the texture is an error. -1: no source at all.
int GltfReader::texture_source(const tinygltf::Texture& t, const std::string& tw) {
  auto image_index = [&](int i, const std::string& where) {
    if (i < 0 || size_t(i) >= model_.images.size())
      fail(where + ": image " + std::to_string(i) + " does not exist (the file has " +
           std::to_string(model_.images.size()) + " images)");
    return i;
  };
  auto extension_source = [&](const char* name) -> int {
    auto it = t.extensions.find(name);
    if (it == t.extensions.end()) return -2;
    const std::string ew = tw + ".extensions." + name;
    if (!it->second.IsObject() || !it->second.Has("source") || !it->second.Get("source").IsNumber())
      fail(ew + ": expected an object with a \"source\" image index");
    return image_index(it->second.Get("source").GetNumberAsInt(), ew + ".source");
  };
  if (t.source >= 0) image_index(t.source, tw + ".source");
  const int webp = extension_source("EXT_texture_webp");
  if (webp >= 0) {
    if (!model_.images[size_t(webp)].image.empty()) {
      use_extension("EXT_texture_webp");
      return webp;
    }
    if (t.source < 0)
      fail(tw + ".extensions.EXT_texture_webp: " + idx("images", webp) +
           " does not decode as WebP and the texture has no PNG/JPEG fallback source");
  }
  const int basisu = extension_source("KHR_texture_basisu");
  if (basisu >= 0 || (t.source >= 0 && ktx2_images_.count(t.source))) {
    if (t.source < 0 || ktx2_images_.count(t.source))
      fail(tw + (basisu >= 0 ? ".extensions.KHR_texture_basisu" : ".source") +
           ": KTX2 / Basis Universal images cannot be decoded (no decoder is available) and the texture has no "
           "PNG/JPEG fallback source");
    use_extension("KHR_texture_basisu", ExtensionUse::Support::approximated,
                  "KTX2 images not decoded: their PNG/JPEG fallback sources are drawn");
  }
  return t.source;
}

Texture::Wrap GltfReader::wrap(int mode, const std::string& where) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return Texture::Wrap::repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Texture::Wrap::clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Texture::Wrap::mirror;
  }
  warn(where + ": unknown wrap mode " + std::to_string(mode) + "; using REPEAT");
  return Texture::Wrap::repeat;
}

// Scene material for glTF material gi (-1: the specification's default
// material): gltf_material.h's factors and every texture slot.
int GltfReader::material(int gi, const std::string& where) {
  if (gi == -1) {
    if (default_material_ == invalid) {
      scene_.materials.push_back(gltf_default_material());
      default_material_ = int(scene_.materials.size()) - 1;
    }
    return default_material_;
  }
  if (gi < 0 || size_t(gi) >= model_.materials.size())
    fail(where + ": material " + std::to_string(gi) + " does not exist (the file has " +
         std::to_string(model_.materials.size()) + " materials)");
  if (materials_[size_t(gi)] != invalid) return materials_[size_t(gi)];
  const tinygltf::Material& gm = model_.materials[size_t(gi)];
  const std::string mw = idx("materials", gi);
  Material m = gltf_material_factors(gm, path_, mw, extensions_);
  if (gm.alphaMode != "OPAQUE" && gm.alphaMode != "MASK" && gm.alphaMode != "BLEND" && !gm.alphaMode.empty())
    warn(mw + ".alphaMode: unknown mode '" + gm.alphaMode + "'; drawn OPAQUE");
  read_texture_slots(gm, mw, m.pbr);
  // The Phong fields' albedo (gltf_material.h): the base colour texture.
  m.diffuse_texture = m.pbr.base_color_texture.texture;
  m.uv_transform = m.pbr.base_color_texture.transform;
  scene_.materials.push_back(std::move(m));
  materials_[size_t(gi)] = int(scene_.materials.size()) - 1;
  return materials_[size_t(gi)];
}

}  // namespace rayform::gltf_detail
