// OBJ + MTL reader: shared assets (counts, materials, paths), small files of
// our own for every rule, and the obj2gltf edge cases as a table.
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/base/error.h"
#include "rayform/scene/node_walk.h"
#include "rayform/scene/scene_stats.h"
#include "rayform/importers/scene_io.h"
#include "test_importers.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>

namespace rayform {
namespace {
namespace fs = std::filesystem;

using test::any_contains;
using test::asset;

void write_file(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

std::string error_of(const std::string& path, const ObjReadOptions& o = {}) {
  try {
    read_obj_scene(path, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

size_t total_triangles(const Scene& s) {
  size_t n = 0;
  for (const Mesh& m : s.meshes) n += m.triangle_count();
  return n;
}

int material_named(const Scene& s, const std::string& name) {
  for (size_t i = 0; i < s.materials.size(); ++i)
    if (s.materials[i].name == name) return int(i);
  return invalid;
}

// ---- shared assets --------------------------------------------------------------

TEST(ObjReader, StanfordBunnyGetsSmoothUnitNormals) {
  RAYFORM_REQUIRE_SHARED();
  std::vector<std::string> warnings;
  Scene s = read_obj_scene(asset("obj/stanford-bunny.obj").string(), {}, &warnings);
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.triangle_count(), 69451u);
  // No uvs or normals: one vertex per position the faces use (35947 are
  // declared, 34834 referenced: counted from the file with awk).
  EXPECT_EQ(m.positions.size(), 34834u);
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_TRUE(m.colors.empty());
  ASSERT_EQ(m.normals.size(), m.positions.size());  // generated
  // Smooth normals agree with the faces around them.
  size_t agree = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
         c = m.positions[m.indices[3 * t + 2]];
    vec3 fn = glm::cross(b - a, c - a);
    if (glm::length(fn) == 0.f) continue;
    fn = glm::normalize(fn);
    if (glm::dot(fn, m.normals[m.indices[3 * t]]) > 0.5f) ++agree;
  }
  EXPECT_GT(agree, m.triangle_count() * 95 / 100);
  for (const vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.f, 1e-4f);
  // No .mtl: every face uses the one default material.
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_TRUE(s.cameras.empty());
  EXPECT_TRUE(s.lights.empty());
}

TEST(ObjReader, FlatOptionLeavesFaceNormalsToTheRenderer) {
  RAYFORM_REQUIRE_SHARED();
  Scene s = read_obj_scene(asset("obj/stanford-bunny.obj").string(), ObjReadOptions{true});
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.meshes[0].normals.empty());
  EXPECT_EQ(s.meshes[0].triangle_count(), 69451u);
}

TEST(ObjReader, BeastQuadsAreSplitIntoTriangles) {
  RAYFORM_REQUIRE_SHARED();
  Scene s = read_obj_scene(asset("obj/beast.obj").string());
  // 32228 quads, 124 triangles, 10 pentagons, 2 hexagons (counted from the file).
  EXPECT_EQ(total_triangles(s), 32228u * 2 + 124 + 10 * 3 + 2 * 4);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].uvs.size(), s.meshes[0].positions.size());
  EXPECT_EQ(s.meshes[0].normals.size(), s.meshes[0].positions.size());
}

TEST(ObjReader, SpiderWindowsTexturePathsAndGroups) {
  RAYFORM_REQUIRE_SHARED();
  std::vector<std::string> warnings;
  Scene s = read_obj_scene(asset("obj/spider/spider.obj").string(), {}, &warnings);
  // spider.mtl defines 5 materials; the OBJ has 19 groups, each with a usemtl.
  EXPECT_EQ(s.materials.size(), 5u);
  EXPECT_EQ(s.meshes.size(), 19u);
  EXPECT_EQ(total_triangles(s), 1368u);
  EXPECT_EQ(s.textures.size(), 5u);
  EXPECT_FALSE(any_contains(warnings, "cannot find")) << (warnings.empty() ? "" : warnings.front());
  for (const Texture& t : s.textures) {
    EXPECT_TRUE(fs::is_regular_file(t.path)) << t.path;  // ".\wal67ar_small.jpg" resolved beside the .mtl
    EXPECT_TRUE(t.srgb);
    EXPECT_EQ(t.lookup, Texture::Lookup::standard);
    EXPECT_EQ(t.wrap_u, Texture::Wrap::repeat);
  }
  int skin = material_named(s, "Skin");
  ASSERT_NE(skin, invalid);
  const Material& m = s.materials[skin];
  ASSERT_NE(m.diffuse_texture, invalid);
  EXPECT_EQ(fs::path(s.textures[m.diffuse_texture].path).filename(), "wal67ar_small.jpg");
  EXPECT_EQ(s.textures[m.diffuse_texture].name, ".\\wal67ar_small.jpg");
  EXPECT_TRUE(m.texture_modulates);
  EXPECT_NEAR(m.diffuse.x, 0.827451f, 1e-6f);
  // Group nodes named after the OBJ groups, each holding one shape node.
  const Node& root = s.nodes[s.root];
  ASSERT_EQ(root.children.size(), 19u);
  EXPECT_EQ(s.nodes[root.children[0]].name, "HLeib01");
  EXPECT_EQ(s.nodes[root.children[0]].kind, Node::Kind::group);
  ASSERT_EQ(s.nodes[root.children[0]].children.size(), 1u);
  const Node& shape = s.nodes[s.nodes[root.children[0]].children[0]];
  EXPECT_EQ(shape.kind, Node::Kind::shape);
  EXPECT_EQ(shape.material, material_named(s, "HLeibTex"));
}

TEST(ObjReader, CornellBoxKeepsPerFaceMaterials) {
  RAYFORM_REQUIRE_SHARED();
  Scene s = read_obj_scene(asset("obj/cornell-box/cornell-box.obj").string());
  // cornell-box.mtl defines base, green, red (5 usemtl statements use them).
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.meshes.size(), 3u);  // objects base, cube.001, cube.002
  EXPECT_EQ(total_triangles(s), 34u);
  int base = material_named(s, "base"), green = material_named(s, "green"), red = material_named(s, "red");
  ASSERT_NE(green, invalid);
  EXPECT_NEAR(s.materials[green].diffuse.y, 0.800408f, 1e-6f);
  EXPECT_FLOAT_EQ(s.materials[base].shininess, 250.f);
  EXPECT_FLOAT_EQ(s.materials[base].specular.x, 0.5f);
  EXPECT_EQ(s.materials[base].refraction_index, 0.f);  // Ni is not refraction for an opaque MTL material
  const Node& root = s.nodes[s.root];
  ASSERT_EQ(root.children.size(), 3u);
  EXPECT_EQ(s.nodes[root.children[0]].name, "base");
  const Node& base_shape = s.nodes[s.nodes[root.children[0]].children[0]];
  const Mesh& bm = s.meshes[base_shape.shape];
  ASSERT_EQ(bm.face_materials.size(), bm.triangle_count());
  std::set<int> used(bm.face_materials.begin(), bm.face_materials.end());
  EXPECT_EQ(used, (std::set<int>{base, green, red}));
  // Its README: normals made so that the box is seen from inside. OBJ has no
  // culling, so every material is double-sided with two-sided lighting.
  for (const Material& m : s.materials) {
    EXPECT_TRUE(m.double_sided) << m.name;
    EXPECT_TRUE(m.two_sided_lighting) << m.name;
  }
}

