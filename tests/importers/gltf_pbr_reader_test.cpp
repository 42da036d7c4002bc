// glTF materials as the file means them (gltf_material.h): every core and
// extension field in Material::pbr, every texture reference a TextureSlot
// (texCoord, KHR_texture_transform), colour textures sRGB and data textures
// linear, the specular-glossiness approximation, bad values as errors naming
// their JSON path, two uv sets, tangents, and what the extension report says.
// Small .glb files built here; a few Khronos samples from ../shared.
#include "rayform/importers/gltf/gltf_reader.h"
#include "rayform/base/error.h"
#include "test_importers.h"
#include "test_glb.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace rayform {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kFloat = 5126;

// 2x2 RGBA PNG: red, green / blue, white with alpha 128.
const char* png_2x2 =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAAE0lEQVR4nGP4z8DwHwyBNAg0AABJSQl4KKDbdwAAAABJRU5ErkJggg==";

// One triangle (positions (0,0,0) (1,0,0) (0,1,0)) on node 0 with
// `attributes` beyond POSITION, material 0 when `materials` has any, written
// as a .glb whose buffer holds the accessors added.
struct PbrDraft {
  json j = json::object();
  std::vector<uint8_t> bin;
  json attributes = json::object();

  PbrDraft() {
    j["asset"] = {{"version", "2.0"}};
    j["buffers"] = json::array({json::object()});
    j["bufferViews"] = json::array();
    j["accessors"] = json::array();
    j["materials"] = json::array();
    attributes["POSITION"] = floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  }
  int floats(const std::vector<float>& v, const char* type, size_t count) {
    while (bin.size() % 4) bin.push_back(0);
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", v.size() * 4}});
    const auto* p = reinterpret_cast<const uint8_t*>(v.data());
    bin.insert(bin.end(), p, p + v.size() * 4);
    j["accessors"].push_back(
        {{"bufferView", j["bufferViews"].size() - 1}, {"componentType", kFloat}, {"count", count}, {"type", type}});
    return int(j["accessors"].size()) - 1;
  }
  // `n` textures, each on the one 2x2 PNG.
  void textures(int n) {
    j["images"] = json::array({{{"uri", std::string("data:image/png;base64,") + png_2x2}}});
    j["textures"] = json::array();
    for (int i = 0; i < n; ++i) j["textures"].push_back({{"source", 0}});
  }
  std::vector<uint8_t> glb() const {
    json out = j;
    json prim = {{"attributes", attributes}};
    if (!j["materials"].empty()) prim["material"] = 0;
    else out.erase("materials");
    out["meshes"] = json::array({{{"primitives", json::array({prim})}}});
    out["nodes"] = json::array({{{"mesh", 0}}});
    out["scenes"] = json::array({{{"nodes", json::array({0})}}});
    out["scene"] = 0;
    out["buffers"][0]["byteLength"] = bin.size();
    return test::make_glb(out.dump(), bin);
  }
};

class GltfPbr : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::temp_dir("gltf-pbr"); }
  void TearDown() override { fs::remove_all(dir_); }
  Scene load(const PbrDraft& d, std::vector<std::string>* warnings = nullptr,
             std::vector<ExtensionUse>* extensions = nullptr) {
    const std::vector<uint8_t> bytes = d.glb();
    const fs::path path = dir_ / "t.glb";
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return read_gltf_scene(path.string(), {}, warnings, extensions);
  }
  // The error of loading `d` without the file name; "" when it loads.
  std::string error(const PbrDraft& d) {
    try {
      load(d);
    } catch (const Error& e) {
      const std::string m = e.what(), prefix = (dir_ / "t.glb").string() + ": ";
      return m.rfind(prefix, 0) == 0 ? m.substr(prefix.size()) : "(no file name) " + m;
    }
    return "";
  }
  fs::path dir_;
};

// texture `index` on uv set `texcoord`.
json tex(int index, int texcoord = 0) { return {{"index", index}, {"texCoord", texcoord}}; }

