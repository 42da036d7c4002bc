// The writers (importers/scene_writer.h, course_txt/course_writer.h,
// obj/obj_writer.h, gltf/gltf_writer.h) at the Scene level: a scene written
// and read back must give the same instances, matrices, materials, cameras,
// lights and background, with analytic spheres and planes restored exactly
// from the glTF extras; what a format cannot hold must be reported.
#include "rayform/importers/gltf/gltf_writer.h"
#include "rayform/importers/gltf/gltf_material.h"
#include "rayform/base/error.h"
#include "rayform/scene/node_walk.h"
#include "rayform/scene/scene_stats.h"
#include "rayform/importers/scene_io.h"
#include "rayform/importers/scene_writer.h"
#include "rayform/importers/shape_tessellation.h"
#include "test_importers.h"
#include "test_paths.h"
#include "test_scenes.h"
#include "rayform/importers/texture_files.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <random>

namespace rayform {
namespace {
namespace fs = std::filesystem;

const char* kCourseScenes[] = {"scene01_plane", "scene02_cube",      "scene03_sphere",
                               "scene04_axes",  "scene05_bunny_200", "scene06_bunny_1k",
                               "scene07_shine", "scene08_c",         "scene09_s"};

fs::path course(const std::string& name) { return test::shared_dir() / "course" / "2012" / (name + ".txt"); }
using test::any_contains;
using test::asset;

std::string joined(const std::vector<std::string>& v) {
  std::string out;
  for (const std::string& s : v) out += s + "\n";
  return out;
}

struct Instance {
  ShapeKind kind;
  int shape;
  int material;
  mat4 world;
};

std::vector<Instance> instances(const Scene& s) {
  std::vector<Instance> out;
  for_each_shape_node(s, [&](const Node& n, const mat4& m) { out.push_back({n.shape_kind, n.shape, n.material, m}); });
  return out;
}

Scene write_and_read(const Scene& scene, const fs::path& path, const SaveOptions& options = {},
                     std::vector<std::string>* messages = nullptr, std::vector<std::string>* warnings = nullptr,
                     std::optional<CourseDialect> dialect = std::nullopt) {
  save_scene(scene, path.string(), options, messages);
  LoadedScene l = load_scene(path.string(), LoadOptions{dialect});
  if (warnings) *warnings = l.warnings;
  return std::move(l.scene);
}

void expect_same_material(const Material& a, const Material& b, const std::string& what) {
  EXPECT_EQ(a.diffuse, b.diffuse) << what;
  EXPECT_EQ(a.specular, b.specular) << what;
  EXPECT_EQ(a.shininess, b.shininess) << what;
  EXPECT_EQ(a.texture_modulates, b.texture_modulates) << what;
  EXPECT_EQ(a.diffuse_texture == invalid, b.diffuse_texture == invalid) << what;
  EXPECT_EQ(a.emission, b.emission) << what;
  EXPECT_EQ(a.refraction_index, b.refraction_index) << what;
  EXPECT_EQ(a.two_sided_lighting, b.two_sided_lighting) << what;
}

// Mesh a against mesh b, triangle by triangle (vertex order may differ).
void expect_same_mesh(const Mesh& a, const Mesh& b, float normal_tol, float uv_tol, const std::string& what) {
  ASSERT_EQ(a.triangle_count(), b.triangle_count()) << what;
  ASSERT_EQ(a.normals.empty(), b.normals.empty()) << what;
  ASSERT_EQ(a.uvs.empty(), b.uvs.empty()) << what;
  int bad = 0;
  for (size_t c = 0; c < a.indices.size() && bad < 5; ++c) {
    uint32_t i = a.indices[c], j = b.indices[c];
    if (a.positions[i] != b.positions[j]) {
      ADD_FAILURE() << what << ": corner " << c << " position differs";
      ++bad;
    }
    // (A zero normal, which readers make where only degenerate faces meet, is
    // not data a format keeps: OBJ readers make it again from the faces.)
    if (!a.normals.empty() && a.normals[i] != vec3(0.f) && glm::length(a.normals[i] - b.normals[j]) > normal_tol) {
      ADD_FAILURE() << what << ": corner " << c << " normal differs by " << glm::length(a.normals[i] - b.normals[j])
                    << " (" << a.normals[i].x << " " << a.normals[i].y << " " << a.normals[i].z << " vs "
                    << b.normals[j].x << " " << b.normals[j].y << " " << b.normals[j].z << ")";
      ++bad;
    }
    if (!a.uvs.empty() && glm::length(a.uvs[i] - b.uvs[j]) > uv_tol) {
      ADD_FAILURE() << what << ": corner " << c << " uv differs by " << glm::length(a.uvs[i] - b.uvs[j]);
      ++bad;
    }
  }
}

// Texels whose RGB differ (the reader decodes glTF images to RGBA).
size_t rgb_differences(const Texture& ta, const Texture& tb) {
  // The same file bytes (a copied PNG) need no decoding.
  if (!ta.path.empty() && !tb.path.empty() && fs::exists(ta.path) && fs::exists(tb.path) &&
      read_file_bytes(ta.path) == read_file_bytes(tb.path))
    return 0;
  Pixels8 pa = texture_pixels(ta), pb = texture_pixels(tb);
  if (pa.width != pb.width || pa.height != pb.height) return size_t(-1);
  size_t differ = 0;
  for (size_t p = 0; p < size_t(pa.width) * size_t(pa.height); ++p)
    for (int k = 0; k < 3; ++k)
      differ += pa.data[p * size_t(pa.channels) + size_t(std::min(k, pa.channels - 1))] !=
                pb.data[p * size_t(pb.channels) + size_t(std::min(k, pb.channels - 1))];
  return differ;
}

// Everything a course scene holds, compared between the original and a
// scene read back from a written file.
void expect_same_course_scene(const Scene& a, const Scene& b, float normal_tol, float uv_tol, const std::string& what) {
  ASSERT_EQ(b.cameras.size(), 1u) << what;
  const Camera &ca = a.cameras[0], &cb = b.cameras[0];
  EXPECT_EQ(ca.center, cb.center) << what;
  EXPECT_EQ(ca.direction, cb.direction) << what;
  EXPECT_EQ(ca.up, cb.up) << what;
  EXPECT_EQ(ca.fov_deg, cb.fov_deg) << what;
  EXPECT_EQ(ca.aspect, cb.aspect) << what;
  EXPECT_EQ(ca.up_vector, cb.up_vector) << what;
  ASSERT_EQ(a.lights.size(), b.lights.size()) << what;
  for (size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].kind, b.lights[i].kind) << what;
    EXPECT_EQ(a.lights[i].color, b.lights[i].color) << what;
    EXPECT_EQ(a.lights[i].falloff, b.lights[i].falloff) << what;
    if (a.lights[i].kind == Light::Kind::directional) EXPECT_EQ(a.lights[i].direction, b.lights[i].direction) << what;
    else EXPECT_EQ(a.lights[i].position, b.lights[i].position) << what;
  }
  EXPECT_EQ(a.background.color, b.background.color) << what;
  EXPECT_EQ(a.background.ambient, b.background.ambient) << what;
  ASSERT_EQ(a.materials.size(), b.materials.size()) << what;
  for (size_t i = 0; i < a.materials.size(); ++i) {
    expect_same_material(a.materials[i], b.materials[i], what + " material " + std::to_string(i));
    if (a.materials[i].diffuse_texture != invalid && b.materials[i].diffuse_texture != invalid) {
      const Texture &ta = a.textures[size_t(a.materials[i].diffuse_texture)],
                    &tb = b.textures[size_t(b.materials[i].diffuse_texture)];
      EXPECT_EQ(ta.lookup, tb.lookup) << what;
      EXPECT_EQ(ta.srgb, tb.srgb) << what;
      EXPECT_EQ(ta.wrap_u, tb.wrap_u) << what;
      EXPECT_EQ(rgb_differences(ta, tb), 0u) << what << ": texture pixels";
    }
  }
  std::vector<Instance> ia = instances(a), ib = instances(b);
  ASSERT_EQ(ia.size(), ib.size()) << what;
  SceneStats sa = scene_stats(a), sb = scene_stats(b);
  EXPECT_EQ(sa.spheres, sb.spheres) << what;
  EXPECT_EQ(sa.planes, sb.planes) << what;
  EXPECT_EQ(sa.mesh_triangles, sb.mesh_triangles) << what;
  for (size_t i = 0; i < ia.size(); ++i) {
    const std::string w = what + " instance " + std::to_string(i);
    ASSERT_EQ(ia[i].kind, ib[i].kind) << w;
    EXPECT_EQ(ia[i].material, ib[i].material) << w;
    EXPECT_EQ(ia[i].world, ib[i].world) << w;
    switch (ia[i].kind) {
      case ShapeKind::sphere:  // exactly the analytic sphere, not a tessellation
        EXPECT_EQ(a.spheres[size_t(ia[i].shape)].center, b.spheres[size_t(ib[i].shape)].center) << w;
        EXPECT_EQ(a.spheres[size_t(ia[i].shape)].radius, b.spheres[size_t(ib[i].shape)].radius) << w;
        break;
      case ShapeKind::plane:
        EXPECT_EQ(a.planes[size_t(ia[i].shape)].normal, b.planes[size_t(ib[i].shape)].normal) << w;
        EXPECT_EQ(a.planes[size_t(ia[i].shape)].offset, b.planes[size_t(ib[i].shape)].offset) << w;
        break;
      case ShapeKind::triangle:
        EXPECT_EQ(a.triangles[size_t(ia[i].shape)].vertices, b.triangles[size_t(ib[i].shape)].vertices) << w;
        break;
      case ShapeKind::mesh:
        expect_same_mesh(a.meshes[size_t(ia[i].shape)], b.meshes[size_t(ib[i].shape)], normal_tol, uv_tol, w);
        break;
    }
  }
}