TEST(ObjReader, DuckTextureWithoutKdIsTheColour) {
  RAYFORM_REQUIRE_SHARED();
  Scene s = read_obj_scene(asset("duck/duck.obj").string());
  EXPECT_EQ(total_triangles(s), 4212u);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  EXPECT_EQ(m.name, "blinn3-fx");
  // duck.mtl has map_Kd but no Kd: K = 1 x texel.
  EXPECT_EQ(m.diffuse, vec3(1.f));
  ASSERT_NE(m.diffuse_texture, invalid);
  EXPECT_EQ(fs::path(s.textures[m.diffuse_texture].path).filename(), "duck.png");
  EXPECT_TRUE(s.textures[m.diffuse_texture].srgb);
  // Ns 0 with Ks 0.5: no highlight rather than a constant one.
  EXPECT_EQ(m.specular, vec3(0.f));
  EXPECT_EQ(s.meshes[0].uvs.size(), s.meshes[0].positions.size());
}

TEST(ObjReader, LoadSceneDispatchesObjAndPassesFlat) {
  RAYFORM_REQUIRE_SHARED();
  LoadOptions o;
  o.flat_normals = true;
  LoadedScene l = load_scene(asset("obj2gltf-edge-cases/box-positions-only/box-positions-only.obj").string(), o);
  EXPECT_EQ(l.format, SceneFormat::obj);
  ASSERT_EQ(l.scene.meshes.size(), 1u);
  EXPECT_TRUE(l.scene.meshes[0].normals.empty());
  LoadedScene smooth = load_scene(asset("obj2gltf-edge-cases/box-positions-only/box-positions-only.obj").string());
  EXPECT_EQ(smooth.scene.meshes[0].normals.size(), smooth.scene.meshes[0].positions.size());
}

// ---- the obj2gltf edge cases ----------------------------------------------------

struct EdgeCase {
  const char* file;  // under obj2gltf-edge-cases/
  bool loads;
  size_t triangles, meshes, materials, textures;
  const char* message;  // substring of the error, or of some warning ("" = no warnings at all)
  const char* reason;
};

