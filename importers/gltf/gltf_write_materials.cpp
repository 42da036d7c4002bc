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
  try {
    bytes = texture_file(t, {"png", "jpg"}, &ext);
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
  if (!t.srgb) ex["srgb"] = Value(false);
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
    if (!m.uv_transform.is_identity()) {
      const GltfUvTransform t = scene_uv_transform_to_gltf(m.uv_transform);
      Value::Object tt;
      tt["offset"] = Value(Value::Array{num(t.offset.x), num(t.offset.y)});
      tt["rotation"] = num(t.rotation);
      tt["scale"] = Value(Value::Array{num(t.scale.x), num(t.scale.y)});
      gm.pbrMetallicRoughness.baseColorTexture.extensions["KHR_texture_transform"] = Value(std::move(tt));
      use_extension("KHR_texture_transform");
    }
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
  return gm;
}

void GltfWriter::add_material(int mi) { model_.materials.push_back(make_material(mi, true)); }

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