// ---- course scenes through glTF and through the course writer --------------------------

TEST(SceneWriter, CourseScenesThroughGlbComeBackExactly) {
  RAYFORM_REQUIRE_SHARED();
  fs::path dir = test::temp_dir("writer-course-glb");
  for (const char* name : kCourseScenes) {
    Scene a = load_scene(course(name).string()).scene;
    std::vector<std::string> warnings;
    Scene b = write_and_read(a, dir / (std::string(name) + ".glb"), {}, nullptr, &warnings);
    EXPECT_TRUE(warnings.empty()) << name << ":\n" << joined(warnings);
    // uvs pass through v_gltf = 1 - v: one rounding of 1 - v.
    expect_same_course_scene(a, b, 1e-6f, 1e-7f, std::string(name) + ".glb");
  }
  fs::remove_all(dir);
}

TEST(SceneWriter, Course2019ScenesThroughGltfComeBackExactly) {
  // Falloff, the raw up vector, 2019 mesh normals, cube maps, refraction.
  RAYFORM_REQUIRE_SHARED();
  fs::path dir = test::temp_dir("writer-course-2019");
  int cube_maps = 0;
  for (const auto& e : fs::directory_iterator(test::shared_dir() / "course" / "2019")) {
    if (e.path().extension() != ".txt") continue;
    const std::string name = e.path().stem().string();
    Scene a = load_scene(e.path().string(), LoadOptions{CourseDialect::v2019}).scene;
    std::vector<std::string> warnings;
    // .gltf with the images beside it (the cube maps' 1024x1024 PNGs are copied, not re-encoded)
    Scene b = write_and_read(a, dir / (name + ".gltf"), {}, nullptr, &warnings);
    EXPECT_TRUE(warnings.empty()) << name << ":\n" << joined(warnings);
    expect_same_course_scene(a, b, 1e-6f, 1e-7f, name + ".gltf (2019)");
    ASSERT_EQ(a.background.cube_map[0] != invalid, b.background.cube_map[0] != invalid) << name;
    if (a.background.cube_map[0] != invalid) {
      ++cube_maps;
      EXPECT_EQ(a.background.cube_map_dir, b.background.cube_map_dir);
      for (int f = 0; f < 6; ++f) {
        const Texture &ta = a.textures[size_t(a.background.cube_map[size_t(f)])],
                      &tb = b.textures[size_t(b.background.cube_map[size_t(f)])];
        EXPECT_EQ(ta.lookup, tb.lookup);
        EXPECT_EQ(ta.srgb, tb.srgb);
        EXPECT_EQ(rgb_differences(ta, tb), 0u) << name << " cube map face " << f;
      }
    }
    // And back to a course file in the 2019 dialect, which the writer picks by itself.
    std::vector<std::string> messages;
    Scene c = write_and_read(b, dir / (name + ".txt"), {}, &messages, nullptr, CourseDialect::v2019);
    expect_same_course_scene(a, c, 1e-6f, 1e-7f, name + ".gltf -> .txt (2019)");
  }
  EXPECT_GE(cube_maps, 1);
  fs::remove_all(dir);
}