const EdgeCase edge_cases[] = {
    {"box-complex-material-alpha/box-complex-material-alpha.obj", true, 12, 1, 1, 2, "map_d",
     "every MTL map is read; map_Kd is the colour, map_Bump is kept, the others (and d, map_d) are warned about"},
    {"box-complex-material/box-complex-material.obj", true, 12, 1, 1, 2, "transparency (d 0.9",
     "as above without map_d; d < 1 cannot be rendered, so it is a warning"},
    {"box-external-resources-in-root/box-external-resources-in-root.obj", true, 12, 1, 2, 1, "",
     "mtllib ../box/box.mtl and map_Kd ../box-textured/cesium.png resolve against the file that names them"},
    {"box-external-resources/box-external-resources.obj", true, 12, 1, 2, 1, "",
     "same: resources in sibling folders are found"},
    {"box-groups/box-groups.obj", true, 36, 3, 3, 0, "", "three `g` groups: three group nodes, one mesh each"},
    {"box-incomplete-attributes/box-incomplete-normals.obj", true, 12, 1, 1, 0, "normals of this file are ignored",
     "faces name normals that are not declared: the normals are dropped (warning) and generated"},
    {"box-incomplete-attributes/box-incomplete-positions.obj", false, 0, 0, 0, 0,
     "face refers to vertex 2 but only 1 vertices are declared",
     "faces name vertices that are not declared: there is no geometry to draw, so it is an error with the line"},
    {"box-incomplete-attributes/box-incomplete-uvs.obj", true, 12, 1, 1, 0,
     "texture coordinates of this file are ignored", "faces name uvs that are not declared: uvs dropped (warning)"},
    {"box-incorrect-winding-order/box-incorrect-winding-order.obj", true, 12, 1, 1, 0, "",
     "winding is geometry; the written normals are kept"},
    {"box-missing-attributes/box-missing-attributes.obj", true, 12, 1, 1, 0, "normals of this file are ignored",
     "f v/vt/vn with no vt or vn lines at all: both dropped with warnings, normals generated"},
    {"box-missing-mtllib/box-missing-mtllib.obj", true, 12, 1, 1, 0, "cannot find material library '/box.mtl'",
     "missing .mtl is a warning; faces get the default material"},
    {"box-missing-texture/box-missing-texture.obj", true, 12, 1, 1, 0, "cannot find map_Kd texture '/cesium.png'",
     "missing texture is a warning; the material keeps Kd and has no texture"},
    {"box-missing-usemtl/box-missing-usemtl.obj", true, 12, 1, 2, 0, "",
     "faces before any usemtl use the default material (the unused MTL material is still listed)"},
    {"box-mixed-attributes-2/box-mixed-attributes-2.obj", true, 48, 2, 2, 1, "material [ 'Missing' ] not found",
     "faces with and without uvs/normals in one object; an unknown usemtl falls back to the default material"},
    {"box-mixed-attributes/box-mixed-attributes.obj", true, 12, 1, 1, 0, "",
     "corners without uv get (0,0), without normal get generated ones"},
    {"box-mtllib-spaces/box mtllib.obj", true, 12, 1, 3, 0, "", "mtllib file names with spaces, two files on one line"},
    {"box-mtllib/box-mtllib.obj", true, 12, 1, 3, 0, "", "several mtllib lines and two files on one line"},
    {"box-multiple-materials/box-multiple-materials.obj", true, 12, 1, 3, 0, "",
     "usemtl per face: Mesh::face_materials"},
    {"box-negative-indices/box-negative-indices.obj", true, 12, 1, 1, 0, "", "relative (negative) indices"},
    {"box-no-materials/box-no-materials.obj", true, 36, 1, 1, 0, "",
     "no mtllib, no groups: one mesh, default material"},
    {"box-normals/box-normals.obj", true, 12, 1, 1, 0, "", "normals only, no uvs"},
    {"box-objects-groups-materials-2/box-objects-groups-materials-2.obj", true, 36, 3, 3, 0, "",
     "usemtl before o/g and changing inside groups"},
    {"box-objects-groups-materials/box-objects-groups-materials.obj", true, 36, 3, 3, 0, "",
     "one object, three groups, materials changing inside each group"},
    {"box-objects-groups/box-objects-groups.obj", true, 36, 3, 3, 0, "", "o then g: one node per group"},
    {"box-objects/box-objects.obj", true, 36, 3, 3, 0, "", "three `o` objects"},
    {"box-positions-only/box-positions-only.obj", true, 12, 1, 1, 0, "", "no uvs, no normals: normals generated"},
    {"box-resources-in-root/box-resources-in-root.obj", true, 12, 1, 1, 1, "not found as written",
     "mtllib and map_Kd name subfolders that do not exist; the files beside them are used, with a warning"},
    {"box-rotated/box-rotated.obj", true, 64, 3, 1, 0, "", "three objects, one with triangles and quads"},
    {"box-shared-textures-2/box-shared-textures-2.obj", true, 12, 1, 1, 1, "map_Ke not used",
     "one image used twice is one texture; map_Ke is warned about"},
    {"box-shared-textures/box-shared-textures.obj", true, 12, 1, 1, 1, "map_Ka, map_Ks not used",
     "one image used three times is one texture"},
    {"box-subdirectories/box-textured.obj", true, 12, 1, 1, 1, "",
     "mtllib materials/x.mtl, map_Kd images/x.png relative to the .mtl"},
    {"box-texture-options/box-texture-options.obj", true, 12, 1, 1, 2, "transparency",
     "-s/-o options parsed (identity here) into the uv transform"},
    {"box-textured/box-textured.obj", true, 12, 1, 1, 1, "", "map_Kd beside the .mtl"},
    {"box-transparent/box-transparent.obj", true, 12, 1, 1, 0, "transparency (d 0.0",
     "d 0 cannot be rendered: a warning, drawn opaque"},
    {"box-triangles/box-triangles.obj", true, 12, 1, 1, 0, "", "triangles already"},
    {"box-uncleaned/box-uncleaned.obj", true, 12, 1, 1, 0, "",
     "repeated o/g/usemtl lines without faces make no empty nodes"},
    {"box-unnamed-material/box-unnamed-material.obj", true, 12, 1, 1, 0, "",
     "`newmtl` and `usemtl` without a name match each other"},
    {"box-unnormalized/box-unnormalized.obj", true, 12, 1, 1, 0, "written normal(s) of zero length",
     "written normals are normalised; the zero one is replaced by a generated normal (warning)"},
    {"box-usemtl/box-usemtl.obj", true, 36, 1, 3, 0, "", "usemtl without o/g: one mesh, three materials"},
    {"box-uvs/box-uvs.obj", true, 12, 1, 1, 0, "", "uvs but no normals"},
    {"box-windows-paths/box-windows-paths.obj", true, 12, 1, 1, 1, "",
     "mtllib materials\\\\x.mtl and map_Kd .\\images\\x.png: '\\' separators normalised"},
    {"box-with-tabs/box-with-tabs.obj", true, 12, 1, 1, 0, "", "tabs between face corners"},
    {"box/box.obj", true, 12, 1, 1, 0, "", "the plain box"},
    {"concave/concave.obj", true, 16, 1, 1, 0, "", "concave pentagons triangulated (3 triangles each)"},
};

