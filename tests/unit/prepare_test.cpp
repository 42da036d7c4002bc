// prepare_scene (src/render/prepared_scene.h): the node tree flattened into
// instances, each used mesh built once however often it is instanced (and
// read once by the course reader) and, with a MeshAccelCache, once for all
// the frames of a turntable, only the textures of used materials decoded,
// and the feature flags the render loop relies on.
#include "rayform/importers/course_txt/course_reader.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/base/error.h"
#include "rayform/scene/procedural_mesh.h"
#include "test_paths.h"
#include "test_bytes.h"
#include "test_scenes.h"
#include "test_work_share.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <fstream>
#include <thread>

namespace rayform {
namespace {

using test::same_bytes;
namespace fs = std::filesystem;

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

const char* kCubeObj =
    "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n"
    "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";

using test::shape_node;

// A default camera; root group 0 with the given children appended.
Scene scene_with(std::vector<Node> children) {
  Scene s;
  s.cameras.push_back(Camera{});
  test::add_root_group(s, std::move(children));
  return s;
}

TEST(Prepare, MeshInstancedSeveralTimesIsReadAndBuiltOnce) {
  auto dir = test::temp_dir("prepare_once");
  write_file(dir / "cube.obj", kCubeObj);
  // The same file named three ways, under three transforms.
  std::string text = R"(
PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
Group { numObjects 3
  Transform { Translate -3 0 0 TriangleMesh { obj_file cube.obj } }
  Transform { Translate 3 0 0 TriangleMesh { obj_file ./cube.obj } }
  Transform { UniformScale 0.5 TriangleMesh { obj_file )" +
                     (dir / "cube.obj").string() + R"( } }
}
)";
  write_file(dir / "scene.txt", text);
  CourseScene cs = read_course_scene((dir / "scene.txt").string());
  ASSERT_EQ(cs.scene.meshes.size(), 1u) << "one OBJ file, one Mesh";
  EXPECT_EQ(cs.scene.meshes[0].triangle_count(), 12u);
  PreparedScene p = prepare_scene(cs.scene);
  ASSERT_EQ(p.instances.size(), 3u);
  for (const Instance& inst : p.instances) {
    EXPECT_EQ(inst.kind, ShapeKind::mesh);
    EXPECT_EQ(inst.shape, 0);
    EXPECT_TRUE(inst.has_transform);
  }
  ASSERT_EQ(p.meshes.size(), 1u) << "one accelerator per Scene mesh, not per instance";
  EXPECT_EQ(p.meshes[0].triangles.size(), 12u);
  // World bounds of the three instances: x from -4 to 4.
  EXPECT_EQ(p.bounds.lo.x, -4.f);
  EXPECT_EQ(p.bounds.hi.x, 4.f);
  fs::remove_all(dir);
}

TEST(Prepare, OnlyUsedMeshesAreBuilt) {
  Scene s = scene_with({shape_node(ShapeKind::mesh, 1)});
  s.meshes.push_back(make_icosphere(1));
  s.meshes.push_back(make_cube());
  s.meshes.push_back(make_icosphere(2));
  PreparedScene p = prepare_scene(s);
  ASSERT_EQ(p.meshes.size(), 3u);
  EXPECT_TRUE(p.meshes[0].bvh.nodes.empty());
  EXPECT_EQ(p.meshes[1].triangles.size(), 12u);
  EXPECT_TRUE(p.meshes[2].bvh.nodes.empty());
}

TEST(Prepare, SharedPreparesBuildTheLargeUsedMeshesSharedInMeshOrder) {
  // Meshes 0 and 3 are used and over the threshold, 1 is used and under it,
  // 2 is over it but unused: two shared builds, the same on every part.
  Scene s =
      scene_with({shape_node(ShapeKind::mesh, 3), shape_node(ShapeKind::mesh, 1), shape_node(ShapeKind::mesh, 0)});
  s.meshes.push_back(make_bumpy_torus(12000, 2));
  s.meshes.push_back(make_icosphere(3));
  s.meshes.push_back(make_bumpy_torus(8000, 3));
  s.meshes.push_back(make_grid(60, 50));
  PrepareOptions o;
  o.bvh.share_min_triangles = 5000;
  const PreparedScene whole = prepare_scene(s, o);
  for (int parts : {2, 3}) {
    test::ThreadExchange ex(parts);
    std::vector<PreparedScene> prepared(parts);
    std::vector<std::thread> threads;
    for (int p = 0; p < parts; ++p)
      threads.emplace_back([&, p] {
        const WorkShare share = ex.share(p);
        PrepareOptions po = o;
        po.share = &share;
        prepared[p] = prepare_scene(s, po);
      });
    for (std::thread& t : threads) t.join();
    for (int p = 0; p < parts; ++p) {
      EXPECT_EQ(ex.calls(p), 2) << parts << " parts: part " << p;
      ASSERT_EQ(prepared[p].meshes.size(), 4u);
      for (size_t m = 0; m < 4; ++m) {
        EXPECT_TRUE(same_bytes(whole.meshes[m].bvh.nodes, prepared[p].meshes[m].bvh.nodes)) << "mesh " << m;
        EXPECT_TRUE(same_bytes(whole.meshes[m].packets, prepared[p].meshes[m].packets)) << "mesh " << m;
        EXPECT_EQ(whole.meshes[m].triangles, prepared[p].meshes[m].triangles) << "mesh " << m;
      }
      EXPECT_TRUE(prepared[p].meshes[2].bvh.nodes.empty()) << "an unused mesh was built";
      EXPECT_EQ(prepared[p].meshes[0].triangles.size(), s.meshes[0].triangle_count());
    }
  }
}

// The packets' buffer of mesh i: the same buffer after a take from the cache, a new one after a build.
const TrianglePacket* packets_of(const PreparedScene& p, size_t i) { return p.meshes[i].packets.data(); }

bool same_accel(const MeshAccel& a, const MeshAccel& b) {
  return same_bytes(a.bvh.nodes, b.bvh.nodes) && same_bytes(a.packets, b.packets) && a.triangles == b.triangles;
}

TEST(Prepare, ManyMeshesAndInstancesPrepareTheSameOnOneThreadAndOnFour) {
  // 40 small meshes (built at once, each by one task), two large ones (one
  // after the other, each by parallel tasks), one unused; 2000 instances
  // under transforms, a plane among them.
  std::vector<Node> nodes;
  Scene s;
  for (int i = 0; i < 40; ++i)
    s.meshes.push_back(i % 2 ? make_icosphere(1 + i % 3) : make_bumpy_torus(200 + 50 * i, i));
  s.meshes.push_back(make_bumpy_torus(60000, 7));
  s.meshes.push_back(make_grid(200, 190));
  s.meshes.push_back(make_cube());
  s.planes.push_back(Plane{});
  for (int i = 0; i < 2000; ++i) {
    Node n = shape_node(ShapeKind::mesh, i % 42);
    n.local = glm::rotate(glm::translate(mat4(1.f), vec3(float(i % 50), float(i / 50), 0.f)), 0.01f * float(i),
                          vec3(0.f, 1.f, 1.f));
    nodes.push_back(n);
  }
  nodes.push_back(shape_node(ShapeKind::plane, 0));
  Scene scene = scene_with(std::move(nodes));
  scene.meshes = std::move(s.meshes);
  scene.planes = std::move(s.planes);
  auto prepare_on = [&](int threads) {
    tbb::task_arena arena(threads);
    PreparedScene p;
    arena.execute([&] { p = prepare_scene(scene); });
    return p;
  };
  const PreparedScene one = prepare_on(1), four = prepare_on(4);
  ASSERT_EQ(one.meshes.size(), 43u);
  ASSERT_EQ(four.meshes.size(), 43u);
  for (size_t m = 0; m < 42; ++m) {
    EXPECT_EQ(one.meshes[m].triangles.size(), scene.meshes[m].triangle_count()) << "mesh " << m;
    EXPECT_TRUE(same_accel(one.meshes[m], four.meshes[m])) << "mesh " << m;
  }
  EXPECT_TRUE(four.meshes[42].bvh.nodes.empty()) << "an unused mesh was built";
  ASSERT_EQ(one.instances.size(), 2001u);
  ASSERT_EQ(four.instances.size(), 2001u);
  for (size_t i = 0; i < one.instances.size(); ++i) {
    const Instance &a = one.instances[i], &b = four.instances[i];
    EXPECT_TRUE(a.kind == b.kind && a.shape == b.shape && a.material == b.material &&
                a.has_transform == b.has_transform && std::memcmp(&a.to_world, &b.to_world, sizeof(mat4)) == 0 &&
                std::memcmp(&a.to_object, &b.to_object, sizeof(mat4)) == 0 &&
                std::memcmp(&a.normal_to_world, &b.normal_to_world, sizeof(mat3)) == 0 &&
                std::memcmp(&a.world_bounds, &b.world_bounds, sizeof(Bounds3)) == 0)
        << "instance " << i;
  }
  EXPECT_EQ(four.plane_instances, std::vector<uint32_t>{2000});
  EXPECT_TRUE(same_bytes(one.top.nodes, four.top.nodes));
  EXPECT_EQ(one.top.primitives, four.top.primitives);
  EXPECT_EQ(std::memcmp(&one.bounds, &four.bounds, sizeof(Bounds3)), 0);
  // The instances' records against one computed here.
  const Instance& i7 = four.instances[7];
  EXPECT_TRUE(i7.has_transform);
  const mat4 inverse = glm::inverse(i7.to_world);
  EXPECT_EQ(std::memcmp(&i7.to_object, &inverse, sizeof(mat4)), 0);
}

TEST(Prepare, ACacheKeepsTheBvhsOfUnchangedMeshesFromFrameToFrame) {
  // A turntable: every frame a copy of one loaded scene under another camera.
  Scene source = scene_with({shape_node(ShapeKind::mesh, 0), shape_node(ShapeKind::mesh, 2)});
  source.meshes.push_back(make_bumpy_torus(3000, 2));
  source.meshes.push_back(make_icosphere(2));  // unused
  source.meshes.push_back(make_grid(20, 30));
  const PreparedScene reference = prepare_scene(source);
  MeshAccelCache cache;
  cache.source = &source;
  auto frame = [&](float x) {
    Scene f = source;
    f.cameras[0].center.x = x;
    return f;
  };
  PrepareOptions o;
  o.cache = &cache;
  const Scene f1 = frame(1.f);
  PreparedScene p1 = prepare_scene(f1, o);  // an empty cache: built
  for (size_t m : {0u, 2u}) EXPECT_TRUE(same_accel(reference.meshes[m], p1.meshes[m])) << "mesh " << m;
  const TrianglePacket* torus_packets = packets_of(p1, 0);
  keep_mesh_accels(p1, o.bvh, cache);
  ASSERT_EQ(cache.meshes.size(), 3u);
  EXPECT_TRUE(cache.meshes[0] && cache.meshes[2]);
  EXPECT_FALSE(cache.meshes[1]) << "an unused mesh has no BVH to keep";

  // The next frame takes both BVHs (the very buffers) and gets the structure a build gives.
  const Scene f2 = frame(2.f);
  PreparedScene p2 = prepare_scene(f2, o);
  EXPECT_EQ(packets_of(p2, 0), torus_packets) << "the torus was built again";
  for (size_t m : {0u, 2u}) EXPECT_TRUE(same_accel(reference.meshes[m], p2.meshes[m])) << "mesh " << m;
  EXPECT_FALSE(cache.meshes[0] || cache.meshes[2]) << "taken, not copied";
  EXPECT_TRUE(p2.meshes[1].bvh.nodes.empty());
  keep_mesh_accels(p2, o.bvh, cache);

  // A frame whose grid moved one vertex: the grid is built again, the torus still taken.
  Scene f3 = frame(3.f);
  f3.meshes[2].positions[7].z += 0.25f;
  const TrianglePacket* grid_packets = cache.meshes[2]->packets.data();
  PreparedScene p3 = prepare_scene(f3, o);
  EXPECT_EQ(packets_of(p3, 0), torus_packets);
  EXPECT_NE(packets_of(p3, 2), grid_packets);
  EXPECT_TRUE(same_accel(prepare_scene(f3).meshes[2], p3.meshes[2])) << "the changed grid's own BVH";
  EXPECT_FALSE(same_accel(reference.meshes[2], p3.meshes[2]));
  keep_mesh_accels(p3, o.bvh, cache);
  EXPECT_TRUE(cache.meshes[0]);
  EXPECT_FALSE(cache.meshes[2]) << "kept a BVH of a mesh that is not the source's";

  // Other build options: built again, as those options build it.
  PrepareOptions other = o;
  other.bvh.max_leaf_size = 2;
  PreparedScene p4 = prepare_scene(f2, other);
  EXPECT_NE(packets_of(p4, 0), torus_packets);
  PrepareOptions other_alone;
  other_alone.bvh = other.bvh;
  EXPECT_TRUE(same_accel(prepare_scene(f2, other_alone).meshes[0], p4.meshes[0]));
}

Texture embedded_texture() {
  Texture t;
  t.width = 2;
  t.height = 1;
  t.channels = 3;
  t.pixels = {255, 0, 0, 0, 255, 0};
  t.lookup = Texture::Lookup::course;
  return t;
}

TEST(Prepare, UnusedTexturesAreNotDecoded) {
  Scene s = scene_with({shape_node(ShapeKind::sphere, 0, 1)});
  s.spheres.push_back({});
  Texture missing;
  missing.path = "/nonexistent/never-decoded.bmp";  // decoding it would throw
  s.textures = {missing, embedded_texture()};
  s.materials.resize(2);
  s.materials[0].diffuse_texture = 0;  // no shape uses material 0
  s.materials[1].diffuse_texture = 1;
  PreparedScene p;
  ASSERT_NO_THROW(p = prepare_scene(s));
  ASSERT_EQ(p.textures.size(), 2u);
  EXPECT_TRUE(p.textures[0].empty()) << "texture of an unused material was decoded";
  ASSERT_EQ(p.textures[1].width, 2);
  EXPECT_EQ(p.textures[1].texel(1, 0)[1], 1.f);
  EXPECT_TRUE(p.features.textures);
  // Used, the missing file is an error.
  s.nodes[1].material = 0;
  EXPECT_THROW(prepare_scene(s), Error);
}

// A textured sphere under a cube map of 4x4 faces: the images a shared
// prepare's parts decode, each its share, and exchange once.
Scene textured_scene_with_cube_map() {
  Scene s = scene_with({shape_node(ShapeKind::sphere, 0, 0)});
  s.spheres.push_back({});
  s.textures.push_back(embedded_texture());
  s.textures[0].srgb = true;
  for (int f = 0; f < 6; ++f) {
    Texture t;
    t.width = t.height = 4;
    t.channels = f % 2 ? 4 : 3;
    for (int i = 0; i < 16 * t.channels; ++i) t.pixels.push_back(uint8_t(f * 40 + i * 3));
    t.srgb = f < 3;
    s.background.cube_map[size_t(f)] = int(s.textures.size());
    s.textures.push_back(t);
  }
  s.materials.resize(1);
  s.materials[0].diffuse_texture = 0;
  return s;
}

bool same_image(const TextureImage& a, const TextureImage& b) {
  return a.width == b.width && a.height == b.height && a.rgba8 == b.rgba8 && a.rgbaf == b.rgbaf &&
         a.to_linear == b.to_linear && a.wrap_u == b.wrap_u && a.wrap_v == b.wrap_v && a.filter == b.filter &&
         a.lookup == b.lookup;
}

// Each part of a shared prepare runs `prepare` on its own thread; returns
// each part's exception message ("" when it did not throw).
std::vector<std::string> prepare_shared(const Scene& s, int parts, test::ThreadExchange& ex,
                                        std::vector<PreparedScene>& prepared) {
  prepared.assign(size_t(parts), PreparedScene{});
  std::vector<std::string> errors(static_cast<size_t>(parts));
  std::vector<std::thread> threads;
  for (int p = 0; p < parts; ++p)
    threads.emplace_back([&, p] {
      const WorkShare share = ex.share(p);
      PrepareOptions po;
      po.share = &share;
      try {
        prepared[size_t(p)] = prepare_scene(s, po);
      } catch (const Error& e) {
        errors[size_t(p)] = e.what();
      }
    });
  for (std::thread& t : threads) t.join();
  return errors;
}

TEST(Prepare, SharedPreparesDecodeTheTexturesAndCubeMapShared) {
  const Scene s = textured_scene_with_cube_map();
  const PreparedScene whole = prepare_scene(s);
  ASSERT_EQ(whole.cube_map.size(), 6u);
  ASSERT_EQ(whole.cube_map[1].width, 4);
  for (int parts : {2, 3}) {
    test::ThreadExchange ex(parts);
    std::vector<PreparedScene> prepared;
    const std::vector<std::string> errors = prepare_shared(s, parts, ex, prepared);
    for (int p = 0; p < parts; ++p) {
      SCOPED_TRACE(std::to_string(parts) + " parts: part " + std::to_string(p));
      EXPECT_EQ(errors[size_t(p)], "");
      EXPECT_EQ(ex.calls(p), 1) << "one exchange of the decoded images";
      EXPECT_GT(ex.sent(p), size_t(2 * 4 * 4 * 4)) << "each part sends the images it decoded";
      const PreparedScene& q = prepared[size_t(p)];
      ASSERT_EQ(q.textures.size(), whole.textures.size());
      EXPECT_TRUE(same_image(q.textures[0], whole.textures[0]));
      ASSERT_EQ(q.cube_map.size(), 6u);
      for (size_t f = 0; f < 6; ++f) EXPECT_TRUE(same_image(q.cube_map[f], whole.cube_map[f])) << "face " << f;
      EXPECT_TRUE(q.features.cube_map);
      EXPECT_EQ(q.memory_bytes(), whole.memory_bytes());
    }
  }
}

TEST(Prepare, AFaceThatFailsToDecodeInASharedPrepareFailsEveryPartAlike) {
  Scene s = textured_scene_with_cube_map();
  s.textures[4].pixels.clear();
  s.textures[4].path = "/nonexistent/face.png";  // face 3: decoded by part 0 of 2, part 1 of 3
  std::string alone;
  try {
    prepare_scene(s);
  } catch (const Error& e) {
    alone = e.what();
  }
  ASSERT_NE(alone.find("/nonexistent/face.png"), std::string::npos) << alone;
  for (int parts : {2, 3}) {
    test::ThreadExchange ex(parts);
    std::vector<PreparedScene> prepared;
    const std::vector<std::string> errors = prepare_shared(s, parts, ex, prepared);
    for (int p = 0; p < parts; ++p) {
      EXPECT_EQ(errors[size_t(p)], alone) << parts << " parts: part " << p;
      EXPECT_EQ(ex.calls(p), 1) << parts << " parts: part " << p;
    }
  }
}

TEST(Prepare, CourseSceneWithAnUnusedBrokenTexture) {
  auto dir = test::temp_dir("prepare_tex");
  write_file(dir / "broken.bmp", "this is not a picture");
  std::string text = R"(
PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 30 }
Materials { numMaterials 2
  Material { diffuseColor 1 0 0 }
  Material { texture broken.bmp } }
Group { numObjects 1 MaterialIndex 0 Sphere { center 0 0 0 radius 1 } }
)";
  write_file(dir / "scene.txt", text);
  CourseScene cs = read_course_scene((dir / "scene.txt").string());
  ASSERT_EQ(cs.scene.textures.size(), 1u);
  PreparedScene p;
  ASSERT_NO_THROW(p = prepare_scene(cs.scene));
  EXPECT_TRUE(p.textures[0].empty());
  EXPECT_FALSE(p.features.textures);
  // The same scene using material 1 must fail, naming the picture.
  std::string used = text;
  used.replace(used.find("MaterialIndex 0"), 15, "MaterialIndex 1");
  write_file(dir / "scene.txt", used);
  CourseScene cu = read_course_scene((dir / "scene.txt").string());
  try {
    prepare_scene(cu.scene);
    FAIL() << "decoding a broken texture should fail";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.bmp"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(Prepare, FlattensTheTreeWithWorldMatrices) {
  Scene s = scene_with({});
  s.spheres.push_back({vec3(0.f), 1.f});
  Node outer;
  outer.kind = Node::Kind::transform;
  outer.local = glm::translate(mat4(1.f), vec3(1, 2, 3));
  Node inner;
  inner.kind = Node::Kind::transform;
  inner.local = glm::scale(mat4(1.f), vec3(2.f));
  Node group;                                                    // a nested group holding the same sphere twice
  s.nodes.push_back(outer);                                      // 1
  s.nodes.push_back(inner);                                      // 2
  s.nodes.push_back(group);                                      // 3
  s.nodes.push_back(shape_node(ShapeKind::sphere, 0, invalid));  // 4
  s.nodes[0].children = {1, 4};
  s.nodes[1].children = {2};
  s.nodes[2].children = {3};
  s.nodes[3].children = {4};
  PreparedScene p = prepare_scene(s);
  ASSERT_EQ(p.instances.size(), 2u);
  // Depth-first: the transformed one first.
  EXPECT_TRUE(p.instances[0].has_transform);
  EXPECT_EQ(p.instances[0].to_world, glm::translate(mat4(1.f), vec3(1, 2, 3)) * glm::scale(mat4(1.f), vec3(2.f)));
  EXPECT_EQ(transform_point(p.instances[0].to_object, vec3(3, 4, 5)), vec3(1, 1, 1));
  EXPECT_EQ(p.instances[0].world_bounds.lo, vec3(-1, 0, 1));
  EXPECT_EQ(p.instances[0].world_bounds.hi, vec3(3, 4, 5));
  EXPECT_FALSE(p.instances[1].has_transform);
  EXPECT_EQ(p.instances[0].material, 0) << "no material: the default one appended after the scene's (none here)";
  ASSERT_EQ(p.materials.size(), 1u);
  EXPECT_TRUE(p.features.transforms);
  EXPECT_FALSE(p.features.planes);
}

TEST(Prepare, FeatureFlags) {
  Scene s = scene_with({shape_node(ShapeKind::sphere, 0, 0), shape_node(ShapeKind::plane, 0, 1)});
  s.spheres.push_back({});
  s.planes.push_back({});
  s.materials.resize(3);
  s.materials[2].specular = vec3(1.f);  // unused: does not count
  PreparedScene p = prepare_scene(s);
  EXPECT_FALSE(p.features.specular);
  EXPECT_TRUE(p.features.planes);
  EXPECT_FALSE(p.features.transforms);
  EXPECT_FALSE(p.features.point_lights);
  EXPECT_FALSE(p.features.falloff);
  EXPECT_EQ(p.plane_instances.size(), 1u);
  EXPECT_EQ(p.top.primitives.size(), 1u) << "planes stay outside the BVH";
  s.materials[1].specular = vec3(0.5f);
  Light pl;
  pl.kind = Light::Kind::point;
  s.lights.push_back(pl);
  PreparedScene q = prepare_scene(s);
  EXPECT_TRUE(q.features.specular);
  EXPECT_TRUE(q.features.point_lights);
  EXPECT_FALSE(q.features.falloff);
  s.lights[0].falloff = 0.5f;
  EXPECT_TRUE(prepare_scene(s).features.falloff);
}

TEST(Prepare, BadGraphsAreErrors) {
  Scene s = scene_with({shape_node(ShapeKind::sphere, 3)});  // no sphere 3
  EXPECT_THROW(prepare_scene(s), Error);
  Scene c = scene_with({});
  c.nodes[0].children = {0};  // the root is its own child
  EXPECT_THROW(prepare_scene(c), Error);
}

}  // namespace
}  // namespace rayform