TEST(SceneWriter, CourseScenesThroughTxtComeBackExactly) {
  RAYFORM_REQUIRE_SHARED();
  fs::path dir = test::temp_dir("writer-course-txt");
  for (const char* name : kCourseScenes) {
    Scene a = load_scene(course(name).string()).scene;
    std::vector<std::string> messages;
    Scene b = write_and_read(a, dir / (std::string(name) + ".txt"), {}, &messages);
    // The course computes the normals of the written meshes again: the same ones.
    EXPECT_FALSE(any_contains(messages, "normals")) << joined(messages);
    expect_same_course_scene(a, b, 1e-6f, 0.f, std::string(name) + ".txt");
    // ... and so does glb -> txt.
    Scene c = write_and_read(load_scene((dir / (std::string(name) + ".txt")).string()).scene,
                             dir / (std::string(name) + "_2.glb"));
    Scene d = write_and_read(c, dir / (std::string(name) + "_3.txt"));
    expect_same_course_scene(a, d, 1e-6f, 1e-7f, std::string(name) + " txt->glb->txt");
  }
  fs::remove_all(dir);
}

TEST(SceneWriter, GlbWithoutShapeExtrasHoldsTessellations) {
  RAYFORM_REQUIRE_SHARED();
  fs::path dir = test::temp_dir("writer-tess");
  Scene a = load_scene(course("scene01_plane").string()).scene;
  SaveOptions o;
  o.shape_extras = false;
  o.sphere_segments = 16;
  std::vector<std::string> messages;
  Scene b = write_and_read(a, dir / "t.glb", o, &messages);
  SceneStats s = scene_stats(b);
  EXPECT_EQ(s.spheres, 0u);
  EXPECT_EQ(s.planes, 0u);
  // 5 spheres of 2 x 16 x 7 triangles and one quad.
  EXPECT_EQ(s.mesh_triangles, 5u * 224u + 2u);
  EXPECT_TRUE(any_contains(messages, "5 sphere(s) tessellated (16 segments, 224 triangles each)")) << joined(messages);
  // Every vertex of a tessellated sphere lies on it.
  for (const Instance& i : instances(b)) {
    const Mesh& m = b.meshes[size_t(i.shape)];
    if (m.triangle_count() != 224) continue;
    vec3 c(0.f);
    for (const vec3& p : m.positions) c += p;
    c /= float(m.positions.size());
    bool found = false;
    for (const Sphere& sp : a.spheres) {
      if (glm::length(sp.center - c) > 1e-4f) continue;
      found = true;
      for (const vec3& p : m.positions) EXPECT_NEAR(glm::length(p - sp.center), sp.radius, 1e-5f);
    }
    EXPECT_TRUE(found);
  }
  fs::remove_all(dir);
}