TEST_F(GltfPbr, EveryCoreAndExtensionFieldIsRead) {
  PbrDraft d;
  d.attributes["TEXCOORD_0"] = d.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  d.attributes["TEXCOORD_1"] = d.floats({0, 1, 1, 1, 0, 0}, "VEC2", 3);
  d.textures(16);
  json base_tex = tex(0);
  base_tex["extensions"]["KHR_texture_transform"] = {{"offset", {0.1, 0.2}}, {"rotation", 0.3}, {"scale", {2, 3}}};
  json normal = tex(2, 1);
  normal["scale"] = 0.5;
  json occlusion = tex(3);
  occlusion["strength"] = 0.25;
  json coat_normal = tex(12, 1);
  coat_normal["scale"] = 0.75;
  d.j["materials"].push_back(
      {{"name", "everything"},
       {"doubleSided", true},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.3},
       {"emissiveFactor", {0.1, 0.2, 0.3}},
       {"emissiveTexture", tex(4)},
       {"normalTexture", normal},
       {"occlusionTexture", occlusion},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 1, 0.75}},
         {"baseColorTexture", base_tex},
         {"metallicFactor", 0.6},
         {"roughnessFactor", 0.4},
         {"metallicRoughnessTexture", tex(1, 1)}}},
       {"extensions",
        {{"KHR_materials_emissive_strength", {{"emissiveStrength", 5}}},
         {"KHR_materials_ior", {{"ior", 1.33}}},
         {"KHR_materials_specular",
          {{"specularFactor", 0.7},
           {"specularTexture", tex(5)},
           {"specularColorFactor", {0.9, 0.8, 1.5}},
           {"specularColorTexture", tex(6)}}},
         {"KHR_materials_transmission", {{"transmissionFactor", 0.8}, {"transmissionTexture", tex(7)}}},
         {"KHR_materials_volume",
          {{"thicknessFactor", 2.5},
           {"thicknessTexture", tex(8)},
           {"attenuationColor", {0.9, 0.5, 0.1}},
           {"attenuationDistance", 3}}},
         {"KHR_materials_clearcoat",
          {{"clearcoatFactor", 0.9},
           {"clearcoatTexture", tex(9)},
           {"clearcoatRoughnessFactor", 0.2},
           {"clearcoatRoughnessTexture", tex(10)},
           {"clearcoatNormalTexture", coat_normal}}},
         {"KHR_materials_sheen",
          {{"sheenColorFactor", {0.3, 0.2, 0.1}},
           {"sheenColorTexture", tex(13)},
           {"sheenRoughnessFactor", 0.6},
           {"sheenRoughnessTexture", tex(14)}}}}}});
  std::vector<std::string> warnings;
  Scene s = load(d, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  const PbrMaterial& p = m.pbr;
  EXPECT_EQ(m.name, "everything");
  EXPECT_EQ(m.model, Material::Model::metallic_roughness);
  EXPECT_TRUE(m.double_sided);
  EXPECT_TRUE(m.two_sided_lighting);
  EXPECT_FALSE(m.unlit);
  EXPECT_EQ(p.base_color, vec4(0.5f, 0.25f, 1.f, 0.75f));
  EXPECT_FLOAT_EQ(p.metallic, 0.6f);
  EXPECT_FLOAT_EQ(p.roughness, 0.4f);
  EXPECT_FLOAT_EQ(p.normal_scale, 0.5f);
  EXPECT_FLOAT_EQ(p.occlusion_strength, 0.25f);
  EXPECT_EQ(p.emissive, vec3(0.1f, 0.2f, 0.3f));
  EXPECT_FLOAT_EQ(p.emissive_strength, 5.f);
  EXPECT_EQ(p.alpha_mode, PbrMaterial::AlphaMode::mask);
  EXPECT_FLOAT_EQ(p.alpha_cutoff, 0.3f);  // the file's, not folded with the base alpha
  EXPECT_FLOAT_EQ(p.ior, 1.33f);
  EXPECT_FLOAT_EQ(p.specular, 0.7f);
  EXPECT_EQ(p.specular_color, vec3(0.9f, 0.8f, 1.5f));
  EXPECT_FLOAT_EQ(p.transmission, 0.8f);
  EXPECT_FLOAT_EQ(p.thickness, 2.5f);
  EXPECT_EQ(p.attenuation_color, vec3(0.9f, 0.5f, 0.1f));
  EXPECT_FLOAT_EQ(p.attenuation_distance, 3.f);
  EXPECT_FLOAT_EQ(p.clearcoat, 0.9f);
  EXPECT_FLOAT_EQ(p.clearcoat_roughness, 0.2f);
  EXPECT_FLOAT_EQ(p.clearcoat_normal_scale, 0.75f);
  EXPECT_EQ(p.sheen_color, vec3(0.3f, 0.2f, 0.1f));
  EXPECT_FLOAT_EQ(p.sheen_roughness, 0.6f);
  // Every slot names a Scene texture, each glTF texture read once (16 glTF
  // textures, 15 used: texture 11 is not referenced).
  struct Expect {
    const TextureSlot* slot;
    int texcoord;
    bool srgb;
  };
  const Expect expected[] = {
      {&p.base_color_texture, 0, true},
      {&p.metallic_roughness_texture, 1, false},
      {&p.normal_texture, 1, false},
      {&p.occlusion_texture, 0, false},
      {&p.emissive_texture, 0, true},
      {&p.specular_texture, 0, false},
      {&p.specular_color_texture, 0, true},
      {&p.transmission_texture, 0, false},
      {&p.thickness_texture, 0, false},
      {&p.clearcoat_texture, 0, false},
      {&p.clearcoat_roughness_texture, 0, false},
      {&p.clearcoat_normal_texture, 1, false},
      {&p.sheen_color_texture, 0, true},
      {&p.sheen_roughness_texture, 0, false},
  };
  EXPECT_EQ(s.textures.size(), std::size(expected));
  std::vector<int> seen;
  for (const Expect& e : expected) {
    ASSERT_TRUE(e.slot->used());
    ASSERT_LT(size_t(e.slot->texture), s.textures.size());
    EXPECT_EQ(e.slot->texcoord, e.texcoord) << e.slot->texture;
    EXPECT_EQ(s.textures[size_t(e.slot->texture)].srgb, e.srgb) << e.slot->texture;
    EXPECT_EQ(s.textures[size_t(e.slot->texture)].width, 2);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), e.slot->texture), 0);
    seen.push_back(e.slot->texture);
  }
  const UvTransform expect = gltf_uv_transform_to_scene(vec2(0.1f, 0.2f), 0.3f, vec2(2, 3));
  EXPECT_EQ(p.base_color_texture.transform.offset, expect.offset);
  EXPECT_FLOAT_EQ(p.base_color_texture.transform.rotation, -0.3f);
  EXPECT_EQ(p.base_color_texture.transform.scale, vec2(2, 3));
  EXPECT_TRUE(p.normal_texture.transform.is_identity());
  // The Phong fields hold the albedo only.
  EXPECT_EQ(m.diffuse, vec3(0.5f, 0.25f, 1.f));
  EXPECT_EQ(m.diffuse_texture, p.base_color_texture.texture);
  EXPECT_EQ(m.uv_transform.offset, expect.offset);
  EXPECT_TRUE(m.texture_modulates);
  EXPECT_EQ(m.specular, vec3(0.f));
  EXPECT_EQ(m.emission, vec3(0.f));
  EXPECT_LT(m.alpha_cutoff, 0.f);
  EXPECT_EQ(m.refraction_index, 0.f);
}