TEST(ObjReader, Obj2GltfEdgeCasesTableCoversEveryFile) {
  RAYFORM_REQUIRE_SHARED();
  std::set<std::string> in_table, on_disk;
  for (const EdgeCase& c : edge_cases) in_table.insert(c.file);
  fs::path root = asset("obj2gltf-edge-cases");
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.path().extension() == ".obj") on_disk.insert(fs::relative(e.path(), root).generic_string());
  EXPECT_EQ(in_table, on_disk);
  EXPECT_EQ(on_disk.size(), 44u);
}

TEST(ObjReader, Obj2GltfEdgeCasesLoadOrFailClearly) {
  RAYFORM_REQUIRE_SHARED();
  for (const EdgeCase& c : edge_cases) {
    SCOPED_TRACE(std::string(c.file) + ": " + c.reason);
    std::string path = asset(std::string("obj2gltf-edge-cases/") + c.file).string();
    std::vector<std::string> warnings;
    if (!c.loads) {
      try {
        read_obj_scene(path, {}, &warnings);
        ADD_FAILURE() << "expected an error";
      } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(c.message), std::string::npos) << msg;
        EXPECT_EQ(msg.rfind(path, 0), 0u) << "the message names the file: " << msg;
      }
      continue;
    }
    Scene s;
    ASSERT_NO_THROW(s = read_obj_scene(path, {}, &warnings));
    EXPECT_EQ(total_triangles(s), c.triangles);
    EXPECT_EQ(s.meshes.size(), c.meshes);
    EXPECT_EQ(s.materials.size(), c.materials);
    EXPECT_EQ(s.textures.size(), c.textures);
    if (std::string(c.message).empty()) EXPECT_TRUE(warnings.empty()) << warnings.front();
    else EXPECT_TRUE(any_contains(warnings, c.message)) << (warnings.empty() ? "no warnings" : warnings.front());
    // Every scene is well formed: stats walk it, every index is in range.
    SceneStats st = scene_stats(s);
    EXPECT_EQ(st.mesh_triangles, c.triangles);
    for (const Mesh& m : s.meshes) {
      for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
      EXPECT_TRUE(m.normals.empty() || m.normals.size() == m.positions.size());
      EXPECT_TRUE(m.uvs.empty() || m.uvs.size() == m.positions.size());
      for (int fm : m.face_materials) ASSERT_TRUE(fm >= 0 && fm < int(s.materials.size()));
    }
    for (const Material& m : s.materials) {
      if (m.diffuse_texture != invalid) {
        ASSERT_LT(m.diffuse_texture, int(s.textures.size()));
        EXPECT_TRUE(fs::is_regular_file(s.textures[m.diffuse_texture].path));
      }
    }
  }
}