// ---- OBJ assets -------------------------------------------------------------------------------

TEST(SceneWriter, ObjThroughGltfAndObjKeepsCounts) {
  RAYFORM_REQUIRE_SHARED();
  fs::path dir = test::temp_dir("writer-obj");
  for (const char* rel :
       {"duck/duck.obj", "obj/spider/spider.obj", "obj/cornell-box/cornell-box.obj", "obj/suzanne.obj"}) {
    Scene a = load_scene(asset(rel).string()).scene;
    Scene b = write_and_read(a, dir / "m.gltf");
    Scene c = write_and_read(b, dir / "m.obj");
    MeshTotals ta = mesh_totals(a), tb = mesh_totals(b), tc = mesh_totals(c);
    EXPECT_EQ(ta.triangles, tb.triangles) << rel;
    EXPECT_EQ(ta.vertices, tc.vertices) << rel;
    EXPECT_EQ(ta.uvs, tc.uvs) << rel;
    EXPECT_EQ(ta.triangles, tc.triangles) << rel;
    ASSERT_EQ(a.materials.size(), b.materials.size()) << rel;
    ASSERT_EQ(a.materials.size(), c.materials.size()) << rel;
    for (size_t i = 0; i < a.materials.size(); ++i) {
      expect_same_material(a.materials[i], b.materials[i], std::string(rel) + " via glTF");
      expect_same_material(a.materials[i], c.materials[i], std::string(rel) + " via glTF and OBJ");
      EXPECT_EQ(a.materials[i].name, c.materials[i].name);
    }
    EXPECT_EQ(scene_stats(a).instances, scene_stats(c).instances) << rel;
    // OBJ straight to OBJ: the same meshes, corner by corner.
    Scene d = write_and_read(a, dir / "d.obj");
    ASSERT_EQ(a.meshes.size(), d.meshes.size()) << rel;
    for (size_t i = 0; i < a.meshes.size(); ++i) {
      expect_same_mesh(a.meshes[i], d.meshes[i], 1e-6f, 0.f, rel);
      EXPECT_EQ(a.meshes[i].positions.size(), d.meshes[i].positions.size()) << rel;
      EXPECT_EQ(a.meshes[i].face_materials, d.meshes[i].face_materials) << rel;
    }
  }
  fs::remove_all(dir);
}

// ---- a scene built here with what the course scenes lack -------------------------------------

Scene feature_scene() {
  Scene s;
  Camera cam;
  cam.projection = Camera::Projection::perspective;
  cam.aspect = Camera::Aspect::fit;
  cam.center = vec3(1.f, 2.f, 9.f);
  cam.direction = vec3(-0.1f, -0.2f, -1.f);
  cam.up = vec3(0.1f, 1.f, 0.2f);  // not orthogonal to the direction
  cam.up_vector = Camera::UpVector::raw;
  cam.fov_deg = 35.f;
  s.cameras.push_back(cam);
  Camera ortho = cam;
  ortho.name = "top";
  ortho.projection = Camera::Projection::orthographic;
  ortho.ortho_height = 7.5f;
  ortho.up_vector = Camera::UpVector::orthonormal;
  ortho.up = vec3(0.f, 1.f, 0.f);
  s.cameras.push_back(ortho);
  Light spot;
  spot.kind = Light::Kind::spot;
  spot.position = vec3(0.f, 5.f, 2.f);
  spot.direction = vec3(0.f, -1.f, -0.3f);
  spot.color = vec3(3.f, 2.f, 1.f);
  spot.falloff = 2.f;
  spot.spot_inner_deg = 10.f;
  spot.spot_outer_deg = 30.f;
  s.lights.push_back(spot);
  Light sun;
  sun.direction = vec3(1.f, -1.f, -1.f);
  sun.color = vec3(0.5f, 0.6f, 0.7f);
  s.lights.push_back(sun);
  s.background.color = vec3(0.1f, 0.2f, 0.3f);
  s.background.ambient = vec3(0.05f);

  Texture tex;
  tex.name = "checker";
  tex.width = 4;
  tex.height = 2;
  tex.channels = 3;
  for (int i = 0; i < 8; ++i) tex.pixels.insert(tex.pixels.end(), {uint8_t(i * 30), uint8_t(255 - i * 30), 7});
  tex.srgb = true;
  s.textures.push_back(tex);
  Material red;
  red.name = "red glow";
  red.diffuse = vec3(0.8f, 0.1f, 0.1f);
  red.specular = vec3(0.3f);
  red.shininess = 40.f;
  red.emission = vec3(2.f, 0.5f, 0.f);
  s.materials.push_back(red);
  Material textured;
  textured.name = "textured";
  textured.diffuse = vec3(1.f);
  textured.diffuse_texture = 0;
  textured.texture_modulates = true;
  textured.uv_transform.offset = vec2(0.25f, 0.5f);
  textured.uv_transform.rotation = 0.3f;
  textured.uv_transform.scale = vec2(2.f, 3.f);
  s.materials.push_back(textured);

  // A quad of two triangles with two materials, vertex colours and uvs.
  Mesh m;
  m.name = "quad";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.face_materials = {0, 1};
  s.meshes.push_back(m);
  s.spheres.push_back(Sphere{vec3(0.5f, 0.25f, -1.f), 0.75f});
  s.triangles.push_back(Triangle{{vec3(2, 0, 0), vec3(3, 0, 0), vec3(2, 1, 0.5f)}});

  auto add = [&](Node n) {
    s.nodes.push_back(std::move(n));
    return int(s.nodes.size()) - 1;
  };
  Node quad = test::shape_node(ShapeKind::mesh, 0, 0);
  quad.name = "quad";
  Node sphere = test::shape_node(ShapeKind::sphere, 0, 0);
  sphere.name = "sphere";
  Node tri = test::shape_node(ShapeKind::triangle, 0);  // no material
  tri.name = "triangle";
  // A shear: scale along x after a rotation, which no single glTF node holds.
  Node sheared;
  sheared.kind = Node::Kind::transform;
  sheared.name = "sheared";
  sheared.local = glm::scale(mat4(1.f), vec3(2.f, 1.f, 1.f)) * glm::rotate(mat4(1.f), 0.7f, vec3(0.f, 0.f, 1.f));
  sheared.children = {add(sphere)};
  Node moved;
  moved.kind = Node::Kind::transform;
  moved.name = "moved";
  moved.local = glm::translate(mat4(1.f), vec3(0.f, 0.f, -3.f));
  moved.children = {add(quad), add(tri)};
  Node root;
  root.kind = Node::Kind::group;
  root.name = "root";
  root.children = {add(sheared), add(moved)};
  s.root = add(root);
  return s;
}

