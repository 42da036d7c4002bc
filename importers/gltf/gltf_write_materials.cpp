// The glTF writer's materials and textures (GltfWriter, gltf_writer_internal.h):
// Phong materials as metallic-roughness (gltf_material.h) with the Phong
// values in extras, an untextured copy for shapes without uvs, textures as
// PNG or JPEG images (beside the file or in its buffer) with their samplers.
#include "rayform/importers/gltf/gltf_writer_internal.h"
#include "rayform/importers/gltf/gltf_material.h"
#include "rayform/base/error.h"
#include "rayform/base/file_extension.h"
#include "rayform/importers/text_format.h"
#include "rayform/importers/texture_files.h"

#include <algorithm>
#include <cmath>

namespace rayform::gltf_detail {

int GltfWriter::add_sampler(const Texture& t) {
  auto wrap = [](Texture::Wrap w) {
    switch (w) {
      case Texture::Wrap::clamp: return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
      case Texture::Wrap::mirror: return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
      default: return TINYGLTF_TEXTURE_WRAP_REPEAT;
    }
  };
  tinygltf::Sampler s;
  s.wrapS = wrap(t.wrap_u);
  s.wrapT = wrap(t.wrap_v);
  s.magFilter = t.filter == Texture::Filter::nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
  s.minFilter = t.filter == Texture::Filter::nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST
                                                     : TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  auto key = std::make_tuple(s.wrapS, s.wrapT, s.magFilter);
  auto it = samplers_.find(key);
  if (it != samplers_.end()) return it->second;
  model_.samplers.push_back(s);
  int index = int(model_.samplers.size()) - 1;
  samplers_[key] = index;
  return index;
}

// glTF texture of Scene texture ti (written once).
int GltfWriter::add_texture(int ti) {
  if (ti < 0 || ti >= int(scene_.textures.size())) return -1;
  auto it = textures_.find(ti);
  if (it != textures_.end()) return it->second;
  const Texture& t = scene_.textures[size_t(ti)];
  std::string ext;
  std::vector<uint8_t> bytes;
  std::string trailing;
  try {
    bytes = texture_file(t, {"png", "jpg"}, &ext, &trailing);
    if (!trailing.empty()) context_.note(std::string("texture '") + t.name + "': " + trailing);
  } catch (const Error& e) {
    context_.note(std::string("texture '") + t.name + "' cannot be read (" + e.what() +
                  "); materials using it are untextured");
    textures_[ti] = -1;
    return -1;
  }
  if (!t.path.empty()) {
    const std::string src = lower_extension(t.path);
    if (src != ".png" && src != ".jpg" && src != ".jpeg") converted_.insert(t.name);
  }
  tinygltf::Image img;
  std::string base = texture_base_name(t);
  img.name = base;
  img.mimeType = ext == "jpg" ? "image/jpeg" : "image/png";
  if (options_.binary || options_.embed) {
    img.bufferView = add_view(bytes.data(), bytes.size(), 0);
    // tinygltf writes "target" only for the two buffer targets: none here.
  } else {
    std::string file = safe_file_name(context_.stem + "_" + base) + "." + ext;
    for (int k = 2; used_files_.count(file); ++k)
      file = safe_file_name(context_.stem + "_" + base + "_" + std::to_string(k)) + "." + ext;
    used_files_.insert(file);
    img.uri = side_uri(file);
    context_.out.add(context_.out.side_path(file), std::move(bytes));
  }
  model_.images.push_back(std::move(img));
  tinygltf::Texture gt;
  gt.name = t.name;
  gt.source = int(model_.images.size()) - 1;
  gt.sampler = add_sampler(t);
  Value::Object ex;
  if (t.lookup == Texture::Lookup::course) ex["lookup"] = Value(std::string("course"));
  // glTF readers take every texture but those of data slots as sRGB.
  if (!t.srgb && !data_textures_.count(ti)) ex["srgb"] = Value(false);
  if (!ex.empty()) {
    gt.extras = rayform_extras(std::move(ex));
    raw_textures_.insert(t.name);
  }
  model_.textures.push_back(std::move(gt));
  int index = int(model_.textures.size()) - 1;
  textures_[ti] = index;
  return index;
}

// glTF material of Scene material mi; `textured` false: the copy for
// primitives without uvs (glTF requires TEXCOORD_0 wherever a material has a
// texture), which shows the diffuse colour as the renderer does without uvs.
tinygltf::Material GltfWriter::make_material(int mi, bool textured) {
  const Material& m = scene_.materials[size_t(mi)];
  if (m.model == Material::Model::metallic_roughness) return make_pbr_material(mi, textured);
  tinygltf::Material gm;
  gm.name = textured ? m.name : m.name + " (no uvs)";
  const int tex = textured ? add_texture(m.diffuse_texture) : -1;
  // A course texture replaces the colour: base colour 1 x texel.
  const vec3 base = tex >= 0 && !m.texture_modulates ? vec3(1.f) : m.diffuse;
  PbrValues pbr = phong_to_pbr(base, m.specular, m.shininess);
  if (glm::any(glm::greaterThan(m.diffuse, vec3(1.f))) || glm::any(glm::lessThan(m.diffuse, vec3(0.f))))
    clamped_.insert(m.name);
  gm.pbrMetallicRoughness.baseColorFactor = nice_vector({pbr.base.r, pbr.base.g, pbr.base.b, pbr.base.a});
  gm.pbrMetallicRoughness.metallicFactor = nice(pbr.metallic);
  gm.pbrMetallicRoughness.roughnessFactor = nice(pbr.roughness);
  if (tex >= 0) {
    gm.pbrMetallicRoughness.baseColorTexture.index = tex;
    if (!m.uv_transform.is_identity())
      gm.pbrMetallicRoughness.baseColorTexture.extensions["KHR_texture_transform"] = texture_transform(m.uv_transform);
  }
  if (m.emission != vec3(0.f)) {
    float peak = std::max({m.emission.r, m.emission.g, m.emission.b});
    vec3 e = m.emission;
    if (peak > 1.f) {
      e /= peak;
      gm.extensions["KHR_materials_emissive_strength"] = Value(Value::Object{{"emissiveStrength", num(peak)}});
      use_extension("KHR_materials_emissive_strength");
    }
    e = glm::clamp(e, vec3(0.f), vec3(1.f));
    gm.emissiveFactor = nice_vector({e.r, e.g, e.b});
  }
  if (m.alpha_cutoff >= 0.f) {
    gm.alphaMode = "MASK";
    gm.alphaCutoff = nice(std::min(m.alpha_cutoff, 1.f));
  }
  gm.doubleSided = m.double_sided;
  if (m.unlit) {
    gm.extensions["KHR_materials_unlit"] = Value(Value::Object{});
    use_extension("KHR_materials_unlit");
  }

  Value::Object ex;
  ex["phong"] = Value(Value::Object{
      {"diffuse", vec_value(m.diffuse)}, {"specular", vec_value(m.specular)}, {"shininess", num(m.shininess)}});
  ex["texture_modulates"] = Value(m.texture_modulates);
  ex["two_sided_lighting"] = Value(m.two_sided_lighting);
  if (m.refraction_index != 0.f) ex["refraction_index"] = num(m.refraction_index);
  if (!m.specular_highlight) ex["specular_highlight"] = Value(false);
  if (!m.back_faces_cast_shadows) ex["back_faces_cast_shadows"] = Value(false);
  if (m.noise.enabled)
    ex["noise"] = Value(Value::Object{{"color1", vec_value(m.noise.color1)},
                                      {"color2", vec_value(m.noise.color2)},
                                      {"octaves", Value(m.noise.octaves)},
                                      {"frequency", num(m.noise.frequency)},
                                      {"amplitude", num(m.noise.amplitude)}});
  if (m.emission != vec3(0.f)) ex["emission"] = vec_value(m.emission);
  if (m.alpha_cutoff >= 0.f) ex["alpha_cutoff"] = num(m.alpha_cutoff);
  if (m.bump_texture != invalid) {
    int bt = add_texture(m.bump_texture);
    if (bt >= 0) ex["bump_texture"] = Value(bt);
    if (textured) ++bump_maps_;
  }
  if (m.refraction_index != 0.f && textured) ++refractive_;
  // What was written, so that the reader can tell an edited material.
  ex["pbr"] = Value(Value::Object{{"base", Value(Value::Array{Value(gm.pbrMetallicRoughness.baseColorFactor[0]),
                                                              Value(gm.pbrMetallicRoughness.baseColorFactor[1]),
                                                              Value(gm.pbrMetallicRoughness.baseColorFactor[2]),
                                                              Value(gm.pbrMetallicRoughness.baseColorFactor[3])})},
                                  {"metallic", Value(gm.pbrMetallicRoughness.metallicFactor)},
                                  {"roughness", Value(gm.pbrMetallicRoughness.roughnessFactor)}});
  if (!textured) ex["variant_of"] = Value(mi);
  gm.extras = rayform_extras(std::move(ex));
  uv_sets_needed_.push_back(tex >= 0 ? uv_set_0 : 0);
  return gm;
}

// KHR_texture_transform of a Scene uv transform (in glTF's uv convention).
Value GltfWriter::texture_transform(const UvTransform& transform) {
  const GltfUvTransform t = scene_uv_transform_to_gltf(transform);
  Value::Object tt;
  tt["offset"] = Value(Value::Array{num(t.offset.x), num(t.offset.y)});
  tt["rotation"] = num(t.rotation);
  tt["scale"] = Value(Value::Array{num(t.scale.x), num(t.scale.y)});
  use_extension("KHR_texture_transform");
  return Value(std::move(tt));
}

// A glTF textureInfo object ({} when the slot has no texture or `textured`
// is false): index, texCoord, KHR_texture_transform; the slot's uv set is
// added to `uv_sets`.
Value::Object GltfWriter::texture_object(const TextureSlot& slot, bool textured, int* uv_sets) {
  Value::Object o;
  const int tex = textured && slot.used() ? add_texture(slot.texture) : -1;
  if (tex < 0) return o;
  o["index"] = Value(tex);
  if (slot.texcoord != 0) o["texCoord"] = Value(slot.texcoord);
  if (!slot.transform.is_identity())
    o["extensions"] = Value(Value::Object{{"KHR_texture_transform", texture_transform(slot.transform)}});
  *uv_sets |= slot.texcoord == 0 ? uv_set_0 : uv_set_1;
  return o;
}

namespace {

// The textureInfo object `o` (texture_object) into tinygltf's TextureInfo types.
template <class Info>
void set_info(const Value::Object& o, Info& info) {
  if (o.empty()) return;
  info.index = o.at("index").GetNumberAsInt();
  if (auto it = o.find("texCoord"); it != o.end()) info.texCoord = it->second.GetNumberAsInt();
  if (auto it = o.find("extensions"); it != o.end())
    info.extensions["KHR_texture_transform"] = it->second.Get("KHR_texture_transform");
}

vec3 clamp01(vec3 v) { return glm::clamp(v, vec3(0.f), vec3(1.f)); }

}  // namespace

// glTF material of a metallic-roughness Scene material: every PbrMaterial
// field, extensions where a field differs from its default; no extras but
// `variant_of` on the copy without textures (`textured` false).
tinygltf::Material GltfWriter::make_pbr_material(int mi, bool textured) {
  const Material& m = scene_.materials[size_t(mi)];
  const PbrMaterial& p = m.pbr;
  const PbrMaterial d;
  tinygltf::Material gm;
  gm.name = textured ? m.name : m.name + " (no uvs)";
  int uv_sets = 0;
  auto slot = [&](const TextureSlot& s) { return texture_object(s, textured, &uv_sets); };
  tinygltf::PbrMetallicRoughness& pmr = gm.pbrMetallicRoughness;
  pmr.baseColorFactor = nice_vector({p.base_color.r, p.base_color.g, p.base_color.b, p.base_color.a});
  pmr.metallicFactor = nice(p.metallic);
  pmr.roughnessFactor = nice(p.roughness);
  set_info(slot(p.base_color_texture), pmr.baseColorTexture);
  set_info(slot(p.metallic_roughness_texture), pmr.metallicRoughnessTexture);
  set_info(slot(p.normal_texture), gm.normalTexture);
  if (gm.normalTexture.index >= 0) gm.normalTexture.scale = nice(p.normal_scale);
  set_info(slot(p.occlusion_texture), gm.occlusionTexture);
  if (gm.occlusionTexture.index >= 0) gm.occlusionTexture.strength = nice(p.occlusion_strength);
  set_info(slot(p.emissive_texture), gm.emissiveTexture);
  // emissiveFactor holds [0, 1]: a brighter colour goes into the strength.
  const float peak = std::max({p.emissive.r, p.emissive.g, p.emissive.b});
  const vec3 emissive = peak > 1.f ? p.emissive / peak : p.emissive;
  const float strength = peak > 1.f ? p.emissive_strength * peak : p.emissive_strength;
  if (emissive != vec3(0.f)) gm.emissiveFactor = nice_vector({emissive.r, emissive.g, emissive.b});
  if (strength != d.emissive_strength && emissive != vec3(0.f)) {
    gm.extensions["KHR_materials_emissive_strength"] = Value(Value::Object{{"emissiveStrength", num(strength)}});
    use_extension("KHR_materials_emissive_strength");
  }
  switch (p.alpha_mode) {
    case PbrMaterial::AlphaMode::opaque: gm.alphaMode = "OPAQUE"; break;
    case PbrMaterial::AlphaMode::mask:
      gm.alphaMode = "MASK";
      gm.alphaCutoff = nice(p.alpha_cutoff);
      break;
    case PbrMaterial::AlphaMode::blend: gm.alphaMode = "BLEND"; break;
  }
  gm.doubleSided = m.double_sided;
  auto extension = [&](const char* name, Value::Object o) {
    gm.extensions[name] = Value(std::move(o));
    use_extension(name);
  };
  if (m.unlit) extension("KHR_materials_unlit", {});
  if (p.ior != d.ior) extension("KHR_materials_ior", {{"ior", num(p.ior)}});
  {
    Value::Object o;
    if (p.specular != d.specular) o["specularFactor"] = num(p.specular);
    if (p.specular_color != d.specular_color) o["specularColorFactor"] = vec_value(p.specular_color);
    if (Value::Object t = slot(p.specular_texture); !t.empty()) o["specularTexture"] = Value(std::move(t));
    if (Value::Object t = slot(p.specular_color_texture); !t.empty()) o["specularColorTexture"] = Value(std::move(t));
    if (!o.empty()) extension("KHR_materials_specular", std::move(o));
  }
  {
    Value::Object o;
    if (p.transmission != d.transmission) o["transmissionFactor"] = num(p.transmission);
    if (Value::Object t = slot(p.transmission_texture); !t.empty()) o["transmissionTexture"] = Value(std::move(t));
    if (!o.empty()) extension("KHR_materials_transmission", std::move(o));
  }
  {
    Value::Object o;
    if (p.thickness != d.thickness) o["thicknessFactor"] = num(p.thickness);
    if (Value::Object t = slot(p.thickness_texture); !t.empty()) o["thicknessTexture"] = Value(std::move(t));
    if (p.attenuation_color != d.attenuation_color) o["attenuationColor"] = vec_value(clamp01(p.attenuation_color));
    // An infinite distance (no attenuation) is the default; JSON has no infinity.
    if (std::isfinite(p.attenuation_distance)) o["attenuationDistance"] = num(p.attenuation_distance);
    if (!o.empty()) extension("KHR_materials_volume", std::move(o));
  }
  {
    Value::Object o;
    if (p.clearcoat != d.clearcoat) o["clearcoatFactor"] = num(p.clearcoat);
    if (Value::Object t = slot(p.clearcoat_texture); !t.empty()) o["clearcoatTexture"] = Value(std::move(t));
    if (p.clearcoat_roughness != d.clearcoat_roughness) o["clearcoatRoughnessFactor"] = num(p.clearcoat_roughness);
    if (Value::Object t = slot(p.clearcoat_roughness_texture); !t.empty())
      o["clearcoatRoughnessTexture"] = Value(std::move(t));
    if (Value::Object t = slot(p.clearcoat_normal_texture); !t.empty()) {
      t["scale"] = num(p.clearcoat_normal_scale);
      o["clearcoatNormalTexture"] = Value(std::move(t));
    }
    if (!o.empty()) extension("KHR_materials_clearcoat", std::move(o));
  }
  {
    Value::Object o;
    if (p.sheen_color != d.sheen_color) o["sheenColorFactor"] = vec_value(clamp01(p.sheen_color));
    if (Value::Object t = slot(p.sheen_color_texture); !t.empty()) o["sheenColorTexture"] = Value(std::move(t));
    if (p.sheen_roughness != d.sheen_roughness) o["sheenRoughnessFactor"] = num(p.sheen_roughness);
    if (Value::Object t = slot(p.sheen_roughness_texture); !t.empty()) o["sheenRoughnessTexture"] = Value(std::move(t));
    if (!o.empty()) extension("KHR_materials_sheen", std::move(o));
  }
  if (!textured) gm.extras = rayform_extras({{"variant_of", Value(mi)}});
  uv_sets_needed_.push_back(uv_sets);
  return gm;
}

void GltfWriter::add_material(int mi) { model_.materials.push_back(make_material(mi, true)); }

// Scene textures used only by the data slots of metallic-roughness
// materials (read linear by glTF readers, so no "srgb" extra).
void GltfWriter::find_data_textures() {
  std::set<int> colour;
  for (const Material& m : scene_.materials) {
    if (m.model != Material::Model::metallic_roughness) {
      colour.insert(m.diffuse_texture);
      colour.insert(m.bump_texture);
      continue;
    }
    const PbrMaterial& p = m.pbr;
    for (const TextureSlot* s :
         {&p.base_color_texture, &p.emissive_texture, &p.specular_color_texture, &p.sheen_color_texture})
      colour.insert(s->texture);
    for (const TextureSlot* s :
         {&p.metallic_roughness_texture, &p.normal_texture, &p.occlusion_texture, &p.specular_texture,
          &p.transmission_texture, &p.thickness_texture, &p.clearcoat_texture, &p.clearcoat_roughness_texture,
          &p.clearcoat_normal_texture, &p.sheen_roughness_texture})
      if (s->used()) data_textures_.insert(s->texture);
  }
  for (int f : scene_.background.cube_map) colour.insert(f);
  for (int t : colour) data_textures_.erase(t);
}

// The untextured copy of glTF material gi (made once).
int GltfWriter::untextured(int gi) {
  auto it = untextured_.find(gi);
  if (it != untextured_.end()) return it->second;
  model_.materials.push_back(make_material(gi, false));
  ++untextured_uses_;
  return untextured_[gi] = int(model_.materials.size()) - 1;
}

void GltfWriter::use_extension(const std::string& e) {
  if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), e) == model_.extensionsUsed.end())
    model_.extensionsUsed.push_back(e);
}

}  // namespace rayform::gltf_detail
