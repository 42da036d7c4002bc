#include "rayform/importers/gltf/gltf_material.h"

#include "rayform/base/error.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>

namespace rayform {

namespace {

constexpr float default_f0 = gltf_dielectric_f0;
constexpr float default_ior = 1.5f;
// The range of Phong exponents the mapping produces.
constexpr float min_shininess = 1.f, max_shininess = 1024.f;

float shininess_of_roughness(float roughness) {
  const float alpha2 = roughness * roughness * roughness * roughness;
  const float n = alpha2 > 0.f ? (2.f / alpha2 - 2.f) / 4.f : max_shininess;
  return std::clamp(n, min_shininess, max_shininess);
}

// Reads the members of one extension object, each failing with its JSON path.
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
  bool has(const char* key) const { return v_.Has(key); }

 private:
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw Error(file_ + ": " + where_ + (key.empty() ? "" : "." + key) + ": " + what);
  }
  const tinygltf::Value& v_;
  std::string file_, where_;
};

void record(std::vector<ExtensionUse>& uses, const std::string& name, ExtensionUse::Support support,
            const std::string& detail) {
  for (const ExtensionUse& u : uses)
    if (u.name == name) return;
  uses.push_back(ExtensionUse{name, support, detail});
}

}  // namespace

void gltf_material_to_phong(const tinygltf::Material& gm, const std::string& file, const std::string& where,
                            Material& m, std::vector<ExtensionUse>& extensions) {
  using Support = ExtensionUse::Support;
  const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() != 4)
    throw Error(file + ": " + where + ".pbrMetallicRoughness.baseColorFactor: expected 4 numbers, found " +
                std::to_string(pbr.baseColorFactor.size()));
  const vec4 base(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
  if (!is_finite(vec3(base)) || !std::isfinite(base.a))
    throw Error(file + ": " + where + ".pbrMetallicRoughness.baseColorFactor: not finite");
  auto ext = [&](const char* name) -> const tinygltf::Value* {
    auto it = gm.extensions.find(name);
    return it == gm.extensions.end() ? nullptr : &it->second;
  };
  auto ext_where = [&](const char* name) { return where + ".extensions." + name; };

  vec3 diffuse = vec3(base);
  float metallic = float(pbr.metallicFactor), roughness = float(pbr.roughnessFactor);
  vec3 f0_dielectric(default_f0);
  float ior = default_ior;
  if (const tinygltf::Value* v = ext("KHR_materials_ior")) {
    // ior 0 is allowed by the extension (a perfect reflector); keep it out of
    // the refraction code, which needs ior >= 1.
    ExtensionReader r(*v, file, ext_where("KHR_materials_ior"));
    ior = r.number("ior", default_ior, 0.f, 1e6f);
    if (ior != 0.f && ior < 1.f)
      throw Error(file + ": " + ext_where("KHR_materials_ior") + ".ior: " + std::to_string(ior) +
                  " is neither 0 nor a number >= 1");
    const float f = ior == 0.f ? 1.f : (ior - 1.f) / (ior + 1.f);
    f0_dielectric = vec3(f * f);
    if (ior == 0.f) ior = default_ior;
    record(extensions, "KHR_materials_ior", Support::read, "");
  }
  if (const tinygltf::Value* v = ext("KHR_materials_specular")) {
    ExtensionReader r(*v, file, ext_where("KHR_materials_specular"));
    const float factor = r.number("specularFactor", 1.f, 0.f, 1.f);
    const vec3 color = vec3(r.numbers("specularColorFactor", 3, vec4(1.f)));
    f0_dielectric = glm::min(f0_dielectric * color, vec3(1.f)) * factor;
    record(extensions, "KHR_materials_specular", Support::approximated,
           "scales the dielectric reflectance; its textures are not sampled");
  }
  if (const tinygltf::Value* v = ext("KHR_materials_pbrSpecularGlossiness")) {
    ExtensionReader r(*v, file, ext_where("KHR_materials_pbrSpecularGlossiness"));
    const vec4 d = r.numbers("diffuseFactor", 4, vec4(1.f));
    diffuse = vec3(d);
    const vec3 specular = vec3(r.numbers("specularFactor", 3, vec4(1.f)));
    const float glossiness = r.number("glossinessFactor", 1.f, 0.f, 1.f);
    m.diffuse = diffuse;
    pbr_to_phong(specular, 1.f, 1.f - glossiness, specular, m);  // F0 = specular
    record(extensions, "KHR_materials_pbrSpecularGlossiness", Support::approximated,
           "diffuse, specular and glossiness factors and the diffuse texture; other textures are not sampled");
  } else {
    m.diffuse = diffuse;
    pbr_to_phong(diffuse, metallic, roughness, f0_dielectric, m);
  }

  if (const tinygltf::Value* v = ext("KHR_materials_clearcoat")) {
    ExtensionReader r(*v, file, ext_where("KHR_materials_clearcoat"));
    const float coat = r.number("clearcoatFactor", 0.f, 0.f, 1.f);
    const float coat_roughness = r.number("clearcoatRoughnessFactor", 0.f, 0.f, 1.f);
    if (coat > 0.f) {
      const float smooth = 1.f - coat_roughness;
      m.specular += vec3(coat * default_f0 * smooth * smooth);
      m.shininess = std::max(m.shininess, shininess_of_roughness(coat_roughness));
    }
    record(extensions, "KHR_materials_clearcoat", Support::approximated,
           "the coat's lobe is folded into the one Phong lobe");
  }
  if (const tinygltf::Value* v = ext("KHR_materials_transmission")) {
    ExtensionReader r(*v, file, ext_where("KHR_materials_transmission"));
    const float transmission = r.number("transmissionFactor", 0.f, 0.f, 1.f);
    if (transmission > 0.f) {
      m.refraction_index = ior;
      m.specular = glm::max(m.specular, transmission * glm::clamp(vec3(base), vec3(0.f), vec3(1.f)));
      m.diffuse *= 1.f - transmission;
    }
    record(extensions, "KHR_materials_transmission", Support::approximated,
           "refraction weighted by the specular colour (seen with --bounces 1 or more); no volume absorption");
  }

  if (gm.emissiveFactor.size() == 3)
    m.emission = vec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]);
  else if (!gm.emissiveFactor.empty())
    throw Error(file + ": " + where + ".emissiveFactor: expected 3 numbers, found " +
                std::to_string(gm.emissiveFactor.size()));
  if (const tinygltf::Value* v = ext("KHR_materials_emissive_strength")) {
    ExtensionReader r(*v, file, ext_where("KHR_materials_emissive_strength"));
    m.emission *= r.number("emissiveStrength", 1.f, 0.f, 1e30f);
    record(extensions, "KHR_materials_emissive_strength", Support::read, "");
  }
  if (!is_finite(m.emission)) throw Error(file + ": " + where + ".emissiveFactor: not finite");
  if (ext("KHR_materials_unlit")) {
    m.unlit = true;
    record(extensions, "KHR_materials_unlit", Support::read, "");
  }
  static const char* const ignored[] = {"KHR_materials_sheen",       "KHR_materials_volume",
                                        "KHR_materials_iridescence", "KHR_materials_anisotropy",
                                        "KHR_materials_dispersion",  "KHR_materials_diffuse_transmission"};
  for (const char* name : ignored)
    if (ext(name)) record(extensions, name, Support::ignored, "no Phong equivalent");
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