TEST(ObjReader, EdgeCaseDetails) {
  RAYFORM_REQUIRE_SHARED();
  auto load = [](const std::string& rel) { return read_obj_scene(asset("obj2gltf-edge-cases/" + rel).string()); };
  {  // Angle-weighted normals of a cube made of quads: at every corner the
     // three faces count equally however the quads were split.
    Scene s = load("box-positions-only/box-positions-only.obj");
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.normals.size(), 8u);
    vec3 c(0.f);
    for (const vec3& p : m.positions) c += p / 8.f;
    for (size_t i = 0; i < 8; ++i) {
      vec3 out = glm::normalize(m.positions[i] - c);
      EXPECT_NEAR(glm::dot(m.normals[i], out), 1.f, 1e-5f) << i;
    }
  }
  {  // Relative indices give the same cube as absolute ones.
    Scene a = load("box-negative-indices/box-negative-indices.obj");
    Scene b = load("box-positions-only/box-positions-only.obj");
    EXPECT_EQ(scene_stats(a).bounds.lo, scene_stats(b).bounds.lo);
    EXPECT_EQ(scene_stats(a).bounds.hi, scene_stats(b).bounds.hi);
  }
  {  // Two mtllib files on one line, and names with spaces.
    for (const char* f : {"box-mtllib/box-mtllib.obj", "box-mtllib-spaces/box mtllib.obj"}) {
      Scene s = load(f);
      std::set<std::string> names;
      for (const Material& m : s.materials) names.insert(m.name);
      EXPECT_EQ(names, (std::set<std::string>{"Red", "Green", "Blue"})) << f;
      std::map<int, int> per_material;
      for (int fm : s.meshes[0].face_materials) per_material[fm]++;
      EXPECT_EQ(per_material.size(), 3u) << f;
      for (auto [mat, count] : per_material) EXPECT_EQ(count, 4) << f;
      EXPECT_NEAR(s.materials[material_named(s, "Blue")].diffuse.z, 0.64f, 1e-6f);
    }
  }
  {  // Windows separators in mtllib and map_Kd.
    Scene s = load("box-windows-paths/box-windows-paths.obj");
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(fs::path(s.textures[0].path).filename(), "cesium.png");
    EXPECT_EQ(fs::path(s.textures[0].path).parent_path().filename(), "images");
  }
  {  // Written normals are normalised; a zero one is replaced by a generated one.
    std::vector<std::string> warnings;
    Scene s =
        read_obj_scene(asset("obj2gltf-edge-cases/box-unnormalized/box-unnormalized.obj").string(), {}, &warnings);
    for (const vec3& n : s.meshes[0].normals) EXPECT_NEAR(glm::length(n), 1.f, 1e-5f);
    EXPECT_TRUE(any_contains(warnings, "1 written normal(s) of zero length"));
    bool has_z = false;  // "vn 0 0 0.5" became (0, 0, 1)
    for (const vec3& n : s.meshes[0].normals) has_z |= n == vec3(0, 0, 1);
    EXPECT_TRUE(has_z);
  }
  {  // Triangulating the concave faces keeps their area (no overlaps).
    Scene s = load("concave/concave.obj");
    const Mesh& m = s.meshes[0];
    float top = 0.f;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
           c = m.positions[m.indices[3 * t + 2]];
      if (a.y > 0.f && b.y > 0.f && c.y > 0.f) top += 0.5f * glm::length(glm::cross(b - a, c - a));
    }
    // 2 x 2 square less the notch (base 2, depth 0.54185 + 0.33651).
    EXPECT_NEAR(top, 4.f - (0.541850f + 0.336510f), 1e-4f);
  }
  {  // A texture used by several maps is one texture.
    Scene s = load("box-shared-textures/box-shared-textures.obj");
    EXPECT_EQ(s.textures.size(), 1u);
  }
  {  // o + g: the group name wins (tinyobjloader keeps one name per section).
    Scene s = load("box-objects-groups/box-objects-groups.obj");
    const Node& root = s.nodes[s.root];
    ASSERT_EQ(root.children.size(), 3u);
    EXPECT_EQ(s.nodes[root.children[1]].name, "CubeGreen_CubeGreen_Green");
    EXPECT_EQ(s.nodes[s.nodes[root.children[1]].children[0]].material, material_named(s, "Green"));
  }
}

