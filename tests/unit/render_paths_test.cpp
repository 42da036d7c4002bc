// The specialised render paths (src/render/render.cpp) give exactly the image
// of the generic one: colour, depth, normals and albedo, bit for bit, for the
// course scenes of both dialects (with and without shadows and bounces), our
// own textured scenes and a scene with cut-outs and single-sided materials.
// Also: single-sided materials cull back faces for camera and secondary rays,
// and the image does not depend on the thread count or the tile size.
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/render/scene_intersect.h"
#include "rayform/scene/procedural_mesh.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/importers/scene_io.h"
#include "test_paths.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <tuple>

namespace rayform {
namespace {
namespace fs = std::filesystem;

// Number of values that differ in their bits (NaN-safe, -0 != +0).
size_t differing(const float* a, const float* b, size_t n) {
  size_t d = 0;
  for (size_t i = 0; i < n; ++i) d += std::memcmp(a + i, b + i, sizeof(float)) != 0;
  return d;
}

void expect_identical(const RenderResult& a, const RenderResult& b, const std::string& what) {
  ASSERT_EQ(a.color.pixels.size(), b.color.pixels.size()) << what;
  EXPECT_EQ(differing(a.color.pixels.data(), b.color.pixels.data(), a.color.pixels.size()), 0u) << what << ": colour";
  ASSERT_EQ(a.depth.size(), b.depth.size()) << what;
  EXPECT_EQ(differing(a.depth.data(), b.depth.data(), a.depth.size()), 0u) << what << ": depth";
  ASSERT_EQ(a.normals.size(), b.normals.size()) << what;
  EXPECT_EQ(differing(&a.normals[0].x, &b.normals[0].x, 3 * a.normals.size()), 0u) << what << ": normals";
  EXPECT_EQ(differing(a.albedo.pixels.data(), b.albedo.pixels.data(), a.albedo.pixels.size()), 0u)
      << what << ": albedo";
}

// Renders `scene` specialised and generic with the same options; returns the path name.
std::string check_paths(const Scene& scene, RenderOptions o, const std::string& what) {
  PreparedScene p = prepare_scene(scene);
  o.depth = o.normals = o.albedo = true;
  o.generic = false;
  RenderResult special = render(p, o);
  std::string name = render_path_name(p, o);
  o.generic = true;
  RenderResult generic = render(p, o);
  expect_identical(special, generic, what + " [" + name + "]");
  return name;
}

TEST(RenderPaths, CourseScenesSpecialisedEqualsGeneric) {
  RAYFORM_REQUIRE_SHARED();
  int scenes = 0, specialised = 0;
  for (const char* dialect : {"2012", "2019"}) {
    for (const auto& e : fs::directory_iterator(test::shared_dir() / "course" / dialect)) {
      if (e.path().extension() != ".txt") continue;
      LoadedScene l = load_scene(e.path().string());
      for (int variant = 0; variant < 2; ++variant) {
        RenderOptions o;
        o.width = o.height = 48;
        o.shadows = variant == 1;
        o.bounces = variant == 1 ? 3 : 0;
        std::string name =
            check_paths(l.scene, o, e.path().filename().string() + (variant ? " -shadows -bounces 3" : ""));
        specialised += name != "generic";
      }
      ++scenes;
    }
  }
  EXPECT_EQ(scenes, 9 + 7);
  // Every course scene lacks cut-outs, so every one takes a specialised path.
  EXPECT_EQ(specialised, 2 * scenes);
}

TEST(RenderPaths, OwnTexturedScenesSpecialisedEqualsGeneric) {
  for (const char* name : {"textures_transformed.txt", "triangles_lights.txt", "transforms_nested.txt"}) {
    LoadedScene l = load_scene((test::source_dir() / "scenes" / "tests" / name).string());
    RenderOptions o;
    o.width = o.height = 48;
    o.shadows = true;
    o.spp = 4;
    check_paths(l.scene, o, name);
  }
}

// Each pixel is traced on its own: thread count and tile size do not change a bit.
TEST(RenderPaths, ImageDoesNotDependOnThreadsOrTiles) {
  LoadedScene l = load_scene((test::source_dir() / "scenes" / "tests" / "textures_transformed.txt").string());
  PreparedScene p = prepare_scene(l.scene);
  RenderOptions o;
  o.width = 61;  // not a multiple of the tile size
  o.height = 47;
  o.shadows = true;
  o.spp = 4;
  o.depth = o.normals = o.albedo = true;
  o.threads = 1;
  RenderResult one = render(p, o);
  for (auto [threads, tile] : {std::pair{2, 16}, std::pair{0, 16}, std::pair{2, 7}, std::pair{3, 64}}) {
    o.threads = threads;
    o.tile_size = tile;
    expect_identical(one, render(p, o), "threads " + std::to_string(threads) + ", tile " + std::to_string(tile));
  }
}

// Camera rays of one-mesh scenes go through the mesh eight at a time: the
// image is the one they give one by one, for a transformed mesh (course
// scene06), an OBJ without transform, odd sizes (partial packets at the ends
// of tile rows), small tiles, and with every output.
TEST(RenderPaths, EightRayPacketsGiveTheSameImage) {
  std::vector<std::pair<std::string, LoadedScene>> scenes;
  scenes.emplace_back("torus.obj", load_scene((test::source_dir() / "scenes" / "assets" / "torus.obj").string()));
  add_default_camera(scenes.back().second.scene);
  add_headlight(scenes.back().second.scene, 0);
  const fs::path scene06 = test::shared_dir() / "course" / "2012" / "scene06_bunny_1k.txt";
  if (fs::exists(scene06)) scenes.emplace_back("scene06", load_scene(scene06.string()));
  for (auto& [name, loaded] : scenes) {
    PreparedScene p = prepare_scene(loaded.scene);
    ASSERT_GE(sole_mesh_instance(p), 0) << name << " should take the packet path";
    for (auto [w, h, tile] : {std::tuple{61, 47, 16}, std::tuple{64, 64, 5}}) {
      RenderOptions o;
      o.width = w;
      o.height = h;
      o.tile_size = tile;
      o.shadows = true;
      o.depth = o.normals = o.albedo = true;
      o.packets = false;
      const RenderResult one_by_one = render(p, o);
      o.packets = true;
      expect_identical(one_by_one, render(p, o), name + " " + std::to_string(w) + "x" + std::to_string(h));
      int hits = 0;
      for (float d : one_by_one.depth) hits += std::isfinite(d);
      EXPECT_GT(hits, w * h / 20) << name;  // the mesh is in the picture
    }
  }
}

// Two quads across the camera's axis: the near one at z = 1 (red), wound so
// that its normal points away from the camera (we see its back) unless
// `near_facing`; the far one at z = 0 (blue) facing the camera.
Scene two_quads(bool near_double_sided, bool near_facing = false) {
  Scene s;
  Camera c;
  c.center = vec3(0.f, 0.f, 5.f);
  c.direction = vec3(0.f, 0.f, -1.f);
  c.fov_deg = 30.f;
  s.cameras.push_back(c);
  Light l;
  l.kind = Light::Kind::directional;
  l.direction = vec3(0.f, 0.f, -1.f);
  l.color = vec3(1.f);
  s.lights.push_back(l);
  s.background.color = vec3(0.25f);
  Material near, far;
  near.diffuse = vec3(1.f, 0.f, 0.f);
  near.double_sided = near_double_sided;
  far.diffuse = vec3(0.f, 0.f, 1.f);
  s.materials = {near, far};
  auto quad = [](float z, bool facing_camera) {
    Mesh m;
    m.positions = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
    m.indices = facing_camera ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
    return m;
  };
  s.meshes = {quad(1.f, near_facing), quad(0.f, true)};
  test::add_root_group(s, {test::shape_node(ShapeKind::mesh, 0, 0), test::shape_node(ShapeKind::mesh, 1, 1)});
  return s;
}

TEST(RenderPaths, SingleSidedMaterialsCullBackFaces) {
  RenderOptions o;
  o.width = o.height = 32;
  o.albedo = o.depth = true;
  // Pixel (16, 16): its ray is half a pixel off the axis, so its distances to
  // the planes z = 1 and z = 0 exceed 4 and 5 by under 1e-3 relative.
  const int centre = 16 * 32 + 16;
  {
    Scene both = two_quads(true);  // outlives its PreparedScene, which points to it
    PreparedScene p = prepare_scene(both);
    EXPECT_FALSE(p.features.single_sided);
    RenderResult r = render(p, o);
    EXPECT_EQ(r.albedo.pixels[3 * centre + 0], 1.f) << "double-sided: the near quad's back face is seen";
    EXPECT_NEAR(r.depth[centre], 4.f, 4e-3f);
  }
  Scene single = two_quads(false);
  PreparedScene p = prepare_scene(single);
  EXPECT_TRUE(p.features.single_sided);
  EXPECT_EQ(render_path_name(p, o).find("culling"), std::string::npos) << "culling needs the skipping path";
  RenderResult r = render(p, o);
  EXPECT_EQ(r.albedo.pixels[3 * centre + 0], 0.f) << "single-sided: the ray passes the back face";
  EXPECT_EQ(r.albedo.pixels[3 * centre + 2], 1.f) << "and hits the far quad";
  EXPECT_NEAR(r.depth[centre], 5.f, 5e-3f);
  // Front faces of single-sided materials stay.
  Scene front = two_quads(false, true);
  PreparedScene facing = prepare_scene(front);
  RenderResult rf = render(facing, o);
  EXPECT_EQ(rf.albedo.pixels[3 * centre + 0], 1.f);
  EXPECT_NEAR(rf.depth[centre], 4.f, 4e-3f);
  check_paths(two_quads(false), o, "single-sided quads");
}

// Two-sided lighting: a back face is shaded with its normal reversed (glTF
// doubleSided, OBJ); without it (course scenes) with the normal as given.
TEST(RenderPaths, TwoSidedLightingReversesBackFaceNormals) {
  RenderOptions o;
  o.width = o.height = 32;
  o.normals = true;
  const int centre = 16 * 32 + 16;
  for (bool two_sided : {false, true}) {
    Scene s = two_quads(true);  // we see the near quad's back; the light shines from the camera
    s.materials[0].two_sided_lighting = two_sided;
    PreparedScene p = prepare_scene(s);
    RenderResult r = render(p, o);
    const float* c = &r.color.pixels[3 * centre];
    if (two_sided) {
      EXPECT_GT(c[0], 0.99f) << "lit as its front: cos ~ 1 times the red diffuse colour";
      EXPECT_GT(r.normals[centre].z, 0.99f) << "the normal faces the viewer";
    } else {
      EXPECT_EQ(c[0], 0.f) << "the given normal faces away from the light";
      EXPECT_LT(r.normals[centre].z, -0.99f);
    }
    check_paths(s, o, two_sided ? "two-sided lighting" : "one-sided lighting");
    // Refractive materials keep their normals (inside and outside matter).
    s.materials[0].refraction_index = 1.5f;
    PreparedScene pr = prepare_scene(s);
    EXPECT_LT(render(pr, o).normals[centre].z, -0.99f);
  }
}

}  // namespace
}  // namespace rayform