void expect_near(const mat4& a, const mat4& b, float tol, const std::string& what) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << what << " [" << c << "][" << r << "]";
}

TEST(SceneWriter, GltfKeepsWhatTheCourseScenesLack) {
  fs::path dir = test::temp_dir("writer-features");
  Scene a = feature_scene();
  for (const char* file : {"f.glb", "f.gltf", "e.gltf"}) {
    SaveOptions o;
    o.embed = std::string(file) == "e.gltf";
    std::vector<std::string> messages, warnings;
    Scene b = write_and_read(a, dir / file, o, &messages, &warnings);
    EXPECT_TRUE(warnings.empty()) << joined(warnings);
    EXPECT_TRUE(any_contains(messages, "shear")) << joined(messages);
    // Cameras and lights, exactly.
    ASSERT_EQ(b.cameras.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(a.cameras[i].center, b.cameras[i].center);
      EXPECT_EQ(a.cameras[i].direction, b.cameras[i].direction);
      EXPECT_EQ(a.cameras[i].up, b.cameras[i].up);
      EXPECT_EQ(a.cameras[i].up_vector, b.cameras[i].up_vector);
      EXPECT_EQ(a.cameras[i].aspect, b.cameras[i].aspect);
      EXPECT_EQ(a.cameras[i].projection, b.cameras[i].projection);
      EXPECT_EQ(a.cameras[i].name, b.cameras[i].name);
    }
    EXPECT_EQ(b.cameras[1].ortho_height, 7.5f);
    EXPECT_EQ(b.cameras[0].fov_deg, 35.f);
    ASSERT_EQ(b.lights.size(), 2u);
    EXPECT_EQ(b.lights[0].kind, Light::Kind::spot);
    EXPECT_EQ(b.lights[0].color, a.lights[0].color);
    EXPECT_EQ(b.lights[0].falloff, 2.f);
    EXPECT_EQ(b.lights[0].position, a.lights[0].position);
    EXPECT_EQ(b.lights[0].direction, a.lights[0].direction);
    EXPECT_NEAR(b.lights[0].spot_outer_deg, 30.f, 1e-4f);
    EXPECT_EQ(b.lights[1].direction, a.lights[1].direction);
    EXPECT_EQ(b.background.color, a.background.color);
    EXPECT_EQ(b.background.ambient, a.background.ambient);
    // Materials: Phong values, emission above 1, the rotated uv transform.
    // The triangle has no material: glTF's default material, which the reader adds.
    ASSERT_EQ(b.materials.size(), 3u);
    EXPECT_EQ(b.materials[2].diffuse, vec3(1.f));
    EXPECT_EQ(b.materials[2].specular, vec3(0.f));
    expect_same_material(a.materials[0], b.materials[0], file);
    expect_same_material(a.materials[1], b.materials[1], file);
    EXPECT_NEAR(b.materials[1].uv_transform.rotation, 0.3f, 1e-6f);
    EXPECT_NEAR(b.materials[1].uv_transform.offset.x, 0.25f, 1e-6f);
    EXPECT_NEAR(b.materials[1].uv_transform.offset.y, 0.5f, 1e-6f);
    EXPECT_EQ(b.materials[1].uv_transform.scale, vec2(2.f, 3.f));
    ASSERT_EQ(b.textures.size(), 1u);
    EXPECT_EQ(b.textures[0].pixels.size() / size_t(b.textures[0].channels), 8u);
    // Shapes: the sphere under the shear (two nodes), the quad split per material, the triangle.
    SceneStats st = scene_stats(b);
    EXPECT_EQ(st.spheres, 1u);
    EXPECT_EQ(st.triangles, 1u);
    EXPECT_EQ(st.mesh_triangles, 2u);
    EXPECT_EQ(st.instances, 4u);  // sphere, quad x 2 materials, triangle
    for (const Instance& i : instances(b)) {
      if (i.kind == ShapeKind::sphere) {
        expect_near(i.world, a.nodes[size_t(a.nodes[size_t(a.root)].children[0])].local, 1e-6f, "sheared sphere");
        EXPECT_EQ(b.spheres[size_t(i.shape)].radius, 0.75f);
      } else if (i.kind == ShapeKind::triangle) {
        EXPECT_EQ(i.material, 2);
        EXPECT_EQ(b.triangles[size_t(i.shape)].vertices, a.triangles[0].vertices);
      } else {
        const Mesh& m = b.meshes[size_t(i.shape)];
        EXPECT_EQ(m.colors.size(), m.positions.size());
        EXPECT_EQ(m.triangle_count(), 1u);
        EXPECT_EQ(i.world, glm::translate(mat4(1.f), vec3(0.f, 0.f, -3.f)));
      }
    }
  }
  fs::remove_all(dir);
}

