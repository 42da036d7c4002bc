// The writers and the metallic-roughness model (issue 30): glTF writes every
// PbrMaterial field as the file format says it (checked in the written JSON,
// and after a read back); OBJ writes Kd/Ks/Ns plus MTL's PBR statements,
// which its reader reads back; the course approximates as Phong. Each with
// its notes.
#include "rayform/importers/material_approximation.h"
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/importers/scene_io.h"
#include "rayform/importers/scene_writer.h"
#include "rayform/importers/text_format.h"
#include "rayform/importers/texture_files.h"
#include "test_importers.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool mentions(const std::vector<std::string>& messages, const std::string& part) {
  for (const std::string& m : messages)
    if (m.find(part) != std::string::npos) return true;
  return false;
}

Texture pixel_texture(const std::string& name, bool srgb, uint8_t value) {
  Texture t;
  t.name = name;
  t.width = t.height = 2;
  t.channels = 4;
  t.pixels.assign(16, value);
  t.srgb = srgb;
  return t;
}

// A quad with both uv sets and tangents, its material metallic-roughness
// with every field away from its default, and one light of colour 1.
Scene pbr_scene() {
  Scene s;
  s.textures.push_back(pixel_texture("colour", true, 200));  // 0: base colour, emissive, sheen colour
  s.textures.push_back(pixel_texture("data", false, 100));   // 1: the data slots
  Material m;
  m.name = "every field";
  m.model = Material::Model::metallic_roughness;
  m.double_sided = false;
  PbrMaterial& p = m.pbr;
  p.base_color = vec4(0.5f, 0.25f, 0.75f, 0.5f);
  p.base_color_texture = TextureSlot{0, 0, {}};
  p.base_color_texture.transform.offset = vec2(0.25f, 0.5f);
  p.base_color_texture.transform.scale = vec2(2.f, 3.f);
  p.metallic = 0.25f;
  p.roughness = 0.75f;
  p.metallic_roughness_texture = TextureSlot{1, 1, {}};
  p.normal_texture = TextureSlot{1, 0, {}};
  p.normal_scale = 0.5f;
  p.occlusion_texture = TextureSlot{1, 1, {}};
  p.occlusion_strength = 0.25f;
  p.emissive = vec3(2.f, 1.f, 0.5f);
  p.emissive_texture = TextureSlot{0, 0, {}};
  p.emissive_strength = 1.5f;
  p.alpha_mode = PbrMaterial::AlphaMode::blend;
  p.ior = 1.25f;
  p.specular = 0.5f;
  p.specular_texture = TextureSlot{1, 0, {}};
  p.specular_color = vec3(0.5f, 1.f, 1.f);
  p.transmission = 0.5f;
  p.transmission_texture = TextureSlot{1, 0, {}};
  p.thickness = 0.125f;
  p.attenuation_color = vec3(0.5f, 0.75f, 1.f);
  p.attenuation_distance = 2.f;
  p.clearcoat = 0.75f;
  p.clearcoat_roughness = 0.25f;
  p.clearcoat_normal_texture = TextureSlot{1, 0, {}};
  p.clearcoat_normal_scale = 0.75f;
  p.sheen_color = vec3(0.25f, 0.5f, 0.75f);
  p.sheen_color_texture = TextureSlot{0, 0, {}};
  p.sheen_roughness = 0.375f;
  s.materials.push_back(m);
  Mesh q;
  q.name = "quad";
  q.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  q.normals.assign(4, vec3(0, 0, 1));
  q.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  q.uvs1 = {{0, 0}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}};
  q.tangents.assign(4, vec4(1, 0, 0, -1));
  q.indices = {0, 1, 2, 0, 2, 3};
  s.meshes.push_back(q);
  Node root;
  root.name = "root";
  Node shape;
  shape.name = "quad";
  shape.kind = Node::Kind::shape;
  shape.shape_kind = ShapeKind::mesh;
  shape.shape = 0;
  shape.material = 0;
  s.nodes = {root, shape};
  s.nodes[0].children = {1};
  s.root = 0;
  Light l;
  l.kind = Light::Kind::directional;
  l.color = vec3(1.f);
  l.direction = vec3(0, 0, -1);
  s.lights.push_back(l);
  return s;
}