// ---- files of our own -----------------------------------------------------------

class ObjFiles : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::temp_dir("obj-reader"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name, const std::string& text) {
    write_file(dir_ / name, text);
    return (dir_ / name).string();
  }
  fs::path dir_;
};

const char* quad_obj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";

// Corners of a position alone (no uv, no written normal) weld by position:
// one vertex per position used, in the order first used; a corner with a
// uv is a vertex of its own.
TEST_F(ObjFiles, PositionOnlyCornersAreVerticesInTheOrderFirstUsed) {
  const std::string numbers = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nv 1 1 0\nvt 0.5 0.5\n";
  const Scene plain = read_obj_scene(file("plain.obj", numbers + "f 3 1 2\nf 2 5 3\n"));
  ASSERT_EQ(plain.meshes.size(), 1u);
  const Mesh& m = plain.meshes[0];
  EXPECT_EQ(m.positions, (std::vector<vec3>{{0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 2, 3, 0}));
  EXPECT_EQ(m.normals.size(), 4u);
  const Scene uv = read_obj_scene(file("uv.obj", numbers + "f 3 1 2\nf 2/1 5 3\n"));
  ASSERT_EQ(uv.meshes.size(), 1u);
  EXPECT_EQ(uv.meshes[0].positions, (std::vector<vec3>{{0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}}));
  EXPECT_EQ(uv.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 0}));
}

TEST_F(ObjFiles, MaterialsAndTextureOptions) {
  write_file(dir_ / "tex" / "wood.png", "not really a png: decoded at prepare time only");
  std::string mtl =
      "newmtl plain\nKd 0.1 0.2 0.3\nKs 0.4 0.5 0.6\nNs 32\nKe 0.01 0.02 0.03\n"
      "newmtl textured\nmap_Kd -s 2 3 1 -o 0.25 0.5 0 tex\\wood.png\n"
      "newmtl clamped\nKd 0.5 0.5 0.5\nmap_Kd -clamp on tex/wood.png\n"
      "newmtl nokd\nKs 0.1 0.1 0.1\nNs 0\n";
  file("m.mtl", mtl);
  std::string path = file("m.obj", std::string("mtllib m.mtl\n") + quad_obj +
                                       "usemtl plain\nf 1/1 2/2 3/3\nusemtl textured\nf 1/1 3/3 4/4\n"
                                       "usemtl clamped\nf 1 2 3\nusemtl nokd\nf 1 3 4\n");
  std::vector<std::string> warnings;
  Scene s = read_obj_scene(path, {}, &warnings);
  ASSERT_EQ(s.materials.size(), 4u);
  const Material& plain = s.materials[0];
  EXPECT_EQ(plain.diffuse, vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(plain.specular, vec3(0.4f, 0.5f, 0.6f));
  EXPECT_EQ(plain.shininess, 32.f);
  EXPECT_EQ(plain.emission, vec3(0.01f, 0.02f, 0.03f));
  EXPECT_EQ(plain.diffuse_texture, invalid);
  EXPECT_TRUE(plain.texture_modulates);
  const Material& textured = s.materials[1];
  EXPECT_EQ(textured.diffuse, vec3(1.f));  // map_Kd without Kd
  ASSERT_NE(textured.diffuse_texture, invalid);
  EXPECT_EQ(textured.uv_transform.scale, vec2(2.f, 3.f));
  EXPECT_EQ(textured.uv_transform.offset, vec2(0.25f, 0.5f));
  EXPECT_EQ(textured.uv_transform.rotation, 0.f);
  const Texture& t = s.textures[textured.diffuse_texture];
  EXPECT_EQ(fs::path(t.path), (dir_ / "tex" / "wood.png").lexically_normal());
  EXPECT_TRUE(t.srgb);
  EXPECT_TRUE(t.pixels.empty());
  EXPECT_EQ(t.wrap_u, Texture::Wrap::repeat);
  const Material& clamped = s.materials[2];
  ASSERT_NE(clamped.diffuse_texture, invalid);
  EXPECT_NE(clamped.diffuse_texture, textured.diffuse_texture);  // same image, other wrap
  EXPECT_EQ(s.textures[clamped.diffuse_texture].wrap_u, Texture::Wrap::clamp);
  EXPECT_TRUE(clamped.uv_transform.is_identity());
  const Material& nokd = s.materials[3];
  EXPECT_EQ(nokd.diffuse, vec3(0.8f));  // no Kd, no map: default grey
  EXPECT_EQ(nokd.specular, vec3(0.f));  // Ns 0: no highlight
  // One mesh, the faces keeping their materials in order.
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].face_materials, (std::vector<int>{0, 1, 2, 3}));
  // Some corners have uvs, some not: every vertex gets one.
  EXPECT_EQ(s.meshes[0].uvs.size(), s.meshes[0].positions.size());
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