TEST_F(GltfPbr, UnlitBlendAndDefaultsOfEachExtension) {
  PbrDraft d;
  d.j["materials"].push_back({{"alphaMode", "BLEND"},
                              {"extensions",
                               {{"KHR_materials_unlit", json::object()},
                                {"KHR_materials_volume", json::object()},
                                {"KHR_materials_ior", {{"ior", 0}}},
                                {"KHR_materials_specular", json::object()},
                                {"KHR_materials_clearcoat", json::object()},
                                {"KHR_materials_sheen", json::object()}}}});
  Scene s = load(d);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  const PbrMaterial& p = m.pbr;
  EXPECT_TRUE(m.unlit);
  EXPECT_FALSE(m.double_sided);
  EXPECT_FALSE(m.two_sided_lighting);
  EXPECT_EQ(p.alpha_mode, PbrMaterial::AlphaMode::blend);
  EXPECT_EQ(p.ior, 0.f);  // allowed: a mirror-like reflector
  EXPECT_EQ(p.thickness, 0.f);
  EXPECT_TRUE(std::isinf(p.attenuation_distance));
  EXPECT_EQ(p.attenuation_color, vec3(1.f));
  EXPECT_EQ(p.specular, 1.f);
  EXPECT_EQ(p.specular_color, vec3(1.f));
  EXPECT_EQ(p.clearcoat, 0.f);
  EXPECT_EQ(p.sheen_color, vec3(0.f));
  EXPECT_EQ(p.metallic, 1.f);  // the core defaults
  EXPECT_EQ(p.roughness, 1.f);
  EXPECT_EQ(p.base_color, vec4(1.f));
}