TEST(SceneWriter, TexturedMaterialOnShapesWithoutUvsStaysOneMaterial) {
  // glTF wants TEXCOORD_0 wherever a material has a texture: the sphere (no
  // uvs) gets an untextured copy, which the reader folds back.
  fs::path dir = test::temp_dir("writer-variant");
  Scene a = feature_scene();
  for (Node& n : a.nodes)
    if (n.kind == Node::Kind::shape && n.shape_kind == ShapeKind::sphere) n.material = 1;  // "textured"
  std::vector<std::string> messages;
  Scene b = write_and_read(a, dir / "v.glb", {}, &messages);
  EXPECT_TRUE(any_contains(messages, "untextured copy")) << joined(messages);
  ASSERT_EQ(b.materials.size(), 3u);  // the two, and glTF's default for the triangle
  for (const Instance& i : instances(b)) {
    if (i.kind == ShapeKind::sphere) {
      EXPECT_EQ(i.material, 1);
    }
  }
  EXPECT_NE(b.materials[1].diffuse_texture, invalid);
  fs::remove_all(dir);
}

TEST(SceneWriter, ObjReportsWhatItCannotHold) {
  fs::path dir = test::temp_dir("writer-obj-messages");
  Scene a = feature_scene();
  std::vector<std::string> messages;
  Scene b = write_and_read(a, dir / "f.obj", {}, &messages);
  for (const char* what : {"2 camera(s) dropped", "2 light(s) dropped (1 point or spot", "1 sphere(s) tessellated",
                           "OBJ has no transforms", "background", "rotated uv transform baked"})
    EXPECT_TRUE(any_contains(messages, what)) << what << " not in:\n" << joined(messages);
  // Every message names the file.
  for (const std::string& m : messages) EXPECT_EQ(m.rfind("f.obj: ", 0), 0u) << m;
  // The node "moved" (quad and triangle) is one section: one mesh of three
  // faces and three materials (the triangle's is the added default); vertex colours kept.
  MeshTotals t = mesh_totals(b);
  EXPECT_EQ(t.triangles, 2u + 2u * 64u * 31u + 1u);
  bool quad = false;
  for (const Mesh& m : b.meshes)
    if (!m.face_materials.empty()) {
      quad = true;
      EXPECT_EQ(m.face_materials.size(), 3u);
      // 4 quad corners, 2 of them again with the uvs of the second material's
      // baked (rotated) transform, and the triangle's 3.
      EXPECT_EQ(m.positions.size(), 9u);
      ASSERT_EQ(m.colors.size(), 9u);
      EXPECT_EQ(m.colors[m.indices[2]], vec3(0.f, 0.f, 1.f));
      EXPECT_EQ(b.materials[size_t(m.face_materials[2])].name, "default");
    }
  EXPECT_TRUE(quad);
  // The sheared sphere's tessellation went through the shear.
  float max_x = -infinity;
  for (const Mesh& m : b.meshes)
    if (m.triangle_count() == 2u * 64u * 31u)
      for (const vec3& p : m.positions) max_x = std::max(max_x, p.x);
  EXPECT_GT(max_x, 1.5f);
  fs::remove_all(dir);
}

