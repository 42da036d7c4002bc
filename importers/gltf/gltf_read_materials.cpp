// The glTF reader's materials and textures (GltfReader,
// gltf_reader_internal.h): glTF materials as Scene (Phong) materials through
// gltf_material.h, base colour textures with their image source (core,
// EXT_texture_webp, KHR_texture_basisu's fallback), sampler and
// KHR_texture_transform.
#include "rayform/importers/gltf/gltf_file_access.h"
#include "rayform/importers/gltf/gltf_material.h"
#include "rayform/importers/gltf/gltf_reader_internal.h"

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

GltfReader::TextureRef GltfReader::texture_ref(const tinygltf::TextureInfo& info, const std::string& where) {
  TextureRef r;
  r.texcoord = info.texCoord;
  if (r.texcoord < 0) fail(where + ".texCoord: " + std::to_string(r.texcoord) + " is negative");
  r.texture = texture(info.index, where);
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
    }
    r.transform = gltf_uv_transform_to_scene(offset, rotation, scale);
  }
  return r;
}

// Scene texture for glTF texture ti (sRGB colour data), or invalid when its
// image could not be loaded (warned about).
int GltfReader::texture(int ti, const std::string& where) {
  if (ti < 0 || size_t(ti) >= model_.textures.size())
    fail(where + ".index: texture " + std::to_string(ti) + " does not exist (the file has " +
         std::to_string(model_.textures.size()) + " textures)");
  if (textures_[size_t(ti)] != -2) return textures_[size_t(ti)];
  textures_[size_t(ti)] = invalid;
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
  tex.srgb = true;
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
  textures_[size_t(ti)] = int(scene_.textures.size()) - 1;
  return textures_[size_t(ti)];
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

// Scene material for glTF material gi (-1: the specification's default material).
int GltfReader::material(int gi, const std::string& where) {
  if (gi == -1) {
    if (default_material_ == invalid) {
      Material m;
      m.name = "default";
      m.texture_modulates = true;
      m.double_sided = false;
      pbr_to_phong(vec3(1.f), 1.f, 1.f, vec3(gltf_dielectric_f0), m);  // base colour 1, metallic 1, roughness 1
      scene_.materials.push_back(m);
      material_texcoord_.push_back(0);
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
  const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
  Material m;
  m.name = gm.name.empty() ? mw : gm.name;
  m.texture_modulates = true;
  gltf_material_to_phong(gm, path_, mw, m, extensions_);
  const float base_alpha = float(pbr.baseColorFactor[3]);
  int texcoord = 0;
  if (pbr.baseColorTexture.index >= 0 || pbr.baseColorTexture.index < -1) {
    TextureRef r = texture_ref(pbr.baseColorTexture, mw + ".pbrMetallicRoughness.baseColorTexture");
    m.diffuse_texture = r.texture;
    texcoord = r.texcoord;
    if (r.texture != invalid) m.uv_transform = r.transform;
  }
  // The older specular-glossiness workflow's diffuse texture plays the base colour's part.
  if (auto sg = gm.extensions.find("KHR_materials_pbrSpecularGlossiness"); sg != gm.extensions.end()) {
    const std::string sw = mw + ".extensions.KHR_materials_pbrSpecularGlossiness.diffuseTexture";
    if (sg->second.IsObject() && sg->second.Has("diffuseTexture")) {
      const tinygltf::Value& dt = sg->second.Get("diffuseTexture");
      if (!dt.IsObject() || !dt.Has("index") || !dt.Get("index").IsNumber())
        fail(sw + ": expected an object with an \"index\"");
      tinygltf::TextureInfo info;
      info.index = dt.Get("index").GetNumberAsInt();
      if (dt.Has("texCoord") && dt.Get("texCoord").IsNumber()) info.texCoord = dt.Get("texCoord").GetNumberAsInt();
      TextureRef r = texture_ref(info, sw);
      m.diffuse_texture = r.texture;
      texcoord = r.texcoord;
    }
  }
  // Cut-outs: the shader compares the texel's alpha with alpha_cutoff, while
  // glTF compares baseColorFactor.a x texel alpha with alphaCutoff; fold the
  // factor into the threshold. (Without a texture a uniform alpha below the
  // cutoff cannot be expressed: such a material stays opaque.)
  auto cutoff_for = [&](float c) { return base_alpha > 0.f ? c / base_alpha : 2.f; };
  if (gm.alphaMode == "MASK") {
    m.alpha_cutoff = cutoff_for(float(gm.alphaCutoff));
  } else if (gm.alphaMode == "BLEND") {
    m.alpha_cutoff = cutoff_for(0.5f);
    warn(mw + ": alphaMode BLEND is drawn as MASK with cutoff 0.5 (no blending in this renderer)");
  } else if (gm.alphaMode != "OPAQUE" && !gm.alphaMode.empty()) {
    warn(mw + ": unknown alphaMode '" + gm.alphaMode + "'; drawn OPAQUE");
  }
  m.double_sided = gm.doubleSided;
  m.two_sided_lighting = gm.doubleSided;  // the specification reverses back-face normals
  if (pbr.metallicRoughnessTexture.index >= 0) unused_textures_.insert("metallicRoughnessTexture");
  if (gm.normalTexture.index >= 0) unused_textures_.insert("normalTexture");
  if (gm.occlusionTexture.index >= 0) unused_textures_.insert("occlusionTexture");
  if (gm.emissiveTexture.index >= 0) unused_textures_.insert("emissiveTexture");
  scene_.materials.push_back(std::move(m));
  material_texcoord_.push_back(texcoord);
  materials_[size_t(gi)] = int(scene_.materials.size()) - 1;
  return materials_[size_t(gi)];
}

}  // namespace rayform::gltf_detail
