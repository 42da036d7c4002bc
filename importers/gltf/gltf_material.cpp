#include "rayform/importers/gltf/gltf_material.h"

#include "rayform/base/error.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>

#include <cmath>
#include <limits>
#include <memory>

namespace rayform {

namespace {

// The largest finite float: the upper bound of values the specification
// leaves unbounded (emissive strength, thickness, attenuation distance).
constexpr float unbounded = std::numeric_limits<float>::max();

// Reads the members of one JSON object (an extension, a texture reference),
// each failing with its JSON path.
class ExtensionReader {
 public:
  ExtensionReader(const tinygltf::Value& v, std::string file, std::string where)
      : v_(v), file_(std::move(file)), where_(std::move(where)) {
    if (!v_.IsObject()) fail("", "expected an object");
  }
  // A finite number, `fallback` when absent; outside [lo, hi] is an error.
  float number(const char* key, float fallback, float lo, float hi) const {
    if (!v_.Has(key)) return fallback;
    const tinygltf::Value& n = v_.Get(key);
    const double d = n.IsNumber() ? n.GetNumberAsDouble() : std::nan("");
    if (!(d >= lo && d <= hi)) fail(key, "expected a number from " + std::to_string(lo) + " to " + std::to_string(hi));
    return float(d);
  }
  // `count` finite numbers >= 0, `fallback` when absent.
  vec4 numbers(const char* key, int count, vec4 fallback) const {
    if (!v_.Has(key)) return fallback;
    const tinygltf::Value& a = v_.Get(key);
    if (!a.IsArray() || a.ArrayLen() != size_t(count)) fail(key, "expected " + std::to_string(count) + " numbers");
    vec4 out = fallback;
    for (int i = 0; i < count; ++i) {
      const tinygltf::Value& e = a.Get(i);
      const double d = e.IsNumber() ? e.GetNumberAsDouble() : std::nan("");
      if (!(d >= 0.0) || !std::isfinite(d)) fail(key, "expected finite numbers >= 0");
      out[i] = float(d);
    }
    return out;
  }
  // Member `key` read by its own reader, nullptr when absent.
  std::unique_ptr<ExtensionReader> member(const char* key) const {
    if (!v_.Has(key)) return nullptr;
    return std::make_unique<ExtensionReader>(v_.Get(key), file_, where_ + "." + key);
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw Error(file_ + ": " + where_ + (key.empty() ? "" : "." + key) + ": " + what);
  }