TEST(SceneWriter, CourseWriterPicksTheDialectAndReportsLosses) {
  fs::path dir = test::temp_dir("writer-course-features");
  Scene a = feature_scene();
  std::vector<std::string> messages;
  // The spot light's falloff and the raw up vector need 2019; the file says so by `falloff`.
  Scene b = write_and_read(a, dir / "f.txt", {}, &messages);
  EXPECT_TRUE(any_contains(messages, "written in the 2019 dialect")) << joined(messages);
  for (const char* what : {"1 camera(s) after the first dropped", "spot light(s) written as point lights", "emission",
                           "vertex colours", "added white material"})
    EXPECT_TRUE(any_contains(messages, what)) << what << " not in:\n" << joined(messages);
  ASSERT_EQ(b.lights.size(), 2u);
  EXPECT_EQ(b.lights[0].kind, Light::Kind::point);
  EXPECT_EQ(b.lights[0].falloff, 2.f);
  EXPECT_EQ(b.cameras[0].up_vector, Camera::UpVector::raw);
  EXPECT_EQ(b.cameras[0].up, a.cameras[0].up);
  // One material more: the white one for the triangle after a MaterialIndex.
  ASSERT_EQ(b.materials.size(), 3u);
  EXPECT_EQ(b.materials[2].diffuse, vec3(1.f));
  // The sheared sphere is a Transform around a Sphere: exact sphere, same matrix.
  std::vector<Instance> ib = instances(b);
  ASSERT_EQ(ib.size(), 4u);  // sphere, 2 quad parts, triangle
  int spheres = 0;
  for (const Instance& i : ib)
    if (i.kind == ShapeKind::sphere) {
      ++spheres;
      EXPECT_EQ(i.world, a.nodes[size_t(a.nodes[size_t(a.root)].children[0])].local);
      EXPECT_EQ(b.spheres[size_t(i.shape)].center, a.spheres[0].center);
    } else if (i.kind == ShapeKind::triangle) {
      EXPECT_EQ(i.material, 2);
    }
  EXPECT_EQ(spheres, 1);
  // Asked for 2012: the falloff is dropped, and said so.
  messages.clear();
  SaveOptions o;
  o.dialect = CourseDialect::v2012;
  Scene c = write_and_read(a, dir / "g.txt", o, &messages);
  EXPECT_TRUE(any_contains(messages, "lose their falloff")) << joined(messages);
  EXPECT_EQ(c.lights[0].falloff, 0.f);
  fs::remove_all(dir);
}

TEST(SceneWriter, FlattenBakesTransforms) {
  RAYFORM_REQUIRE_SHARED();
  fs::path dir = test::temp_dir("writer-flatten");
  for (const char* name : {"scene03_sphere", "scene04_axes", "scene07_shine"}) {
    Scene a = load_scene(course(name).string()).scene;
    SaveOptions o;
    o.flatten = true;
    std::vector<std::string> messages;
    Scene b = write_and_read(a, dir / "f.glb", o, &messages);
    std::vector<Instance> ia = instances(a), ib = instances(b);
    ASSERT_EQ(ia.size(), ib.size()) << name;
    for (size_t i = 0; i < ia.size(); ++i) {
      EXPECT_EQ(ib[i].world, mat4(1.f)) << name;
      EXPECT_EQ(ia[i].material, ib[i].material) << name;
      if (ia[i].kind == ShapeKind::mesh) {
        const Mesh &ma = a.meshes[size_t(ia[i].shape)], &mb = b.meshes[size_t(ib[i].shape)];
        ASSERT_EQ(ma.indices.size(), mb.indices.size());
        for (size_t c = 0; c < ma.indices.size(); ++c) {
          vec3 want = transform_point(ia[i].world, ma.positions[ma.indices[c]]);
          EXPECT_LT(glm::length(want - mb.positions[mb.indices[c]]), 1e-5f * std::max(1.f, glm::length(want)));
        }
      }
    }
    if (std::string(name) == "scene03_sphere") {  // under Scale 1 0.2 1: tessellated, and said so
      EXPECT_EQ(ib[0].kind, ShapeKind::mesh);
      EXPECT_TRUE(any_contains(messages, "--flatten: 1 sphere(s)")) << joined(messages);
    }
    if (std::string(name) == "scene07_shine") {  // untransformed spheres stay spheres
      for (const Instance& i : ib) EXPECT_EQ(i.kind, ShapeKind::sphere);
    }
  }
  fs::remove_all(dir);
}

// ---- the extras are checked against the data they annotate ---------------------------------

TEST(SceneWriter, StaleExtrasAreIgnoredWithAWarning) {
  RAYFORM_REQUIRE_SHARED();
  fs::path dir = test::temp_dir("writer-stale");
  Scene a = load_scene(course("scene03_sphere").string()).scene;
  save_scene(a, (dir / "s.gltf").string());
  nlohmann::json j;
  {
    std::ifstream in(dir / "s.gltf");
    in >> j;
  }
  // Another tool changed the base colour and moved the sphere's extras away from its vertices.
  j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.25, 0.5, 0.75, 1.0};
  bool edited = false;
  for (auto& m : j["meshes"])
    for (auto& p : m["primitives"])
      if (p.contains("extras") && p["extras"]["rayform"].contains("sphere")) {
        p["extras"]["rayform"]["sphere"]["radius"] = 2.0;
        edited = true;
      }
  ASSERT_TRUE(edited);
  {
    std::ofstream out(dir / "s.gltf");
    out << j.dump(1);
  }
  LoadedScene b = load_scene((dir / "s.gltf").string());
  EXPECT_TRUE(any_contains(b.warnings, "not those rayform wrote")) << joined(b.warnings);
  EXPECT_TRUE(any_contains(b.warnings, "no longer lie on the sphere")) << joined(b.warnings);
  EXPECT_EQ(b.scene.materials[0].diffuse, vec3(0.25f, 0.5f, 0.75f));  // the file's colour wins
  EXPECT_EQ(scene_stats(b.scene).spheres, 0u);                        // the mesh stays a mesh
  EXPECT_EQ(scene_stats(b.scene).meshes, 1u);
  fs::remove_all(dir);
}