TEST_F(ObjFiles, MissingMtlAndTextureAreWarnings) {
  file("m.mtl", "newmtl a\nKd 1 0 0\nmap_Kd nowhere.png\n");
  std::string path =
      file("m.obj", std::string("mtllib m.mtl gone.mtl\n") + quad_obj + "usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\n");
  std::vector<std::string> warnings;
  Scene s = read_obj_scene(path, {}, &warnings);
  EXPECT_TRUE(any_contains(warnings, "m.obj:1: cannot find material library 'gone.mtl'"));
  EXPECT_TRUE(any_contains(warnings, "cannot find map_Kd texture 'nowhere.png'"));
  EXPECT_TRUE(any_contains(warnings, "material [ 'b' ] not found"));
  ASSERT_EQ(s.materials.size(), 2u);  // a, then the default for b
  EXPECT_EQ(s.materials[0].diffuse, vec3(1, 0, 0));
  EXPECT_EQ(s.materials[0].diffuse_texture, invalid);
  EXPECT_EQ(s.materials[1].name, "default");
  EXPECT_EQ(s.meshes[0].face_materials, (std::vector<int>{0, 1}));
  EXPECT_TRUE(s.textures.empty());
}

TEST_F(ObjFiles, GroupsObjectsNegativeIndicesAndColours) {
  std::string path = file("g.obj",
                          "o first\n"
                          "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\n"
                          "f -3 -2 -1\n"
                          "g second\n"
                          "v 0 0 1 0.5 0.5 0.5\nv 1 0 1 1 1 1\nv 0 1 1 0 0 0\nv 1 1 1 0.25 0.25 0.25\n"
                          "f -4 -3 -1 -2\n");
  Scene s = read_obj_scene(path);
  ASSERT_EQ(s.meshes.size(), 2u);
  const Node& root = s.nodes[s.root];
  EXPECT_EQ(root.name, "g");
  ASSERT_EQ(root.children.size(), 2u);
  EXPECT_EQ(s.nodes[root.children[0]].name, "first");
  EXPECT_EQ(s.nodes[root.children[1]].name, "second");
  const Mesh& a = s.meshes[0];
  ASSERT_EQ(a.triangle_count(), 1u);
  EXPECT_EQ(a.positions[a.indices[0]], vec3(0, 0, 0));
  EXPECT_EQ(a.positions[a.indices[2]], vec3(0, 1, 0));
  ASSERT_EQ(a.colors.size(), a.positions.size());
  EXPECT_EQ(a.colors[a.indices[0]], vec3(1, 0, 0));
  EXPECT_EQ(a.colors[a.indices[2]], vec3(0, 0, 1));
  const Mesh& b = s.meshes[1];
  EXPECT_EQ(b.triangle_count(), 2u);
  EXPECT_EQ(b.positions.size(), 4u);
  EXPECT_EQ(b.colors.size(), 4u);
  // Normals of a flat quad: all +z (generated, smooth = flat here).
  for (const vec3& n : b.normals) EXPECT_NEAR(n.z, 1.f, 1e-6f);
}

TEST_F(ObjFiles, FlatOptionWithSomeNormalsSplitsOnlyTheMissingOnes) {
  std::string path = file("f.obj",
                          "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 2\n"
                          "f 1//1 2//1 3//1\n"  // written normal, scaled: normalised
                          "f 1 2 4\n");         // no normals: its own face normal
  Scene flat = read_obj_scene(path, ObjReadOptions{true});
  const Mesh& m = flat.meshes[0];
  ASSERT_EQ(m.normals.size(), m.positions.size());
  EXPECT_EQ(m.positions.size(), 6u);  // the second face does not share vertices with the first
  EXPECT_EQ(m.normals[m.indices[0]], vec3(0, 0, 1));
  EXPECT_NEAR(m.normals[m.indices[3]].y, -1.f, 1e-6f);  // (1,0,0) x (0,0,1) = (0,-1,0)
  Scene smooth = read_obj_scene(path);
  EXPECT_EQ(smooth.meshes[0].positions.size(), 6u);  // (v, -, -) differs from (v, -, vn)
}

