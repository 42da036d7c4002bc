// load_ready_scene (pipeline/scene_ready.h): an asset without camera or light
// gets the default camera and the light rig, said in notes (nothing printed);
// one with both is left alone; a course scene is left as the course defines
// it; the size and colour meaning follow the format; a caller's camera
// (orbit, adjustments) is in place before the rig, which follows it.
#include "rayform/pipeline/scene_ready.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/base/error.h"
#include "rayform/scene/scene_stats.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace rayform {
namespace {

std::string source(const char* relative) { return (test::source_dir() / relative).string(); }

TEST(SceneReady, AssetWithoutCameraOrLightGetsTheDefaultsAndNotes) {
  const std::string path = source("scenes/assets/materials.obj");
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  const ReadyScene s = load_ready_scene(path);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");  // the library prints nothing
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(s.format, SceneFormat::obj);
  // The default camera: the framing camera at Orbit{} around the bounds.
  ASSERT_EQ(s.scene.cameras.size(), 1u);
  const Camera framing = orbit_camera(scene_stats(s.scene).bounds, Orbit{});
  EXPECT_EQ(s.scene.cameras[0].center, framing.center);
  EXPECT_EQ(s.scene.cameras[0].direction, framing.direction);
  EXPECT_EQ(s.scene.cameras[0].name, "default");
  // The rig along it: head-light, key, fill.
  ASSERT_EQ(s.scene.lights.size(), 3u);
  EXPECT_EQ(s.scene.lights[0].name, "headlight");
  EXPECT_EQ(s.scene.lights[1].name, "key");
  EXPECT_EQ(s.scene.lights[2].name, "fill");
  EXPECT_NEAR(glm::length(s.scene.lights[0].direction - glm::normalize(framing.direction)), 0.f, 1e-6f);
  ASSERT_EQ(s.notes.size(), 2u);
  EXPECT_EQ(s.notes[0], path + " has no camera: added one framing the scene's bounds");
  EXPECT_EQ(s.notes[1],
            path + " has no light: added the default light rig (a head-light, a key and a fill) around the camera");
  // 512x512, linear colours.
  EXPECT_EQ(s.render.width, 512);
  EXPECT_EQ(s.render.height, 512);
  EXPECT_EQ(s.render.camera, 0);
  EXPECT_EQ(s.color.scene, SceneColors::linear);
  EXPECT_EQ(s.color.encoding, ColorEncoding::automatic);
  // And it renders: the centre pixel sees the model, lit.
  RenderOptions o = s.render;
  o.width = o.height = 33;
  const PreparedScene p = prepare_scene(s.scene);
  const RenderResult r = render(p, o);
  const float* centre = r.color.at(16, 16);
  EXPECT_GT(centre[0] + centre[1] + centre[2], 0.1f);
}

TEST(SceneReady, AssetWithCameraAndLightsIsLeftAlone) {
  const ReadyScene s = load_ready_scene(source("scenes/assets/features.gltf"));
  const LoadedScene plain = load_scene(source("scenes/assets/features.gltf"));
  EXPECT_TRUE(s.notes.empty());
  EXPECT_EQ(s.scene.cameras.size(), plain.scene.cameras.size());
  EXPECT_EQ(s.scene.lights.size(), plain.scene.lights.size());
  EXPECT_EQ(s.render.width, 512);
  EXPECT_EQ(s.color.scene, SceneColors::linear);
}

TEST(SceneReady, CourseSceneIsLeftAsTheCourseDefinesIt) {
  // A course scene without lights: the course lights it by its ambient light alone.
  const std::filesystem::path dir = test::temp_dir("scene_ready_course");
  const std::string file = (dir / "unlit.txt").string();
  std::ofstream(file) << "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }\n"
                         "Background { color 0.1 0.2 0.3 ambientLight 1 1 1 }\n"
                         "Materials { numMaterials 1 Material { diffuseColor 0.8 0.3 0.2 } }\n"
                         "Group { numObjects 1 MaterialIndex 0 Sphere { center 0 0 0 radius 1 } }\n";
  const ReadyScene s = load_ready_scene(file);
  std::filesystem::remove_all(dir);
  EXPECT_EQ(s.format, SceneFormat::course_txt);
  EXPECT_TRUE(s.notes.empty());
  EXPECT_TRUE(s.scene.lights.empty());
  ASSERT_EQ(s.scene.cameras.size(), 1u);
  EXPECT_EQ(s.scene.cameras[0].center, vec3(0, 0, 10));
  EXPECT_EQ(s.render.width, 200);  // the course's size
  EXPECT_EQ(s.render.height, 200);
  EXPECT_EQ(s.color.scene, SceneColors::display);
  // The same with scenes/default.txt, which has lights: exactly load_scene's scene.
  const ReadyScene d = load_ready_scene(source("scenes/default.txt"));
  const LoadedScene plain = load_scene(source("scenes/default.txt"));
  EXPECT_TRUE(d.notes.empty());
  ASSERT_EQ(d.scene.lights.size(), plain.scene.lights.size());
  for (size_t i = 0; i < d.scene.lights.size(); ++i)
    EXPECT_EQ(d.scene.lights[i].direction, plain.scene.lights[i].direction);
  EXPECT_EQ(d.scene.cameras[0].center, plain.scene.cameras[0].center);
}

TEST(SceneReady, CallersCameraComesBeforeTheRig) {
  const std::string path = source("scenes/assets/materials.obj");
  // An orbit replaces the cameras: no default camera, no note for it.
  ReadyOptions o;
  o.orbit = Orbit{90.f, 30.f, std::nullopt};
  const ReadyScene orbited = load_ready_scene(path, o);
  ASSERT_EQ(orbited.scene.cameras.size(), 1u);
  const Camera want = orbit_camera(scene_stats(orbited.scene).bounds, *o.orbit);
  EXPECT_EQ(orbited.scene.cameras[0].center, want.center);
  ASSERT_EQ(orbited.notes.size(), 1u);
  EXPECT_NE(orbited.notes[0].find("has no light"), std::string::npos);
  EXPECT_NEAR(glm::length(orbited.scene.lights[0].direction - glm::normalize(want.direction)), 0.f, 1e-6f);
  // An adjustment after the default camera: the rig follows the adjusted camera.
  ReadyOptions a;
  int calls = 0;
  a.adjust_camera = [&](Scene& s) {
    ++calls;
    ASSERT_EQ(s.cameras.size(), 1u);  // the default camera is there
    EXPECT_TRUE(s.lights.empty());    // the lights are not yet
    s.cameras[0].direction = vec3(1, 0, 0);
  };
  const ReadyScene adjusted = load_ready_scene(path, a);
  EXPECT_EQ(calls, 1);
  EXPECT_NEAR(glm::length(adjusted.scene.lights[0].direction - vec3(1, 0, 0)), 0.f, 1e-6f);
  // The camera rendered: the rig follows camera 1 of a scene with two.
  ReadyOptions second;
  second.camera = 1;
  second.adjust_camera = [](Scene& s) {
    Camera side = s.cameras[0];
    side.direction = vec3(0, -1, 0);
    side.up = vec3(0, 0, -1);
    s.cameras.push_back(side);
  };
  const ReadyScene two = load_ready_scene(path, second);
  EXPECT_EQ(two.render.camera, 1);
  EXPECT_NEAR(glm::length(two.scene.lights[0].direction - vec3(0, -1, 0)), 0.f, 1e-6f);
}

TEST(SceneReady, DefaultsPerFormat) {
  EXPECT_EQ(default_render_options(SceneFormat::course_txt).width, 200);
  EXPECT_EQ(default_render_options(SceneFormat::course_txt).height, 200);
  EXPECT_EQ(default_render_options(SceneFormat::obj).width, 512);
  EXPECT_EQ(default_render_options(SceneFormat::gltf).height, 512);
  EXPECT_EQ(scene_colors(SceneFormat::course_txt), SceneColors::display);
  EXPECT_EQ(scene_colors(SceneFormat::obj), SceneColors::linear);
  EXPECT_EQ(scene_colors(SceneFormat::gltf), SceneColors::linear);
  EXPECT_THROW(load_ready_scene(source("scenes/assets/features.bin")), Error);
}

}  // namespace
}  // namespace rayform