class MaterialWriter : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::temp_dir("material-writer"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(MaterialWriter, GltfHoldsEveryPbrFieldAsTheSpecificationSaysIt) {
  std::vector<std::string> messages;
  const fs::path out = dir_ / "pbr.gltf";
  save_scene(pbr_scene(), out.string(), {}, &messages);
  const json j = json::parse(text_of(out));
  ASSERT_EQ(j["materials"].size(), 1u);
  const json& m = j["materials"][0];
  EXPECT_FALSE(m.contains("extras")) << m["extras"].dump();  // no Phong extras
  const json& pmr = m["pbrMetallicRoughness"];
  EXPECT_EQ(pmr["baseColorFactor"], json::array({0.5, 0.25, 0.75, 0.5}));
  EXPECT_EQ(pmr["metallicFactor"], 0.25);
  EXPECT_EQ(pmr["roughnessFactor"], 0.75);
  EXPECT_EQ(pmr["baseColorTexture"].value("texCoord", 0), 0);
  const json& tt = pmr["baseColorTexture"]["extensions"]["KHR_texture_transform"];
  EXPECT_EQ(tt["scale"], json::array({2.0, 3.0}));
  EXPECT_EQ(pmr["metallicRoughnessTexture"]["texCoord"], 1);
  EXPECT_EQ(m["normalTexture"]["scale"], 0.5);
  EXPECT_EQ(m["occlusionTexture"]["strength"], 0.25);
  EXPECT_EQ(m["occlusionTexture"]["texCoord"], 1);
  EXPECT_TRUE(m.contains("emissiveTexture"));
  // emissive (2, 1, 0.5) x 1.5 = (1, 0.5, 0.25) x 3
  EXPECT_EQ(m["emissiveFactor"], json::array({1.0, 0.5, 0.25}));
  EXPECT_EQ(m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"], 3.0);
  EXPECT_EQ(m["alphaMode"], "BLEND");
  EXPECT_EQ(m.value("doubleSided", false), false);
  const json& ex = m["extensions"];
  EXPECT_EQ(ex["KHR_materials_ior"]["ior"], 1.25);
  EXPECT_EQ(ex["KHR_materials_specular"]["specularFactor"], 0.5);
  EXPECT_EQ(ex["KHR_materials_specular"]["specularColorFactor"], json::array({0.5, 1.0, 1.0}));
  EXPECT_TRUE(ex["KHR_materials_specular"].contains("specularTexture"));
  EXPECT_EQ(ex["KHR_materials_transmission"]["transmissionFactor"], 0.5);
  EXPECT_TRUE(ex["KHR_materials_transmission"].contains("transmissionTexture"));
  EXPECT_EQ(ex["KHR_materials_volume"]["thicknessFactor"], 0.125);
  EXPECT_EQ(ex["KHR_materials_volume"]["attenuationColor"], json::array({0.5, 0.75, 1.0}));
  EXPECT_EQ(ex["KHR_materials_volume"]["attenuationDistance"], 2.0);
  EXPECT_EQ(ex["KHR_materials_clearcoat"]["clearcoatFactor"], 0.75);
  EXPECT_EQ(ex["KHR_materials_clearcoat"]["clearcoatRoughnessFactor"], 0.25);
  EXPECT_EQ(ex["KHR_materials_clearcoat"]["clearcoatNormalTexture"]["scale"], 0.75);
  EXPECT_EQ(ex["KHR_materials_sheen"]["sheenColorFactor"], json::array({0.25, 0.5, 0.75}));
  EXPECT_EQ(ex["KHR_materials_sheen"]["sheenRoughnessFactor"], 0.375);
  EXPECT_TRUE(ex["KHR_materials_sheen"].contains("sheenColorTexture"));
  for (const char* e :
       {"KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_specular",
        "KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_clearcoat", "KHR_materials_sheen"})
    EXPECT_NE(std::find(j["extensionsUsed"].begin(), j["extensionsUsed"].end(), e), j["extensionsUsed"].end()) << e;
  // Both uv sets and the tangents.
  const json& attributes = j["meshes"][0]["primitives"][0]["attributes"];
  EXPECT_TRUE(attributes.contains("TEXCOORD_0"));
  EXPECT_TRUE(attributes.contains("TEXCOORD_1"));
  ASSERT_TRUE(attributes.contains("TANGENT"));
  EXPECT_EQ(j["accessors"][attributes["TANGENT"].get<int>()]["type"], "VEC4");
  // The data texture is linear as glTF reads data textures: no "srgb" extra.
  for (const json& t : j["textures"]) EXPECT_FALSE(t.contains("extras")) << t.dump();
  // A light of colour 1 lights a white surface with radiance 1: I = pi (c = C I / pi).
  const json& light = j["extensions"]["KHR_lights_punctual"]["lights"][0];
  EXPECT_NEAR(light["intensity"].get<double>(), double(pi), 1e-6);
  EXPECT_FALSE(mentions(messages, "Phong materials converted"));
}

// Needs the glTF reader of issue 30 (metallic-roughness materials kept as
// Model::metallic_roughness, TEXCOORD_1, TANGENT): passes only after the merge.
TEST_F(MaterialWriter, GltfRoundTripKeepsEveryPbrField) {
  const Scene a = pbr_scene();
  const fs::path out = dir_ / "pbr.glb";
  save_scene(a, out.string());
  LoadedScene loaded = load_scene(out.string());
  const Scene& b = loaded.scene;
  ASSERT_EQ(b.materials.size(), 1u);
  const Material& m = b.materials[0];
  ASSERT_EQ(m.model, Material::Model::metallic_roughness);
  const PbrMaterial& p = a.materials[0].pbr;
  const PbrMaterial& q = m.pbr;
  EXPECT_EQ(q.base_color, p.base_color);
  EXPECT_EQ(q.metallic, p.metallic);
  EXPECT_EQ(q.roughness, p.roughness);
  EXPECT_EQ(q.normal_scale, p.normal_scale);
  EXPECT_EQ(q.occlusion_strength, p.occlusion_strength);
  EXPECT_LT(glm::length(q.emissive * q.emissive_strength - p.emissive * p.emissive_strength), 1e-5f);
  EXPECT_EQ(q.alpha_mode, p.alpha_mode);
  EXPECT_EQ(q.ior, p.ior);
  EXPECT_EQ(q.specular, p.specular);
  EXPECT_EQ(q.specular_color, p.specular_color);
  EXPECT_EQ(q.transmission, p.transmission);
  EXPECT_EQ(q.thickness, p.thickness);
  EXPECT_EQ(q.attenuation_color, p.attenuation_color);
  EXPECT_EQ(q.attenuation_distance, p.attenuation_distance);
  EXPECT_EQ(q.clearcoat, p.clearcoat);
  EXPECT_EQ(q.clearcoat_roughness, p.clearcoat_roughness);
  EXPECT_EQ(q.clearcoat_normal_scale, p.clearcoat_normal_scale);
  EXPECT_EQ(q.sheen_color, p.sheen_color);
  EXPECT_EQ(q.sheen_roughness, p.sheen_roughness);
  EXPECT_FALSE(m.double_sided);
  for (auto [from, to] :
       {std::pair{&p.base_color_texture, &q.base_color_texture},
        std::pair{&p.metallic_roughness_texture, &q.metallic_roughness_texture},
        std::pair{&p.normal_texture, &q.normal_texture}, std::pair{&p.occlusion_texture, &q.occlusion_texture},
        std::pair{&p.emissive_texture, &q.emissive_texture}, std::pair{&p.specular_texture, &q.specular_texture},
        std::pair{&p.transmission_texture, &q.transmission_texture},
        std::pair{&p.clearcoat_normal_texture, &q.clearcoat_normal_texture},
        std::pair{&p.sheen_color_texture, &q.sheen_color_texture}}) {
    ASSERT_TRUE(to->used());
    EXPECT_EQ(to->texcoord, from->texcoord);
    EXPECT_LT(glm::length(to->transform.offset - from->transform.offset), 1e-6f);
    EXPECT_EQ(to->transform.scale, from->transform.scale);
    EXPECT_EQ(b.textures[size_t(to->texture)].pixels, a.textures[size_t(from->texture)].pixels);
  }
  ASSERT_EQ(b.meshes.size(), 1u);
  EXPECT_EQ(b.meshes[0].uvs1.size(), 4u);
  EXPECT_EQ(b.meshes[0].tangents, a.meshes[0].tangents);
  ASSERT_EQ(b.lights.size(), 1u);
  EXPECT_LT(glm::length(b.lights[0].color - vec3(1.f)), 1e-6f);
}

TEST_F(MaterialWriter, ObjWritesPhongAndThePbrStatementsItsReaderReadsBack) {
  Scene s = pbr_scene();
  PbrMaterial& p = s.materials[0].pbr;
  p.metallic_roughness_texture.texcoord = 0;
  p.occlusion_texture = {};
  std::vector<std::string> messages;
  const fs::path out = dir_ / "pbr.obj";
  save_scene(s, out.string(), {}, &messages);
  const std::string mtl = text_of(dir_ / "pbr.mtl");
  Material phong = phong_approximation(s.materials[0]);
  EXPECT_NE(mtl.find("Kd 0.5 0.25 0.75\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("Pr 0.75\nPm 0.25\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("map_Pr -imfchan g "), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("map_Pm -imfchan b "), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("norm -bm 0.5 "), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("d 0.5\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("Pc 0.75\nPcr 0.25\n"), std::string::npos) << mtl;
  EXPECT_TRUE(mentions(messages, "metallic-roughness written as Kd/Ks/Ns"));
  EXPECT_TRUE(mentions(messages, "'every_field': volume dropped") ||
              mentions(messages, "'every field': volume dropped"))
      << messages.front();
  EXPECT_TRUE(mentions(messages, "transmission texture dropped"));
  EXPECT_TRUE(mentions(messages, "transmission dropped"));
  // Ks and Ns: the Phong approximation's.
  EXPECT_NE(mtl.find("Ks " + format_vec3(phong.specular) + "\nNs " + format_float(phong.shininess)), std::string::npos)
      << mtl;

  std::vector<std::string> warnings;
  Scene b = read_obj_scene(out.string(), {}, &warnings);
  ASSERT_EQ(b.materials.size(), 1u);
  const Material& m = b.materials[0];
  ASSERT_EQ(m.model, Material::Model::metallic_roughness);
  EXPECT_EQ(vec3(m.pbr.base_color), vec3(p.base_color));
  EXPECT_EQ(m.pbr.base_color.a, 0.5f);
  EXPECT_EQ(m.pbr.alpha_mode, PbrMaterial::AlphaMode::blend);
  EXPECT_EQ(m.pbr.normal_scale, 0.5f);
  EXPECT_EQ(m.pbr.clearcoat, 0.75f);
  ASSERT_TRUE(m.pbr.metallic_roughness_texture.used());
  // The texture comes back as the texel alone (factor 1), its channels those written.
  const Texture& packed = b.textures[size_t(m.pbr.metallic_roughness_texture.texture)];
  ASSERT_EQ(packed.channels, 3);
  EXPECT_EQ(packed.pixels[1], 100);
  EXPECT_EQ(packed.pixels[2], 100);
  EXPECT_FALSE(packed.srgb);
  ASSERT_TRUE(m.pbr.normal_texture.used());
  EXPECT_FALSE(b.textures[size_t(m.pbr.normal_texture.texture)].srgb);
}

TEST_F(MaterialWriter, CourseApproximatesPbrAsPhongWithOneNotePerKind) {
  Scene s = pbr_scene();
  std::vector<std::string> messages;
  const fs::path out = dir_ / "pbr.txt";
  save_scene(s, out.string(), {}, &messages);
  EXPECT_TRUE(mentions(messages, "'every field': metallic-roughness approximated as Phong"));
  EXPECT_TRUE(mentions(messages, "'every field': normal texture dropped"));
  EXPECT_TRUE(mentions(messages, "'every field': sheen dropped"));
  LoadedScene back = load_scene(out.string());
  ASSERT_EQ(back.scene.materials.size(), 1u);
  const Material& m = back.scene.materials[0];
  const Material expected = phong_approximation(s.materials[0]);
  EXPECT_EQ(m.model, Material::Model::phong);
  EXPECT_EQ(m.diffuse, expected.diffuse);
  EXPECT_EQ(m.specular, expected.specular);
  EXPECT_EQ(m.shininess, expected.shininess);
  EXPECT_NE(m.diffuse_texture, invalid);  // the base colour texture
  EXPECT_EQ(m.refraction_index, 1.25f);   // transmission as refraction
}

TEST(MaterialApproximation, PhongMaterialsPassUnchangedAndPbrOnesMapTheirBase) {
  Material phong;
  phong.diffuse = vec3(0.1f, 0.2f, 0.3f);
  phong.specular = vec3(0.5f);
  phong.shininess = 20.f;
  phong.bump_texture = 3;
  const Material same = phong_approximation(phong);
  EXPECT_EQ(same.diffuse, phong.diffuse);
  EXPECT_EQ(same.bump_texture, 3);
  EXPECT_TRUE(pbr_fields_lost_in_phong(phong).empty());
  Material pbr;
  pbr.model = Material::Model::metallic_roughness;
  pbr.pbr.base_color = vec4(0.8f, 0.6f, 0.4f, 1.f);
  pbr.pbr.metallic = 0.f;
  pbr.pbr.roughness = 0.5f;
  pbr.pbr.base_color_texture = TextureSlot{2, 0, {}};
  pbr.pbr.alpha_mode = PbrMaterial::AlphaMode::mask;
  pbr.pbr.alpha_cutoff = 0.25f;
  const Material a = phong_approximation(pbr);
  EXPECT_EQ(a.model, Material::Model::phong);
  EXPECT_EQ(a.diffuse, vec3(0.8f, 0.6f, 0.4f));
  EXPECT_EQ(a.diffuse_texture, 2);
  EXPECT_TRUE(a.texture_modulates);
  EXPECT_EQ(a.alpha_cutoff, 0.25f);
  // Dielectric: Ks = 0.04 (1 - 0.5)^2.
  EXPECT_NEAR(a.specular.r, 0.01f, 1e-6f);
  EXPECT_TRUE(pbr_fields_lost_in_phong(pbr).empty());
}

}  // namespace
}  // namespace rayform