// ---- the material formula ----------------------------------------------------------------------

// The reader's conversion (gltf_material.h, pbr_to_phong), as documented there.
void reader_pbr_to_phong(vec3 base, float metallic, float roughness, vec3* ks, float* n) {
  vec3 f0 = glm::mix(vec3(0.04f), base, metallic);
  float smooth = 1.f - roughness;
  *ks = f0 * smooth * smooth;
  float alpha2 = roughness * roughness * roughness * roughness;
  *n = std::clamp(alpha2 > 0.f ? (2.f / alpha2 - 2.f) / 4.f : 1024.f, 1.f, 1024.f);
}

TEST(SceneWriter, PhongToPbrInvertsTheReader) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < 1000; ++i) {
    vec3 base(0.1f + 0.9f * u(rng), 0.1f + 0.9f * u(rng), 0.1f + 0.9f * u(rng));
    float metallic = u(rng), roughness = 0.16f + 0.6f * u(rng);
    vec3 ks;
    float n;
    reader_pbr_to_phong(base, metallic, roughness, &ks, &n);
    PbrValues p = phong_to_pbr(base, ks, n);
    EXPECT_EQ(vec3(p.base), base);
    EXPECT_NEAR(p.roughness, roughness, 2e-5f) << "n = " << n;
    EXPECT_NEAR(p.metallic, metallic, 2e-4f);
  }
  // Outside the reader's range: no highlight is a matte dielectric.
  PbrValues matte = phong_to_pbr(vec3(0.5f), vec3(0.f), 20.f);
  EXPECT_EQ(matte.roughness, 1.f);
  EXPECT_EQ(matte.metallic, 0.f);
  EXPECT_EQ(phong_to_pbr(vec3(2.f, -1.f, 0.5f), vec3(0.f), 0.f).base, vec4(1.f, 0.f, 0.5f, 1.f));
}

// ---- files -------------------------------------------------------------------------------------

TEST(SceneWriter, ErrorsNameTheFileAndLeaveNothingBehind) {
  fs::path dir = test::temp_dir("writer-errors");
  Scene a = feature_scene();
  for (const char* ext : {".txt", ".obj", ".gltf", ".glb"}) {
    std::string bad = (dir / "missing" / (std::string("x") + ext)).string();
    try {
      save_scene(a, bad);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
  try {
    save_scene(a, (dir / "x.fbx").string());
    ADD_FAILURE() << "no error for .fbx";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("x.fbx"), std::string::npos) << e.what();
  }
  // A written file replaces an older one; no temporary file stays.
  std::ofstream(dir / "y.glb") << "old";
  SaveResult r = save_scene(a, (dir / "y.glb").string());
  ASSERT_EQ(r.files.size(), 1u);
  EXPECT_EQ(r.files[0], (dir / "y.glb").string());
  EXPECT_GT(fs::file_size(dir / "y.glb"), 100u);
  SaveResult g = save_scene(a, (dir / "y.gltf").string());
  EXPECT_EQ(g.files[0], (dir / "y.gltf").string());
  EXPECT_TRUE(fs::exists(dir / "y.bin"));
  EXPECT_TRUE(fs::exists(dir / "y_checker.png"));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  fs::remove_all(dir);
}

TEST(SceneWriter, TessellatedSphereIsClosedAndFacesOutwards) {
  for (int segments : {3, 4, 7, 64}) {
    Sphere s{vec3(1.f, -2.f, 3.f), 2.5f};
    Mesh m = tessellate_sphere(s, segments);
    int bands = std::max(2, segments / 2);
    EXPECT_EQ(m.triangle_count(), size_t(2 * segments * (bands - 1)));
    EXPECT_EQ(m.positions.size(), size_t(2 + segments * (bands - 1)));
    double volume = 0.0;  // divergence theorem: positive and close to 4/3 pi r^3 when closed and outward
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      dvec3 a = dvec3(m.positions[m.indices[3 * t]] - s.center),
            b = dvec3(m.positions[m.indices[3 * t + 1]] - s.center),
            c = dvec3(m.positions[m.indices[3 * t + 2]] - s.center);
      EXPECT_GT(glm::length(glm::cross(b - a, c - a)), 0.0);  // no degenerate triangle
      volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    double sphere = 4.0 / 3.0 * M_PI * 2.5 * 2.5 * 2.5;
    EXPECT_GT(volume, 0.0);
    if (segments == 64) {
      EXPECT_NEAR(volume / sphere, 1.0, 0.01);
    }
  }
}

}  // namespace
}  // namespace rayform