TEST_F(ObjFiles, ErrorsNameFileAndLine) {
  EXPECT_EQ(error_of((dir_ / "nope.obj").string()), (dir_ / "nope.obj").string() + ": cannot open OBJ file");
  std::string bad = file("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n");
  EXPECT_EQ(error_of(bad), bad + ":5: face refers to vertex 4 but only 3 vertices are declared before it");
  std::string bad_quad = file("badq.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 9\n");
  EXPECT_NE(error_of(bad_quad).find("badq.obj:4: face refers to vertex 9"), std::string::npos) << error_of(bad_quad);
  std::string too_negative = file("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n");
  EXPECT_NE(error_of(too_negative).find("neg.obj:4: face refers to vertex -4"), std::string::npos)
      << error_of(too_negative);
  std::string zero = file("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_EQ(error_of(zero), zero + ":4: a face with an index of 0 or no number (OBJ indices start at 1)");
  std::string inf = file("inf.obj", "v 0 0 0\nv 1e40 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(error_of(inf), inf + ": vertex 2 has a non-finite coordinate");
  std::string empty = file("empty.obj", "# nothing\nv 0 0 0\n");
  EXPECT_EQ(error_of(empty), empty + ": OBJ file has no faces");
  std::string lines = file("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  EXPECT_EQ(error_of(lines), lines + ": OBJ file has no faces");
}

TEST_F(ObjFiles, MtllibLinesAcrossTheSearchBlocksAreAllFound) {
  // The libraries are looked for in blocks of 1 MiB searched at once: lines
  // starting just before, across and right at a block's end all count, once
  // each (a missing library is one warning naming its line: 2, 4 and 6).
  const size_t block = size_t(1) << 20;
  std::string text;
  for (size_t k = 0; k < 3; ++k) {
    const size_t at = (k + 1) * block - 3 + k * 3;  // the word starts 3 before, at, and 3 after a block's end
    text += "#" + std::string(at - text.size() - 2, 'x') + "\n";
    text += "mtllib gone" + std::to_string(k) + ".mtl\n";
  }
  text += "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string path = file("blocks.obj", text);
  std::vector<std::string> warnings;
  read_obj_scene(path, {}, &warnings);
  std::vector<std::string> missing;
  for (const std::string& w : warnings)
    if (w.find("cannot find material library") != std::string::npos) missing.push_back(w);
  ASSERT_EQ(missing.size(), 3u) << testing::PrintToString(warnings);
  for (size_t k = 0; k < 3; ++k)
    EXPECT_EQ(missing[k].rfind(path + ":" + std::to_string(2 * k + 2) + ": cannot find material library 'gone" +
                                   std::to_string(k) + ".mtl'",
                               0),
              0u)
        << missing[k];
}

TEST_F(ObjFiles, LinesEndedByALoneCarriageReturnHoldTheirFaces) {
  // Old Mac line ends, and an indented face: the bounds walk finds the face.
  const Scene s = read_obj_scene(file("cr.obj", "v 0 0 0\rv 1 0 0\r\nv 0 1 0\r \tf 1 2 3\r"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices.size(), 3u);
}

// Mutated files: each either loads or throws rayform::Error; never crashes
// (run under AddressSanitizer too).
TEST_F(ObjFiles, MutatedFilesLoadOrFailCleanly) {
  const std::string base = std::string("mtllib m.mtl\no a\n") + quad_obj +
                           "vn 0 0 1\nusemtl x\nf 1/1/1 2/2/1 3/3/1 4/4/1\ng b\nf -1 -2 -3\n";
  const std::string mtl =
      "newmtl x\nKd 1 1 1\nKs 0.5 0.5 0.5\nNs 10\nd 1\nmap_Kd -s 1 1 1 -o 0 0 -clamp on t.png\nmap_Bump -bm 2 b.png\n";
  std::mt19937 rng(1234);
  const std::string alphabet = "0123456789-/ .\nvftgo#eKdNsmap_";
  int loaded = 0, failed = 0;
  for (int k = 0; k < 600; ++k) {
    // Mutate the OBJ, or (every third file) its MTL.
    const bool obj = k % 3 != 0;
    std::string text = obj ? base : mtl;
    int edits = 1 + int(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0: text[at] = alphabet[rng() % alphabet.size()]; break;
        case 1: text.erase(at, 1 + rng() % 3); break;
        default: text.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
      }
      if (text.empty()) text = "f";
    }
    file("m.mtl", obj ? mtl : text);
    std::string path = file("mut.obj", obj ? text : base);
    try {
      Scene s = read_obj_scene(path);
      for (const Mesh& m : s.meshes)
        for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size()) << text;
      ++loaded;
    } catch (const Error& e) {
      ++failed;
      ASSERT_EQ(std::string(e.what()).rfind(path, 0), 0u) << e.what();
    }
  }
  EXPECT_GT(loaded, 0);
  EXPECT_GT(failed, 0);
}

}  // namespace
}  // namespace rayform