TEST_F(GltfPbr, DefaultMaterialIsTheSpecifications) {
  PbrDraft d;
  Scene s = load(d);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  EXPECT_EQ(m.name, "default");
  EXPECT_EQ(m.model, Material::Model::metallic_roughness);
  EXPECT_EQ(m.pbr.base_color, vec4(1.f));
  EXPECT_EQ(m.pbr.metallic, 1.f);
  EXPECT_EQ(m.pbr.roughness, 1.f);
  EXPECT_FALSE(m.double_sided);
  EXPECT_EQ(m.diffuse, vec3(1.f));
  EXPECT_EQ(m.specular, vec3(0.f));
}

TEST_F(GltfPbr, ATextureUsedAsColourAndAsDataIsTwoSceneTextures) {
  PbrDraft d;
  d.attributes["TEXCOORD_0"] = d.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  d.textures(1);
  d.j["materials"].push_back(
      {{"pbrMetallicRoughness", {{"baseColorTexture", tex(0)}, {"metallicRoughnessTexture", tex(0)}}},
       {"occlusionTexture", tex(0)},
       {"emissiveTexture", tex(0)}});
  Scene s = load(d);
  ASSERT_EQ(s.textures.size(), 2u);
  const PbrMaterial& p = s.materials.at(0).pbr;
  const int colour = p.base_color_texture.texture, data = p.metallic_roughness_texture.texture;
  ASSERT_NE(colour, data);
  EXPECT_TRUE(s.textures[size_t(colour)].srgb);
  EXPECT_FALSE(s.textures[size_t(data)].srgb);
  EXPECT_EQ(p.emissive_texture.texture, colour);
  EXPECT_EQ(p.occlusion_texture.texture, data);
  EXPECT_TRUE(s.textures[size_t(colour)].pixels == s.textures[size_t(data)].pixels);
  EXPECT_EQ(s.textures[size_t(data)].pixels.size(), 16u);
  // A texture used only as data is one linear Scene texture.
  d.j["materials"][0] = {{"normalTexture", tex(0)}};
  s = load(d);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_FALSE(s.textures[0].srgb);
  EXPECT_EQ(s.materials.at(0).pbr.normal_texture.texture, 0);
}

