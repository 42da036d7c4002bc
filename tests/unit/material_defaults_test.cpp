// The render options a scene's materials choose (pipeline/scene_ready.h:
// default_render_options with the scene): physically based materials get the
// Khronos PBR Neutral tone map and bounces for their reflections, more when
// one transmits, with a note; Phong-only scenes keep their format's options.
#include "rayform/pipeline/scene_ready.h"

#include <gtest/gtest.h>

namespace rayform {
namespace {

Scene scene_of(std::vector<Material> materials) {
  Scene s;
  s.materials = std::move(materials);
  return s;
}

Material pbr_material(float transmission = 0.f) {
  Material m;
  m.model = Material::Model::metallic_roughness;
  m.pbr.transmission = transmission;
  return m;
}

TEST(MaterialDefaults, PhongScenesKeepTheFormatsOptions) {
  for (SceneFormat f : {SceneFormat::obj, SceneFormat::gltf, SceneFormat::course_txt}) {
    const RenderOptions want = default_render_options(f, CourseDialect::a5);
    const RenderOptions got = default_render_options(scene_of({Material{}, Material{}}), f, CourseDialect::a5);
    EXPECT_EQ(got.tone_map, ToneMap::none);
    EXPECT_EQ(got.bounces, want.bounces);
    EXPECT_EQ(got.width, want.width);
    EXPECT_EQ(got.exposure_ev, 0.f);
  }
  EXPECT_EQ(default_render_options(scene_of({}), SceneFormat::gltf).tone_map, ToneMap::none);
}

TEST(MaterialDefaults, PbrScenesAreToneMappedAndReflect) {
  const RenderOptions o = default_render_options(scene_of({Material{}, pbr_material()}), SceneFormat::gltf);
  EXPECT_EQ(o.tone_map, ToneMap::khr_neutral);
  EXPECT_EQ(o.bounces, pbr_default_bounces);
  EXPECT_EQ(o.width, asset_image_size);
  EXPECT_FALSE(uses_transmission(scene_of({pbr_material()})));
}

TEST(MaterialDefaults, TransmissionGetsMoreBounces) {
  const Scene glass = scene_of({pbr_material(), pbr_material(0.5f)});
  EXPECT_TRUE(uses_transmission(glass));
  const RenderOptions o = default_render_options(glass, SceneFormat::gltf);
  EXPECT_EQ(o.tone_map, ToneMap::khr_neutral);
  EXPECT_EQ(o.bounces, transmission_default_bounces);
  // A Phong material's pbr fields are not read.
  Material phong;
  phong.pbr.transmission = 1.f;
  EXPECT_FALSE(uses_transmission(scene_of({phong})));
}

TEST(MaterialDefaults, ReadySceneNotesTheTransmissionBounces) {
  LoadedScene loaded;
  loaded.format = SceneFormat::gltf;
  loaded.scene = scene_of({pbr_material(1.f)});
  const ReadyScene ready = make_scene_ready(loaded, "glass.gltf");
  EXPECT_EQ(ready.render.bounces, transmission_default_bounces);
  EXPECT_EQ(ready.render.tone_map, ToneMap::khr_neutral);
  EXPECT_EQ(ready.bounces_note, "glass.gltf uses transmission: --bounces 8 by default");
  loaded.scene = scene_of({pbr_material()});
  EXPECT_EQ(make_scene_ready(loaded, "metal.gltf").bounces_note, "");
}

}  // namespace
}  // namespace rayform