 private:
  const tinygltf::Value& v_;
  std::string file_, where_;
};

void record(std::vector<ExtensionUse>& uses, const std::string& name, ExtensionUse::Support support,
            const std::string& detail) {
  for (const ExtensionUse& u : uses)
    if (u.name == name) return;
  uses.push_back(ExtensionUse{name, support, detail});
}

// A core factor tinygltf parsed as a double, checked to lie in [lo, hi].
float core_factor(double value, float lo, float hi, const std::string& file, const std::string& path) {
  if (!(value >= lo && value <= hi))
    throw Error(file + ": " + path + ": " + std::to_string(value) + " is not a number from " + std::to_string(lo) +
                " to " + std::to_string(hi));
  return float(value);
}

// A core array of `count` finite numbers >= 0 (baseColorFactor, emissiveFactor;
// the specification keeps them within [0, 1], but values above 1, e.g. an
// emissive factor from before KHR_materials_emissive_strength, mean what they
// say and are kept).
vec4 core_color(const std::vector<double>& v, size_t count, vec4 fallback, const std::string& file,
                const std::string& path) {
  if (v.empty()) return fallback;
  if (v.size() != count)
    throw Error(file + ": " + path + ": expected " + std::to_string(count) + " numbers, found " +
                std::to_string(v.size()));
  vec4 out = fallback;
  for (size_t i = 0; i < count; ++i) {
    if (!(v[i] >= 0.0) || !std::isfinite(v[i]))
      throw Error(file + ": " + path + "[" + std::to_string(i) + "]: " + std::to_string(v[i]) +
                  " is not a finite number >= 0");
    out[int(i)] = float(v[i]);
  }
  return out;
}

}  // namespace

Material gltf_default_material() {
  Material m;
  m.name = "default";
  m.model = Material::Model::metallic_roughness;
  m.texture_modulates = true;
  m.double_sided = false;
  m.two_sided_lighting = false;
  m.pbr = PbrMaterial{};  // base colour 1, metallic 1, roughness 1: the specification's defaults
  m.diffuse = vec3(m.pbr.base_color);
  return m;
}

Material gltf_material_factors(const tinygltf::Material& gm, const std::string& file, const std::string& where,
                               std::vector<ExtensionUse>& extensions) {
  using Support = ExtensionUse::Support;
  Material m;
  m.name = gm.name.empty() ? where : gm.name;
  m.model = Material::Model::metallic_roughness;
  m.texture_modulates = true;
  PbrMaterial& p = m.pbr;
  const std::string pw = where + ".pbrMetallicRoughness";
  const tinygltf::PbrMetallicRoughness& core = gm.pbrMetallicRoughness;
  p.base_color = core_color(core.baseColorFactor, 4, vec4(1.f), file, pw + ".baseColorFactor");
  p.metallic = core_factor(core.metallicFactor, 0.f, 1.f, file, pw + ".metallicFactor");
  p.roughness = core_factor(core.roughnessFactor, 0.f, 1.f, file, pw + ".roughnessFactor");
  p.normal_scale = core_factor(gm.normalTexture.scale, -unbounded, unbounded, file, where + ".normalTexture.scale");
  p.occlusion_strength =
      core_factor(gm.occlusionTexture.strength, 0.f, 1.f, file, where + ".occlusionTexture.strength");
  p.emissive = vec3(core_color(gm.emissiveFactor, 3, vec4(0.f), file, where + ".emissiveFactor"));
  if (gm.alphaMode == "MASK") p.alpha_mode = PbrMaterial::AlphaMode::mask;
  else if (gm.alphaMode == "BLEND") p.alpha_mode = PbrMaterial::AlphaMode::blend;
  // Any other alphaMode is OPAQUE (the reader warns).
  p.alpha_cutoff = core_factor(gm.alphaCutoff, 0.f, unbounded, file, where + ".alphaCutoff");
  m.double_sided = gm.doubleSided;
  m.two_sided_lighting = gm.doubleSided;  // the specification reverses back-face normals

  auto ext = [&](const char* name) -> std::unique_ptr<ExtensionReader> {
    auto it = gm.extensions.find(name);
    if (it == gm.extensions.end()) return nullptr;
    return std::make_unique<ExtensionReader>(it->second, file, where + ".extensions." + name);
  };
  if (auto r = ext("KHR_materials_emissive_strength")) {
    p.emissive_strength = r->number("emissiveStrength", 1.f, 0.f, unbounded);
    record(extensions, "KHR_materials_emissive_strength", Support::read, "");
  }
  if (auto r = ext("KHR_materials_ior")) {
    // 0 is allowed by the extension: a material that reflects as a mirror.
    p.ior = r->number("ior", 1.5f, 0.f, unbounded);
    if (p.ior != 0.f && p.ior < 1.f) r->fail("ior", std::to_string(p.ior) + " is neither 0 nor a number >= 1");
    record(extensions, "KHR_materials_ior", Support::read, "");
  }
  if (auto r = ext("KHR_materials_specular")) {
    p.specular = r->number("specularFactor", 1.f, 0.f, 1.f);
    p.specular_color = vec3(r->numbers("specularColorFactor", 3, vec4(1.f)));
    record(extensions, "KHR_materials_specular", Support::read, "");
  }
  if (auto r = ext("KHR_materials_transmission")) {
    p.transmission = r->number("transmissionFactor", 0.f, 0.f, 1.f);
    record(extensions, "KHR_materials_transmission", Support::read, "");
  }
  if (auto r = ext("KHR_materials_volume")) {
    p.thickness = r->number("thicknessFactor", 0.f, 0.f, unbounded);
    p.attenuation_color = vec3(r->numbers("attenuationColor", 3, vec4(1.f)));
    const float infinite = std::numeric_limits<float>::infinity();
    p.attenuation_distance = r->number("attenuationDistance", infinite, 0.f, unbounded);
    if (p.attenuation_distance == 0.f) r->fail("attenuationDistance", "must be greater than 0");
    record(extensions, "KHR_materials_volume", Support::read, "");
  }
  if (auto r = ext("KHR_materials_clearcoat")) {
    p.clearcoat = r->number("clearcoatFactor", 0.f, 0.f, 1.f);
    p.clearcoat_roughness = r->number("clearcoatRoughnessFactor", 0.f, 0.f, 1.f);
    if (auto n = r->member("clearcoatNormalTexture"))
      p.clearcoat_normal_scale = n->number("scale", 1.f, -unbounded, unbounded);
    record(extensions, "KHR_materials_clearcoat", Support::read, "");
  }
  if (auto r = ext("KHR_materials_sheen")) {
    p.sheen_color = vec3(r->numbers("sheenColorFactor", 3, vec4(0.f)));
    p.sheen_roughness = r->number("sheenRoughnessFactor", 0.f, 0.f, 1.f);
    record(extensions, "KHR_materials_sheen", Support::read, "");
  }
  if (auto r = ext("KHR_materials_pbrSpecularGlossiness")) {
    // F0 = min(gltf_dielectric_f0 specular_color, 1) specular = specularFactor.
    p.base_color = r->numbers("diffuseFactor", 4, vec4(1.f));
    p.specular_color = vec3(r->numbers("specularFactor", 3, vec4(1.f))) / gltf_dielectric_f0;
    p.specular = 1.f;
    p.metallic = 0.f;
    p.roughness = 1.f - r->number("glossinessFactor", 1.f, 0.f, 1.f);
    record(extensions, "KHR_materials_pbrSpecularGlossiness", Support::approximated,
           "as metallic-roughness: base colour = diffuse, metallic 0, roughness = 1 - glossinessFactor, F0 = the "
           "specular colour (KHR_materials_specular's colour = specular / 0.04); the specularGlossinessTexture's rgb "
           "scales F0, its glossiness (alpha) is not used");
  }
  if (ext("KHR_materials_unlit")) {
    m.unlit = true;
    record(extensions, "KHR_materials_unlit", Support::read, "");
  }
  static const char* const ignored[] = {"KHR_materials_iridescence", "KHR_materials_anisotropy",
                                        "KHR_materials_dispersion", "KHR_materials_diffuse_transmission"};
  for (const char* name : ignored)
    if (gm.extensions.count(name))
      record(extensions, name, Support::ignored, "not read: the material is shaded without this layer");
  m.diffuse = vec3(p.base_color);
  return m;
}

const std::vector<GltfMaterialTexture>& gltf_material_textures() {
  static const std::vector<GltfMaterialTexture> t = {
      {"", "baseColorTexture", &PbrMaterial::base_color_texture, true},
      {"", "metallicRoughnessTexture", &PbrMaterial::metallic_roughness_texture, false},
      {"", "normalTexture", &PbrMaterial::normal_texture, false},
      {"", "occlusionTexture", &PbrMaterial::occlusion_texture, false},
      {"", "emissiveTexture", &PbrMaterial::emissive_texture, true},
      {"KHR_materials_specular", "specularTexture", &PbrMaterial::specular_texture, false},
      {"KHR_materials_specular", "specularColorTexture", &PbrMaterial::specular_color_texture, true},
      {"KHR_materials_transmission", "transmissionTexture", &PbrMaterial::transmission_texture, false},
      {"KHR_materials_volume", "thicknessTexture", &PbrMaterial::thickness_texture, false},
      {"KHR_materials_clearcoat", "clearcoatTexture", &PbrMaterial::clearcoat_texture, false},
      {"KHR_materials_clearcoat", "clearcoatRoughnessTexture", &PbrMaterial::clearcoat_roughness_texture, false},
      {"KHR_materials_clearcoat", "clearcoatNormalTexture", &PbrMaterial::clearcoat_normal_texture, false},
      {"KHR_materials_sheen", "sheenColorTexture", &PbrMaterial::sheen_color_texture, true},
      {"KHR_materials_sheen", "sheenRoughnessTexture", &PbrMaterial::sheen_roughness_texture, false},
      // The specular-glossiness workflow's textures (gltf_material.h): its
      // diffuse texture is the base colour's; its rgb, the specular colour,
      // scales F0 as KHR_materials_specular's colour texture does.
      {"KHR_materials_pbrSpecularGlossiness", "diffuseTexture", &PbrMaterial::base_color_texture, true},
      {"KHR_materials_pbrSpecularGlossiness", "specularGlossinessTexture", &PbrMaterial::specular_color_texture, true},
  };
  return t;
}

std::vector<std::pair<const char*, const TextureSlot*>> gltf_named_texture_slots(const PbrMaterial& m) {
  std::vector<std::pair<const char*, const TextureSlot*>> out;
  for (const GltfMaterialTexture& t : gltf_material_textures())
    if (std::string(t.extension) != "KHR_materials_pbrSpecularGlossiness") out.emplace_back(t.key, &(m.*t.slot));
  return out;
}

UvTransform gltf_uv_transform_to_scene(vec2 offset, float rotation, vec2 scale) {
  // glTF: M(x) = o + R(r) S x with R(r) = [[cos r, sin r], [-sin r, cos r]]
  // (rows; the matrix the shader applies, and the one under which the
  // KHR_texture_transform sample model's "Correct" markers line up).
  // Scene uvs are F(x) = (x.u, 1 - x.v) of glTF's, and the sampler reads
  // v = 1 at the top, so the stored transform is M' = F M F:
  //   M'(x) = D R(r) S D x + D (R(r) S e + o) + e,  D = diag(1, -1), e = (0, 1)
  // and D R(r) D = R(-r), S D = D S; R(r) S e = (sin r s.y, cos r s.y).
  UvTransform t;
  t.scale = scale;
  t.rotation = -rotation;
  t.offset = vec2(offset.x + std::sin(rotation) * scale.y, 1.f - offset.y - std::cos(rotation) * scale.y);
  return t;
}

GltfUvTransform scene_uv_transform_to_gltf(const UvTransform& t) {
  GltfUvTransform g;
  g.rotation = -t.rotation;
  g.scale = t.scale;
  g.offset = vec2(t.offset.x - std::sin(g.rotation) * t.scale.y, 1.f - t.offset.y - std::cos(g.rotation) * t.scale.y);
  return g;
}

}  // namespace rayform