TEST_F(GltfPbr, TwoUvSetsAndTangents) {
  PbrDraft d;
  d.attributes["NORMAL"] = d.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  d.attributes["TEXCOORD_0"] = d.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  d.attributes["TEXCOORD_1"] = d.floats({0.5f, 0.25f, 1, 1, 0, 0.75f}, "VEC2", 3);
  d.attributes["TANGENT"] = d.floats({2, 0, 0, 1, 0, 3, 0, -1, 1, 0, 0, 1}, "VEC4", 3);
  Scene s = load(d);
  const Mesh& m = s.meshes.at(0);
  EXPECT_EQ(m.uvs, (std::vector<vec2>{{0, 1}, {1, 1}, {0, 0}}));  // v flipped
  EXPECT_EQ(m.uvs1, (std::vector<vec2>{{0.5f, 0.75f}, {1, 0}, {0, 0.25f}}));
  EXPECT_EQ(m.tangents, (std::vector<vec4>{{1, 0, 0, 1}, {0, 1, 0, -1}, {1, 0, 0, 1}}));  // xyz normalised
  // Without them, both stay empty.
  PbrDraft plain;
  Scene p = load(plain);
  EXPECT_TRUE(p.meshes.at(0).uvs1.empty());
  EXPECT_TRUE(p.meshes.at(0).tangents.empty());
  // Bad tangents: the vertex named.
  PbrDraft bad = d;
  bad.attributes["TANGENT"] = bad.floats({1, 0, 0, 1, 1, 0, 0, 0, 1, 0, 0, 1}, "VEC4", 3);
  EXPECT_EQ(error(bad),
            "meshes[0].primitives[0].attributes.TANGENT: vertex 1 is (1.000000, 0.000000, 0.000000, 0.000000): "
            "expected finite xyz and w = 1 or -1");
  bad.attributes["TANGENT"] = bad.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, NAN, 0, 1}, "VEC4", 3);
  EXPECT_NE(error(bad).find("TANGENT: vertex 2 is (1.000000, nan"), std::string::npos) << error(bad);
  bad.attributes["TANGENT"] = bad.floats({1, 0, 0, 1, 1, 0, 0, 1}, "VEC4", 2);
  EXPECT_EQ(error(bad), "meshes[0].primitives[0].attributes.TANGENT: 2 elements, but POSITION has 3");
  bad.attributes["TANGENT"] = bad.floats({1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3", 3);
  EXPECT_NE(error(bad).find("attributes.TANGENT"), std::string::npos) << error(bad);
}

TEST_F(GltfPbr, TexturesOnAMissingOrUnreadUvSetAreSaidSo) {
  PbrDraft d;
  d.attributes["TEXCOORD_0"] = d.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  d.textures(2);
  d.j["materials"].push_back({{"normalTexture", tex(0, 1)}, {"emissiveTexture", tex(1, 2)}});
  std::vector<std::string> warnings;
  Scene s = load(d, &warnings);
  const PbrMaterial& p = s.materials.at(0).pbr;
  EXPECT_TRUE(p.normal_texture.used());
  EXPECT_FALSE(p.emissive_texture.used());
  EXPECT_TRUE(test::any_contains(warnings,
                                 "materials[0].emissiveTexture.texCoord: TEXCOORD_2 is not read (only "
                                 "TEXCOORD_0 and TEXCOORD_1 are); the texture is not used"));
  EXPECT_TRUE(test::any_contains(
      warnings, "meshes[0].primitives[0]: the material's normalTexture uses TEXCOORD_1 but the primitive has none"));
}

TEST_F(GltfPbr, SpecularGlossinessIsApproximatedAsMetallicRoughness) {
  PbrDraft d;
  d.textures(3);
  d.j["materials"].push_back(
      {{"pbrMetallicRoughness", {{"baseColorTexture", tex(2)}, {"metallicRoughnessTexture", tex(2)}}},
       {"extensions",
        {{"KHR_materials_pbrSpecularGlossiness",
          {{"diffuseFactor", {0.2, 0.4, 0.6, 0.8}},
           {"specularFactor", {0.1, 0.02, 0.04}},
           {"glossinessFactor", 0.7},
           {"diffuseTexture", tex(0)},
           {"specularGlossinessTexture", tex(1)}}}}}});
  std::vector<ExtensionUse> used;
  std::vector<std::string> warnings;
  PbrDraft with_uvs = d;
  with_uvs.attributes["TEXCOORD_0"] = with_uvs.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  Scene s = load(with_uvs, &warnings, &used);
  const PbrMaterial& p = s.materials.at(0).pbr;
  EXPECT_EQ(p.base_color, vec4(0.2f, 0.4f, 0.6f, 0.8f));
  EXPECT_EQ(p.metallic, 0.f);
  EXPECT_FLOAT_EQ(p.roughness, 0.3f);
  EXPECT_EQ(p.specular, 1.f);
  // F0 = min(0.04 specular_color, 1) specular = the specular factor.
  EXPECT_NEAR(0.04f * p.specular_color.x, 0.1f, 1e-6f);
  EXPECT_NEAR(0.04f * p.specular_color.y, 0.02f, 1e-6f);
  EXPECT_NEAR(0.04f * p.specular_color.z, 0.04f, 1e-6f);
  // The workflow's textures, not the core ones; both sRGB colour.
  ASSERT_TRUE(p.base_color_texture.used());
  ASSERT_TRUE(p.specular_color_texture.used());
  EXPECT_FALSE(p.metallic_roughness_texture.used());
  EXPECT_EQ(s.textures.size(), 2u);
  EXPECT_TRUE(s.textures[size_t(p.base_color_texture.texture)].srgb);
  EXPECT_TRUE(s.textures[size_t(p.specular_color_texture.texture)].srgb);
  ASSERT_EQ(used.size(), 1u);
  EXPECT_EQ(used[0].name, "KHR_materials_pbrSpecularGlossiness");
  EXPECT_EQ(used[0].support, ExtensionUse::Support::approximated);
  EXPECT_NE(used[0].detail.find("roughness = 1 - glossinessFactor"), std::string::npos) << used[0].detail;
  EXPECT_NE(used[0].detail.find("glossiness (alpha) is not used"), std::string::npos) << used[0].detail;
  EXPECT_TRUE(test::any_contains(warnings, "extensions approximated: KHR_materials_pbrSpecularGlossiness"));
}

TEST_F(GltfPbr, TheExtensionReportTellsWhatWasReadAndWhatWasNot) {
  PbrDraft d;
  const char* read[] = {"KHR_materials_emissive_strength",
                        "KHR_materials_ior",
                        "KHR_materials_specular",
                        "KHR_materials_transmission",
                        "KHR_materials_volume",
                        "KHR_materials_clearcoat",
                        "KHR_materials_sheen",
                        "KHR_materials_unlit"};
  const char* ignored[] = {"KHR_materials_iridescence", "KHR_materials_anisotropy", "KHR_materials_dispersion",
                           "KHR_materials_diffuse_transmission"};
  json extensions = json::object();
  for (const char* e : read) extensions[e] = json::object();
  for (const char* e : ignored) extensions[e] = json::object();
  d.j["materials"].push_back({{"extensions", extensions}});
  d.j["extensionsUsed"] = json::array({"KHR_materials_variants"});
  for (const char* e : read) d.j["extensionsUsed"].push_back(e);
  for (const char* e : ignored) d.j["extensionsUsed"].push_back(e);
  d.j["extensionsRequired"] = d.j["extensionsUsed"];  // each still loads
  d.j["extensions"]["KHR_materials_variants"] = {{"variants", json::array({{{"name", "red"}}})}};
  std::vector<std::string> warnings;
  std::vector<ExtensionUse> used;
  load(d, &warnings, &used);
  auto use = [&](const std::string& name) -> ExtensionUse {
    for (const ExtensionUse& u : used)
      if (u.name == name) return u;
    return {"(absent)", ExtensionUse::Support::read, ""};
  };
  for (const char* e : read) {
    EXPECT_EQ(use(e).name, e);
    EXPECT_EQ(use(e).support, ExtensionUse::Support::read) << e;
  }
  for (const char* e : ignored) {
    EXPECT_EQ(use(e).name, e);
    EXPECT_EQ(use(e).support, ExtensionUse::Support::ignored) << e;
  }
  const ExtensionUse variants = use("KHR_materials_variants");
  EXPECT_EQ(variants.support, ExtensionUse::Support::ignored);
  EXPECT_EQ(variants.detail, "each primitive is drawn with its default material; the variants' materials are not used");
  EXPECT_EQ(used.size(), std::size(read) + std::size(ignored) + 1);
  EXPECT_TRUE(test::any_contains(warnings, "extensions ignored: KHR_materials_iridescence"));
  EXPECT_TRUE(test::any_contains(warnings, "KHR_materials_variants (each primitive is drawn with its default"));
  EXPECT_FALSE(test::any_contains(warnings, "KHR_materials_sheen"));
  EXPECT_FALSE(test::any_contains(warnings, "extensions approximated"));
}

TEST_F(GltfPbr, ValuesOutsideTheSpecificationAreErrorsNamingTheirPath) {
  auto with = [](json material) {
    PbrDraft d;
    d.textures(1);
    d.j["materials"].push_back(material);
    return d;
  };
  EXPECT_EQ(error(with({{"pbrMetallicRoughness", {{"metallicFactor", 2}}}})),
            "materials[0].pbrMetallicRoughness.metallicFactor: 2.000000 is not a number from 0.000000 to 1.000000");
  EXPECT_EQ(error(with({{"pbrMetallicRoughness", {{"baseColorFactor", {1, -1, 1, 1}}}}})),
            "materials[0].pbrMetallicRoughness.baseColorFactor[1]: -1.000000 is not a finite number >= 0");
  EXPECT_EQ(error(with({{"occlusionTexture", {{"index", 0}, {"strength", 1.5}}}})),
            "materials[0].occlusionTexture.strength: 1.500000 is not a number from 0.000000 to 1.000000");
  EXPECT_EQ(error(with({{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 2}}}}}})),
            "materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor: expected a number from 0.000000 to "
            "1.000000");
  EXPECT_EQ(error(with({{"extensions", {{"KHR_materials_volume", {{"attenuationDistance", 0}}}}}})),
            "materials[0].extensions.KHR_materials_volume.attenuationDistance: must be greater than 0");
  EXPECT_EQ(error(with({{"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}}}})),
            "materials[0].extensions.KHR_materials_ior.ior: 0.500000 is neither 0 nor a number >= 1");
  EXPECT_EQ(error(with({{"extensions", {{"KHR_materials_sheen", {{"sheenColorFactor", {1, 1}}}}}}})),
            "materials[0].extensions.KHR_materials_sheen.sheenColorFactor: expected 3 numbers");
  EXPECT_EQ(error(with({{"extensions", {{"KHR_materials_sheen", {{"sheenColorTexture", {{"texCoord", 0}}}}}}}})),
            "materials[0].extensions.KHR_materials_sheen.sheenColorTexture: expected an object with an \"index\"");
  EXPECT_EQ(error(with({{"extensions", {{"KHR_materials_transmission", {{"transmissionTexture", {{"index", 4}}}}}}}})),
            "materials[0].extensions.KHR_materials_transmission.transmissionTexture.index: texture 4 does not exist "
            "(the file has 1 textures)");
  EXPECT_EQ(
      error(with({{"extensions",
                   {{"KHR_materials_clearcoat", {{"clearcoatNormalTexture", {{"index", 0}, {"scale", "x"}}}}}}}})),
      "materials[0].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.scale: expected a number from "
      "-340282346638528859811704183484516925440.000000 to 340282346638528859811704183484516925440.000000");
  // An unknown alphaMode is drawn opaque, with a warning.
  std::vector<std::string> warnings;
  Scene s = load(with({{"alphaMode", "CUTOUT"}}), &warnings);
  EXPECT_EQ(s.materials.at(0).pbr.alpha_mode, PbrMaterial::AlphaMode::opaque);
  EXPECT_TRUE(test::any_contains(warnings, "materials[0].alphaMode: unknown mode 'CUTOUT'; drawn OPAQUE"));
}

// ---- Khronos samples ---------------------------------------------------------------------------

TEST(GltfPbrSamples, ClearCoatMultiUvAndNormalTangentMirror) {
  RAYFORM_REQUIRE_SHARED();
  Scene coat = read_gltf_scene(test::asset("khronos/ClearCoatTest/glTF-Binary/ClearCoatTest.glb").string());
  int coated = 0, coat_normal = 0;
  for (const Material& m : coat.materials) {
    EXPECT_EQ(m.model, Material::Model::metallic_roughness);
    coated += m.pbr.clearcoat > 0.f;
    coat_normal += m.pbr.clearcoat_normal_texture.used();
  }
  EXPECT_GT(coated, 0);
  EXPECT_GT(coat_normal, 0);
  Scene multi = read_gltf_scene(test::asset("khronos/MultiUVTest/glTF-Binary/MultiUVTest.glb").string());
  bool uses_set_1 = false;
  for (const Material& m : multi.materials)
    for (const auto& [name, slot] : gltf_named_texture_slots(m.pbr)) uses_set_1 |= slot->used() && slot->texcoord == 1;
  EXPECT_TRUE(uses_set_1);
  for (const Mesh& m : multi.meshes) EXPECT_EQ(m.uvs1.size(), m.positions.size());
  Scene mirror =
      read_gltf_scene(test::asset("khronos/NormalTangentMirrorTest/glTF-Binary/NormalTangentMirrorTest.glb").string());
  size_t with_tangents = 0, negative_w = 0;
  for (const Mesh& m : mirror.meshes) {
    with_tangents += m.tangents.size() == m.positions.size();
    for (const vec4& t : m.tangents) negative_w += t.w < 0.f;
  }
  EXPECT_EQ(with_tangents, mirror.meshes.size());
  EXPECT_GT(negative_w, 0u);  // the mirrored half
  for (const Material& m : mirror.materials) EXPECT_TRUE(m.pbr.normal_texture.used());
}

}  // namespace
}  // namespace rayform
