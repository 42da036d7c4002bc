// The OBJ reader and MTL's PBR extension (obj/obj_pbr_material.h): a
// material with Pr, Pm, map_Pr or map_Pm is metallic-roughness, its scalar
// maps packed as glTF's metallic-roughness texture; Kd/Ks/Ns materials stay
// Phong as they were.
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/importers/texture_files.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <fstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;

void write_bytes(const fs::path& p, const std::vector<uint8_t>& bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// A 2 x 1 RGB picture: texels (r, g, b) and (r + 1, g + 1, b + 1).
std::vector<uint8_t> png(uint8_t r, uint8_t g, uint8_t b) {
  Pixels8 p;
  p.width = 2;
  p.height = 1;
  p.channels = 3;
  p.data = {r, g, b, uint8_t(r + 1), uint8_t(g + 1), uint8_t(b + 1)};
  return encode_png(p);
}

class ObjPbr : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::temp_dir("obj-pbr"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

const char* triangle_obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";

TEST_F(ObjPbr, PbrStatementsMakeAMetallicRoughnessMaterial) {
  write_bytes(dir_ / "rough.png", png(10, 20, 30));
  write_bytes(dir_ / "metal.png", png(40, 50, 60));
  write_bytes(dir_ / "base.png", png(1, 2, 3));
  write_bytes(dir_ / "normal.png", png(128, 128, 255));
  write_bytes(dir_ / "glow.png", png(5, 5, 5));
  write_text(dir_ / "m.mtl",
             "newmtl metal\nKd 0.5 0.25 1\nPr 0.25\nPm 1\nKe 0.5 0.5 0\nd 0.5\nNi 1.33\nPc 0.5\nPcr 0.125\nPs 0.75\n"
             "newmtl textured\nmap_Kd base.png\nPr 0.5\nmap_Pr -imfchan g rough.png\nmap_Pm -imfchan b metal.png\n"
             "map_Ke glow.png\nmap_Bump -bm 0.5 normal.png\n"
             "newmtl phong\nKd 0.1 0.2 0.3\nKs 0.5 0.5 0.5\nNs 32\nKe 0.25 0 0\nmap_Bump normal.png\n");
  write_text(dir_ / "m.obj",
             std::string(triangle_obj) +
                 "usemtl metal\nf 1/1 2/2 3/3\nusemtl textured\nf 1/1 2/2 3/3\nusemtl phong\nf 1 2 3\n");
  std::vector<std::string> warnings;
  Scene s = read_obj_scene((dir_ / "m.obj").string(), {}, &warnings);
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_TRUE(warnings.empty()) << warnings.front();

  const Material& metal = s.materials[0];
  ASSERT_EQ(metal.model, Material::Model::metallic_roughness);
  EXPECT_EQ(metal.pbr.base_color, vec4(0.5f, 0.25f, 1.f, 0.5f));
  EXPECT_EQ(metal.pbr.alpha_mode, PbrMaterial::AlphaMode::blend);
  EXPECT_EQ(metal.pbr.roughness, 0.25f);
  EXPECT_EQ(metal.pbr.metallic, 1.f);
  EXPECT_EQ(metal.pbr.emissive, vec3(0.5f, 0.5f, 0.f));
  EXPECT_EQ(metal.pbr.ior, 1.33f);
  EXPECT_EQ(metal.pbr.clearcoat, 0.5f);
  EXPECT_EQ(metal.pbr.clearcoat_roughness, 0.125f);
  EXPECT_EQ(metal.pbr.sheen_color, vec3(0.75f));
  EXPECT_FALSE(metal.pbr.metallic_roughness_texture.used());
  EXPECT_TRUE(metal.two_sided_lighting);

  const Material& textured = s.materials[1];
  ASSERT_EQ(textured.model, Material::Model::metallic_roughness);
  EXPECT_EQ(vec3(textured.pbr.base_color), vec3(1.f));  // map_Kd without Kd
  ASSERT_TRUE(textured.pbr.base_color_texture.used());
  EXPECT_TRUE(s.textures[size_t(textured.pbr.base_color_texture.texture)].srgb);
  EXPECT_EQ(textured.pbr.base_color_texture.texcoord, 0);
  // The maps replace Pr and Pm; packed G = map_Pr's green, B = map_Pm's blue.
  EXPECT_EQ(textured.pbr.roughness, 1.f);
  EXPECT_EQ(textured.pbr.metallic, 1.f);
  ASSERT_TRUE(textured.pbr.metallic_roughness_texture.used());
  const Texture& packed = s.textures[size_t(textured.pbr.metallic_roughness_texture.texture)];
  EXPECT_FALSE(packed.srgb);
  ASSERT_EQ(packed.width, 2);
  ASSERT_EQ(packed.channels, 3);
  EXPECT_EQ(packed.pixels, (std::vector<uint8_t>{255, 20, 60, 255, 21, 61}));
  ASSERT_TRUE(textured.pbr.emissive_texture.used());
  EXPECT_EQ(textured.pbr.emissive, vec3(1.f));      // map_Ke without Ke
  ASSERT_TRUE(textured.pbr.normal_texture.used());  // map_Bump: Blender's normal map
  EXPECT_FALSE(s.textures[size_t(textured.pbr.normal_texture.texture)].srgb);
  EXPECT_EQ(textured.pbr.normal_scale, 0.5f);

  // Kd/Ks/Ns: Phong as before, the bump map kept as a bump map.
  const Material& phong = s.materials[2];
  EXPECT_EQ(phong.model, Material::Model::phong);
  EXPECT_EQ(phong.diffuse, vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(phong.specular, vec3(0.5f));
  EXPECT_EQ(phong.shininess, 32.f);
  EXPECT_EQ(phong.emission, vec3(0.25f, 0.f, 0.f));
  EXPECT_NE(phong.bump_texture, invalid);
}

TEST_F(ObjPbr, MissingAndUndecodableMapsAreWarnings) {
  write_text(dir_ / "broken.png", "not a png");
  write_text(dir_ / "m.mtl", "newmtl a\nPm 0.5\nmap_Pr broken.png\nmap_Pm missing.png\n");
  write_text(dir_ / "m.obj", std::string(triangle_obj) + "usemtl a\nf 1 2 3\n");
  std::vector<std::string> warnings;
  Scene s = read_obj_scene((dir_ / "m.obj").string(), {}, &warnings);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].model, Material::Model::metallic_roughness);
  EXPECT_FALSE(s.materials[0].pbr.metallic_roughness_texture.used());
  EXPECT_EQ(s.materials[0].pbr.metallic, 0.5f);  // no texture: the value
  EXPECT_EQ(warnings.size(), 2u);
}

}  // namespace
}  // namespace rayform
