// glTF reader: shared sample assets (counts, identical .gltf/.glb/embedded
// data, cameras, texture transforms) and glTF files written here, inline, for
// every feature and every kind of bad input.
#include "rayform/importers/gltf/gltf_reader.h"
#include "rayform/importers/gltf/gltf_material.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/shade_phong.h"
#include "rayform/base/error.h"
#include "rayform/scene/node_walk.h"
#include "rayform/scene/scene_stats.h"
#include "rayform/importers/scene_io.h"
#include "test_importers.h"
#include "test_glb.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

namespace rayform {
namespace {
namespace fs = std::filesystem;

using test::any_contains;
using test::asset;
using test::make_glb;

// ---- building glTF files ----------------------------------------------------------

// A binary buffer assembled from typed pieces, each aligned to 4 bytes.
struct Bin {
  std::vector<uint8_t> bytes;
  template <class T>
  size_t add(const std::vector<T>& v) {
    while (bytes.size() % 4) bytes.push_back(0);
    size_t at = bytes.size();
    bytes.resize(at + v.size() * sizeof(T));
    if (!v.empty()) std::memcpy(bytes.data() + at, v.data(), v.size() * sizeof(T));
    return at;
  }
};

std::string base64(const std::vector<uint8_t>& b) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < b.size(); i += 3) {
    uint32_t v = uint32_t(b[i]) << 16 | uint32_t(b[i + 1]) << 8 | b[i + 2];
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
  }
  if (b.size() - i == 1) {
    uint32_t v = uint32_t(b[i]) << 16;
    out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
  } else if (b.size() - i == 2) {
    uint32_t v = uint32_t(b[i]) << 16 | uint32_t(b[i + 1]) << 8;
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
  }
  return out;
}

std::string data_uri(const Bin& b) { return "data:application/octet-stream;base64," + base64(b.bytes); }

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

// `j` with the placeholders of its one buffer filled in from `bin`: @N@ the
// byteLength, @BUF@ the data URI.
std::string with_buffer(std::string j, const Bin& bin) {
  j = replace_all(j, "@N@", std::to_string(bin.bytes.size()));
  return replace_all(j, "@BUF@", data_uri(bin));
}

// 2x2 RGBA PNG: red, green / blue, white with alpha 128.
const char* png_2x2 =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAAE0lEQVR4nGP4z8DwHwyBNAg0AABJSQl4KKDbdwAAAABJRU5ErkJggg==";

class GltfFiles : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::temp_dir("gltf-reader"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  std::string write_bytes(const std::string& name, const std::vector<uint8_t>& b) {
    std::ofstream(dir_ / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
    return (dir_ / name).string();
  }
  Scene load(const std::string& name, const std::string& json, std::vector<std::string>* warnings = nullptr) {
    return read_gltf_scene(write(name, json), {}, warnings);
  }
  // The error message for a file, "" when it loads.
  std::string error(const std::string& name, const std::string& json) { return error_of(write(name, json)); }
  static std::string error_of(const std::string& path) {
    try {
      read_gltf_scene(path);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

// A unit quad (4 vertices, 2 triangles) with uvs, u16 indices; @BUF@ is its buffer.
struct Quad {
  Bin bin;
  size_t pos, uv, idx;
  Quad() {
    pos = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    uv = bin.add(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0});
    idx = bin.add(std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
  }
  // JSON around the quad: `extra_top` goes at the top level (after buffers).
  std::string json(const std::string& primitive_extra = "", const std::string& top_extra = "",
                   const std::string& node_extra = "") const {
    std::string j = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0 @NODE@}],
  "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2 @PRIM@}]}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ],
  "bufferViews": [
    {"buffer": 0, "byteOffset": @P@, "byteLength": 48},
    {"buffer": 0, "byteOffset": @U@, "byteLength": 32},
    {"buffer": 0, "byteOffset": @I@, "byteLength": 12}
  ],
  "buffers": [{"byteLength": @N@, "uri": "@BUF@"}] @TOP@
})";
    j = replace_all(j, "@P@", std::to_string(pos));
    j = replace_all(j, "@U@", std::to_string(uv));
    j = replace_all(j, "@I@", std::to_string(idx));
    j = with_buffer(j, bin);
    j = replace_all(j, "@PRIM@", primitive_extra);
    j = replace_all(j, "@NODE@", node_extra);
    j = replace_all(j, "@TOP@", top_extra);
    return j;
  }
};

// One mesh primitive over `bin`: positions accessor 0 (`n` VEC3), optional
// index accessor 1, given mode. Returns JSON.
std::string primitive_file(const Bin& bin, size_t n, int mode, const std::string& index_accessor_json,
                           const std::string& views_json) {
  std::string j = R"({
  "asset": {"version": "2.0"},
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": @MODE@ @IDX@}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": @N@, "type": "VEC3"} @IACC@],
  "bufferViews": [@VIEWS@],
  "buffers": [{"byteLength": @LEN@, "uri": "@BUF@"}]
})";
  j = replace_all(j, "@MODE@", std::to_string(mode));
  j = replace_all(j, "@IDX@", index_accessor_json.empty() ? "" : ", \"indices\": 1");
  j = replace_all(j, "@IACC@", index_accessor_json.empty() ? "" : ", " + index_accessor_json);
  j = replace_all(j, "@N@", std::to_string(n));
  j = replace_all(j, "@VIEWS@", views_json);
  j = replace_all(j, "@LEN@", std::to_string(bin.bytes.size()));
  j = replace_all(j, "@BUF@", data_uri(bin));
  return j;
}

std::vector<uint32_t> triangles_as_positions_x(const Scene& s) {
  // The x coordinate of each triangle corner (positions are (i, 0, 0) in these files).
  std::vector<uint32_t> out;
  for (uint32_t i : s.meshes.at(0).indices) out.push_back(uint32_t(s.meshes[0].positions[i].x));
  return out;
}

// ---- shared assets ------------------------------------------------------------------

void expect_same_scene_data(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
    EXPECT_EQ(a.meshes[i].normals, b.meshes[i].normals);
    EXPECT_EQ(a.meshes[i].uvs, b.meshes[i].uvs);
    EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) {
    EXPECT_EQ(a.textures[i].width, b.textures[i].width);
    EXPECT_EQ(a.textures[i].height, b.textures[i].height);
    EXPECT_EQ(a.textures[i].channels, b.textures[i].channels);
    EXPECT_TRUE(a.textures[i].pixels == b.textures[i].pixels);
    EXPECT_EQ(a.textures[i].filter, b.textures[i].filter);
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].diffuse, b.materials[i].diffuse);
    EXPECT_EQ(a.materials[i].specular, b.materials[i].specular);
    EXPECT_EQ(a.materials[i].diffuse_texture, b.materials[i].diffuse_texture);
  }
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) EXPECT_EQ(a.nodes[i].local, b.nodes[i].local);
}

TEST(GltfReader, BoxTexturedGltfGlbAndEmbeddedAreIdentical) {
  RAYFORM_REQUIRE_SHARED();
  Scene gltf = read_gltf_scene(asset("gltf/BoxTextured-glTF/BoxTextured.gltf").string());
  Scene glb = read_gltf_scene(asset("gltf/BoxTextured-glTF-Binary/BoxTextured.glb").string());
  Scene embedded = read_gltf_scene(asset("gltf/BoxTextured-glTF-Embedded/BoxTextured.gltf").string());
  ASSERT_EQ(gltf.meshes.size(), 1u);
  const Mesh& m = gltf.meshes[0];
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_EQ(m.positions.size(), 24u);
  EXPECT_EQ(m.normals.size(), 24u);
  EXPECT_EQ(m.uvs.size(), 24u);
  ASSERT_EQ(gltf.textures.size(), 1u);
  const Texture& t = gltf.textures[0];
  EXPECT_EQ(t.width, 211);  // CesiumLogoFlat.png
  EXPECT_EQ(t.height, 211);
  EXPECT_EQ(t.channels, 4);
  EXPECT_EQ(t.pixels.size(), 211u * 211u * 4u);
  EXPECT_TRUE(t.srgb);
  EXPECT_EQ(t.lookup, Texture::Lookup::standard);
  EXPECT_EQ(t.wrap_u, Texture::Wrap::mirror);  // sampler: wrapS 33648
  EXPECT_EQ(t.wrap_v, Texture::Wrap::clamp);   // wrapT 33071
  EXPECT_EQ(t.filter, Texture::Filter::linear);
  ASSERT_EQ(gltf.materials.size(), 1u);
  const Material& mat = gltf.materials[0];
  EXPECT_EQ(mat.name, "Texture");
  EXPECT_EQ(mat.diffuse_texture, 0);
  EXPECT_TRUE(mat.texture_modulates);
  EXPECT_EQ(mat.diffuse, vec3(1.f));
  EXPECT_EQ(mat.model, Material::Model::metallic_roughness);
  EXPECT_EQ(mat.pbr.base_color_texture.texture, 0);
  EXPECT_EQ(mat.pbr.metallic, 0.f);
  EXPECT_EQ(mat.pbr.roughness, 1.f);
  EXPECT_FALSE(mat.double_sided);
  EXPECT_FALSE(mat.two_sided_lighting);
  EXPECT_TRUE(gltf.cameras.empty());
  // root group -> node 0 (matrix: -90 degrees about x) -> node 1 -> shape.
  EXPECT_EQ(gltf.nodes.size(), 4u);
  std::vector<mat4> worlds;
  for_each_shape_node(gltf, [&](const Node&, const mat4& w) { worlds.push_back(w); });
  ASSERT_EQ(worlds.size(), 1u);
  vec3 y = transform_vector(worlds[0], vec3(0, 1, 0));
  EXPECT_NEAR(y.z, -1.f, 1e-6f);  // the file's y up becomes -z... as its matrix says
  expect_same_scene_data(gltf, glb);
  expect_same_scene_data(gltf, embedded);
  // The one difference the files have: the .glb and embedded copies keep the
  // sample model's REPEAT sampler.
  EXPECT_EQ(glb.textures[0].wrap_u, Texture::Wrap::repeat);
  EXPECT_EQ(embedded.textures[0].wrap_v, Texture::Wrap::repeat);
  EXPECT_TRUE(embedded.textures[0].path.empty());  // data URI
  EXPECT_FALSE(gltf.textures[0].path.empty());     // external file, kept for writers
  EXPECT_TRUE(fs::is_regular_file(gltf.textures[0].path));
}

TEST(GltfReader, DuckMatchesTheDuckObjAndHasItsCamera) {
  RAYFORM_REQUIRE_SHARED();
  Scene g = read_gltf_scene(asset("duck/duck.gltf").string());
  ASSERT_EQ(g.meshes.size(), 1u);
  EXPECT_EQ(g.meshes[0].triangle_count(), 4212u);
  EXPECT_EQ(g.meshes[0].positions.size(), 2399u);
  ASSERT_EQ(g.textures.size(), 1u);
  EXPECT_EQ(g.textures[0].width, 512);
  ASSERT_EQ(g.cameras.size(), 1u);
  const Camera& c = g.cameras[0];
  EXPECT_EQ(c.projection, Camera::Projection::perspective);
  EXPECT_EQ(c.aspect, Camera::Aspect::fit);
  EXPECT_NEAR(c.fov_deg, 0.6605925559997559 * 180.0 / 3.14159265358979, 1e-4);
  // Camera node matrix under the root's 0.01 scale: position = 0.01 x its translation,
  // direction = -(its z column), normalised.
  EXPECT_NEAR(c.center.x, 4.00113f, 1e-4f);
  EXPECT_NEAR(c.center.y, 4.63264f, 1e-4f);
  EXPECT_NEAR(c.center.z, -4.31078f, 1e-4f);
  vec3 z(0.5364750623703003f, 0.6211478114128113f, -0.571287989616394f);
  EXPECT_NEAR(glm::dot(c.direction, -glm::normalize(z)), 1.f, 1e-5f);
  // The OBJ export of the same duck lies in the same place.
  Scene o = read_obj_scene(asset("duck/duck.obj").string());
  Bounds3 bg = scene_stats(g).bounds, bo = scene_stats(o).bounds;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(bg.lo[k], bo.lo[k], 1e-4f);
    EXPECT_NEAR(bg.hi[k], bo.hi[k], 1e-4f);
  }
}

TEST(GltfReader, TwoCylinderEngineInstancesAndCounts) {
  RAYFORM_REQUIRE_SHARED();
  LoadedScene l = load_scene(asset("gltf/2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string());
  EXPECT_EQ(l.format, SceneFormat::gltf);
  const Scene& s = l.scene;
  SceneStats st = scene_stats(s);
  // Counted from the file's JSON by walking its default scene (python).
  EXPECT_EQ(s.meshes.size(), 34u);  // primitives of its 29 meshes
  EXPECT_EQ(st.instances, 115u);    // primitive uses over the 82 nodes
  EXPECT_EQ(st.mesh_triangles, 121496u);
  EXPECT_EQ(st.unique_mesh_triangles, 75730u);
  EXPECT_EQ(s.materials.size(), 34u);
  // Transforms, shape nodes (one per primitive of a mesh, shared by every
  // node that uses the mesh), root.
  EXPECT_EQ(st.nodes, 82u + 34u + 1u);
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_NEAR(s.cameras[0].fov_deg, 0.3143463730812073 * 180.0 / 3.14159265358979, 1e-4);
  // Material_20: base 0.85, metallic 0, roughness 1 (default).
  EXPECT_EQ(s.materials[0].model, Material::Model::metallic_roughness);
  EXPECT_NEAR(s.materials[0].pbr.base_color.x, 0.85f, 1e-6f);
  EXPECT_EQ(s.materials[0].pbr.metallic, 0.f);
  EXPECT_EQ(s.materials[0].pbr.roughness, 1.f);
  EXPECT_NEAR(s.materials[0].diffuse.x, 0.85f, 1e-6f);
  for (const Mesh& m : s.meshes) {
    EXPECT_EQ(m.normals.size(), m.positions.size());
    EXPECT_TRUE(m.uvs.empty());
  }
}

TEST(GltfReader, TextureTransformTestMaterials) {
  RAYFORM_REQUIRE_SHARED();
  std::vector<std::string> warnings;
  Scene s = read_gltf_scene(asset("gltf/textureTransform/TextureTransformTest.gltf").string(), {}, &warnings);
  ASSERT_EQ(s.materials.size(), 9u);
  EXPECT_EQ(s.textures.size(), 5u);
  auto by_name = [&](const std::string& n) -> const Material& {
    for (const Material& m : s.materials)
      if (m.name == n) return m;
    throw std::runtime_error("no material " + n);
  };
  // Offsets: u unchanged, v mirrored by the flip.
  EXPECT_EQ(by_name("Offset U").uv_transform.offset, vec2(0.5f, 0.f));
  EXPECT_EQ(by_name("Offset V").uv_transform.offset, vec2(0.f, -0.5f));
  EXPECT_EQ(by_name("Offset UV").uv_transform.offset, vec2(0.5f, -0.5f));
  const UvTransform& rot = by_name("Rotation").uv_transform;
  EXPECT_FLOAT_EQ(rot.rotation, -0.39269908169872414f);
  EXPECT_NEAR(rot.offset.x, std::sin(0.39269908f), 1e-6f);
  EXPECT_NEAR(rot.offset.y, 1.f - std::cos(0.39269908f), 1e-6f);
  const UvTransform& scale = by_name("Scale").uv_transform;
  EXPECT_EQ(scale.scale, vec2(1.5f));
  EXPECT_NEAR(scale.offset.y, -0.5f, 1e-6f);
  EXPECT_TRUE(by_name("Correct").uv_transform.is_identity());
  // Sampler 0 (clamp) on textures 0 and 1; the rest use the default sampler.
  EXPECT_EQ(s.textures[by_name("Rotation").diffuse_texture].wrap_u, Texture::Wrap::clamp);
  EXPECT_EQ(s.textures[by_name("Correct").diffuse_texture].wrap_u, Texture::Wrap::repeat);
  // 9 meshes (one primitive each), 12 instances: the markers are instanced.
  EXPECT_EQ(s.meshes.size(), 9u);
  EXPECT_EQ(scene_stats(s).instances, 12u);
  // The offset quads use TEXCOORD_0 = accessor 2 (uvs 0..0.5), flipped.
  const Mesh& offset_u = s.meshes[0];
  EXPECT_EQ(offset_u.uvs[2], vec2(0.5f, 0.5f));
  EXPECT_EQ(offset_u.uvs[0], vec2(0.f, 1.f));
  EXPECT_FALSE(any_contains(warnings, "KHR_texture_transform"));
}

// The stored transform, applied by the renderer's own shading code to the
// stored (flipped) uvs, fetches the texel glTF's KHR_texture_transform names.
TEST(GltfReader, UvTransformMatchesTheSpecificationThroughTheShader) {
  const int W = 16, H = 8;
  Scene scene;
  PreparedScene p;
  TextureImage img;
  img.width = W;
  img.height = H;
  img.rgbaf.assign(size_t(W) * H * 4, 0.f);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      float* px = &img.rgbaf[(size_t(y) * W + x) * 4];
      px[0] = float(x);
      px[1] = float(y);
      px[3] = 1.f;
    }
  img.filter = Texture::Filter::nearest;
  img.wrap_u = img.wrap_v = Texture::Wrap::repeat;
  img.lookup = Texture::Lookup::standard;
  p.scene = &scene;
  p.textures.push_back(img);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u01(0.f, 1.f), ang(-3.f, 3.f), sc(0.3f, 2.f), off(-1.f, 1.f);
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    vec2 o(off(rng), off(rng)), s(sc(rng), sc(rng));
    float r = ang(rng);
    vec2 uv(u01(rng), u01(rng));
    // glTF: t = T R S uv with R rows (cos, sin), (-sin, cos); texel (floor(t.u W), floor(t.v H)), v down.
    vec2 su = uv * s;
    vec2 t = vec2(std::cos(r) * su.x + std::sin(r) * su.y, -std::sin(r) * su.x + std::cos(r) * su.y) + o;
    float fx = t.x * W, fy = t.y * H;
    // Stay away from texel edges, where rounding may pick either texel.
    if (std::abs(fx - std::round(fx)) < 0.02f || std::abs(fy - std::round(fy)) < 0.02f) continue;
    int ex = ((int(std::floor(fx)) % W) + W) % W, ey = ((int(std::floor(fy)) % H) + H) % H;
    Material m;
    m.diffuse_texture = 0;
    m.texture_modulates = true;
    m.uv_transform = gltf_uv_transform_to_scene(o, r, s);
    SurfacePoint sp;
    sp.has_uv = true;
    sp.uv = vec2(uv.x, 1.f - uv.y);  // as the reader stores it
    vec4 k = surface_albedo(p, m, sp);
    ASSERT_EQ(int(k.r), ex) << "trial " << trial;
    ASSERT_EQ(int(k.g), ey) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

// ---- features, on files of our own ----------------------------------------------------

TEST_F(GltfFiles, QuadWithDataUriAndDefaultMaterial) {
  Quad q;
  std::vector<std::string> warnings;
  Scene s = load("quad.gltf", q.json(), &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.name, "quad");
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(m.positions[2], vec3(1, 1, 0));
  EXPECT_TRUE(m.normals.empty());  // no NORMAL: flat, by the renderer's face normals
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.uvs[0], vec2(0, 0));  // glTF (0, 1) flipped to v = 1 - 1
  EXPECT_EQ(m.uvs[2], vec2(1, 1));
  ASSERT_EQ(s.materials.size(), 1u);  // the specification's default material
  EXPECT_EQ(s.materials[0].name, "default");
  EXPECT_EQ(s.materials[0].diffuse, vec3(1.f));
  EXPECT_EQ(s.materials[0].specular, vec3(0.f));
  EXPECT_EQ(s.source_path, (dir_ / "quad.gltf").string());
  // root group -> node 0 (transform) -> shape
  const Node& root = s.nodes[s.root];
  EXPECT_EQ(root.kind, Node::Kind::group);
  ASSERT_EQ(root.children.size(), 1u);
  const Node& n0 = s.nodes[root.children[0]];
  EXPECT_EQ(n0.kind, Node::Kind::transform);
  EXPECT_EQ(n0.local, mat4(1.f));
  ASSERT_EQ(n0.children.size(), 1u);
  EXPECT_EQ(s.nodes[n0.children[0]].kind, Node::Kind::shape);
  EXPECT_EQ(s.nodes[n0.children[0]].material, 0);
}

TEST_F(GltfFiles, ExternalBinAndImageAndGlbGiveTheSameScene) {
  Quad q;
  // external .bin and .png
  std::ofstream(dir_ / "quad.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(q.bin.bytes.data()), std::streamsize(q.bin.bytes.size()));
  std::string tex = R"(, "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
    "textures": [{"source": 0, "sampler": 0}], "samplers": [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33648}],
    "images": [{"uri": "@IMG@"}])";
  std::string external = replace_all(q.json(", \"material\": 0", tex), data_uri(q.bin), "quad.bin");
  // the PNG as a file
  std::vector<uint8_t> png;
  {
    std::string b64 = png_2x2;
    auto val = [](char c) -> int {
      if (c >= 'A' && c <= 'Z') return c - 'A';
      if (c >= 'a' && c <= 'z') return c - 'a' + 26;
      if (c >= '0' && c <= '9') return c - '0' + 52;
      return c == '+' ? 62 : c == '/' ? 63 : -1;
    };
    uint32_t acc = 0;
    int bits = 0;
    for (char c : b64) {
      int v = val(c);
      if (v < 0) continue;
      acc = (acc << 6) | uint32_t(v);
      bits += 6;
      if (bits >= 8) {
        bits -= 8;
        png.push_back(uint8_t(acc >> bits));
      }
    }
  }
  write_bytes("tex 1.png", png);
  std::string ext_json = replace_all(external, "@IMG@", "tex%201.png");  // URIs are percent-encoded
  Scene a = load("external.gltf", ext_json);
  ASSERT_EQ(a.textures.size(), 1u);
  const Texture& t = a.textures[0];
  EXPECT_EQ(t.width, 2);
  EXPECT_EQ(t.height, 2);
  EXPECT_EQ(t.channels, 4);
  EXPECT_EQ(t.pixels, (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128}));
  EXPECT_EQ(t.filter, Texture::Filter::nearest);
  EXPECT_EQ(t.wrap_u, Texture::Wrap::clamp);
  EXPECT_EQ(t.wrap_v, Texture::Wrap::mirror);
  EXPECT_EQ(fs::path(t.path), dir_ / "tex 1.png");
  // Embedded: buffer and image as data URIs.
  std::string embedded =
      replace_all(q.json(", \"material\": 0", tex), "@IMG@", std::string("data:image/png;base64,") + png_2x2);
  Scene b = load("embedded.gltf", embedded);
  expect_same_scene_data(a, b);
  EXPECT_EQ(b.textures[0].wrap_v, Texture::Wrap::mirror);
  // GLB: buffer 0 is the BIN chunk (no uri), the image in a bufferView.
  Bin glb_bin = q.bin;
  size_t png_at = glb_bin.add(png);
  std::string glb_json =
      replace_all(q.json(", \"material\": 0", tex), "\"uri\": \"" + data_uri(q.bin) + "\"", "\"x\": 0");
  glb_json = replace_all(glb_json, "\"images\": [{\"uri\": \"@IMG@\"}]",
                         "\"images\": [{\"bufferView\": 3, \"mimeType\": \"image/png\"}]");
  glb_json = replace_all(glb_json, "{\"buffer\": 0, \"byteOffset\": " + std::to_string(q.idx) + ", \"byteLength\": 12}",
                         "{\"buffer\": 0, \"byteOffset\": " + std::to_string(q.idx) +
                             ", \"byteLength\": 12}, {\"buffer\": 0, \"byteOffset\": " + std::to_string(png_at) +
                             ", \"byteLength\": " + std::to_string(png.size()) + "}");
  glb_json = replace_all(glb_json, "\"byteLength\": " + std::to_string(q.bin.bytes.size()) + ",",
                         "\"byteLength\": " + std::to_string(glb_bin.bytes.size()) + ",");
  Scene c = read_gltf_scene(write_bytes("quad.glb", make_glb(glb_json, glb_bin.bytes)));
  expect_same_scene_data(a, c);
  EXPECT_EQ(c.textures[0].wrap_u, Texture::Wrap::clamp);
  // The extension does not decide: a GLB named .gltf loads too.
  Scene d = read_gltf_scene(write_bytes("glb-named.gltf", make_glb(glb_json, glb_bin.bytes)));
  expect_same_scene_data(a, d);
}

TEST_F(GltfFiles, StripsFansAndIndexTypes) {
  // Positions (i, 0, 0) so that triangles can be read back as vertex numbers.
  Bin bin;
  size_t pos = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0, 5, 0, 0});
  std::string views = "{\"buffer\": 0, \"byteOffset\": " + std::to_string(pos) + ", \"byteLength\": 72}";
  // Non-indexed strip of 6: p_i = {v_i, v_{i+1+i%2}, v_{i+2-i%2}}.
  Scene strip = load("strip.gltf", primitive_file(bin, 6, 5, "", views));
  EXPECT_EQ(triangles_as_positions_x(strip), (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4, 3, 5, 4}));
  // Non-indexed fan of 5: p_i = {v_{i+1}, v_{i+2}, v_0}.
  Scene fan = load("fan.gltf", primitive_file(bin, 5, 6, "", views));
  EXPECT_EQ(triangles_as_positions_x(fan), (std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
  // Indexed, u8 / u16 / u32: the same strip through indices 5 4 3 2 1, a
  // repeated index making a degenerate (dropped) joint triangle.
  const std::vector<uint32_t> order = {5, 4, 3, 3, 2, 1};
  for (int ct : {5121, 5123, 5125}) {
    Bin b = bin;
    size_t at = 0;
    if (ct == 5121) at = b.add(std::vector<uint8_t>(order.begin(), order.end()));
    if (ct == 5123) at = b.add(std::vector<uint16_t>(order.begin(), order.end()));
    if (ct == 5125) at = b.add(order);
    size_t len = order.size() * (ct == 5121 ? 1 : ct == 5123 ? 2 : 4);
    std::string v = views + ", {\"buffer\": 0, \"byteOffset\": " + std::to_string(at) +
                    ", \"byteLength\": " + std::to_string(len) + "}";
    std::string acc =
        "{\"bufferView\": 1, \"componentType\": " + std::to_string(ct) + ", \"count\": 6, \"type\": \"SCALAR\"}";
    Scene s = load("idx" + std::to_string(ct) + ".gltf", primitive_file(b, 6, 5, acc, v));
    // i=0 {5,4,3}; i=1 {4,3,3} dropped; i=2 {3,3,2} dropped; i=3 {3,1,2}.
    EXPECT_EQ(triangles_as_positions_x(s), (std::vector<uint32_t>{5, 4, 3, 3, 1, 2})) << ct;
    // As a triangle list the same indices give two triangles, kept as written.
    Scene list = load("list" + std::to_string(ct) + ".gltf", primitive_file(b, 6, 4, acc, v));
    EXPECT_EQ(triangles_as_positions_x(list), order) << ct;
  }
}

TEST_F(GltfFiles, ByteStrideInterleavedAttributes) {
  // position (12 bytes) + uv (8 bytes) + 4 bytes padding: stride 24.
  std::vector<float> inter;
  const float pos[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    inter.insert(inter.end(), {pos[i][0], pos[i][1], pos[i][2], uv[i][0], uv[i][1], -99.f});
  }
  Bin bin;
  bin.add(inter);
  std::string j = R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
    "textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,@PNG@"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
    "accessors": [{"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                  {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC2"}],
    "bufferViews": [{"buffer": 0, "byteLength": 96, "byteStride": 24}],
    "buffers": [{"byteLength": 96, "uri": "@BUF@"}]})";
  j = replace_all(replace_all(j, "@BUF@", data_uri(bin)), "@PNG@", png_2x2);
  std::vector<std::string> warnings;
  Scene s = load("stride.gltf", j, &warnings);
  const Mesh& m = s.meshes.at(0);
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[1], vec3(2, 0, 0));
  EXPECT_EQ(m.positions[3], vec3(0, 2, 0));
  EXPECT_EQ(m.uvs[1], vec2(1, 1));  // (1, 0) flipped
  EXPECT_EQ(m.uvs[2], vec2(1, 0));
  // 4 vertices without indices in TRIANGLES: one triangle, one vertex left over (warned).
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_TRUE(any_contains(warnings, "not a multiple of 3"));
}

TEST_F(GltfFiles, SparseAccessors) {
  Bin bin;
  size_t base = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  size_t sidx = bin.add(std::vector<uint16_t>{1, 3});
  size_t sval = bin.add(std::vector<float>{5, 0, 0, 5, 5, 0});
  size_t zidx = bin.add(std::vector<uint8_t>{2});
  size_t zval = bin.add(std::vector<float>{0.5f, 0.25f});
  std::string j = R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
    "textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,@PNG@"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0, "mode": 5}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
       "sparse": {"count": 2, "indices": {"bufferView": 1, "componentType": 5123},
                  "values": {"bufferView": 2}}},
      {"componentType": 5126, "count": 4, "type": "VEC2",
       "sparse": {"count": 1, "indices": {"bufferView": 3, "componentType": 5121},
                  "values": {"bufferView": 4}}}],
    "bufferViews": [{"buffer": 0, "byteOffset": @B@, "byteLength": 48}, {"buffer": 0, "byteOffset": @SI@, "byteLength": 4},
                    {"buffer": 0, "byteOffset": @SV@, "byteLength": 24}, {"buffer": 0, "byteOffset": @ZI@, "byteLength": 1},
                    {"buffer": 0, "byteOffset": @ZV@, "byteLength": 8}],
    "buffers": [{"byteLength": @N@, "uri": "@BUF@"}]})";
  j = replace_all(j, "@B@", std::to_string(base));
  j = replace_all(j, "@SI@", std::to_string(sidx));
  j = replace_all(j, "@SV@", std::to_string(sval));
  j = replace_all(j, "@ZI@", std::to_string(zidx));
  j = replace_all(j, "@ZV@", std::to_string(zval));
  j = replace_all(with_buffer(j, bin), "@PNG@", png_2x2);
  Scene s = load("sparse.gltf", j);
  const Mesh& m = s.meshes.at(0);
  EXPECT_EQ(m.positions, (std::vector<vec3>{{0, 0, 0}, {5, 0, 0}, {0, 1, 0}, {5, 5, 0}}));
  // No bufferView: zeros, then element 2 replaced (and flipped).
  EXPECT_EQ(m.uvs, (std::vector<vec2>{{0, 1}, {0, 1}, {0.5f, 0.75f}, {0, 1}}));
  EXPECT_EQ(m.triangle_count(), 2u);
}

TEST_F(GltfFiles, NormalizedIntegerUvsAndColours) {
  Bin bin;
  size_t pos = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  size_t uv = bin.add(std::vector<uint16_t>{0, 65535, 65535, 65535, 0, 0});
  size_t col = bin.add(std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 51, 0});
  std::string j = R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "COLOR_0": 2}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 1, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC4"}],
    "bufferViews": [{"buffer": 0, "byteOffset": @P@, "byteLength": 36}, {"buffer": 0, "byteOffset": @U@, "byteLength": 12},
                    {"buffer": 0, "byteOffset": @C@, "byteLength": 12}],
    "buffers": [{"byteLength": @N@, "uri": "@BUF@"}]})";
  j = replace_all(j, "@P@", std::to_string(pos));
  j = replace_all(j, "@U@", std::to_string(uv));
  j = replace_all(j, "@C@", std::to_string(col));
  j = with_buffer(j, bin);
  Scene s = load("norm.gltf", j);
  const Mesh& m = s.meshes.at(0);
  EXPECT_EQ(m.uvs, (std::vector<vec2>{{0, 0}, {1, 0}, {0, 1}}));
  ASSERT_EQ(m.colors.size(), 3u);
  EXPECT_EQ(m.colors[0], vec3(1, 0, 0));
  EXPECT_EQ(m.colors[1], vec3(0, 1, 0));
  EXPECT_NEAR(m.colors[2].z, 0.2f, 1e-6f);
}

TEST_F(GltfFiles, NodeHierarchyTrsAndMatrix) {
  Quad q;
  std::string j = q.json(
      "", "",
      R"(, "children": [1, 2], "translation": [1, 2, 3], "rotation": [0, 0, 0.7071068, 0.7071068], "scale": [2, 2, 2])");
  j = replace_all(j, R"("nodes": [{"mesh": 0 ,)", R"("nodes": [{"mesh": 0,)");
  // add nodes 1 (matrix, translate 10 on x) and 2 (empty)
  j = replace_all(
      j, R"("scale": [2, 2, 2]}],)",
      R"("scale": [2, 2, 2]}, {"name": "child", "mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 10,0,0,1]}, {"name": "empty"}],)");
  Scene s = load("tree.gltf", j);
  std::vector<std::pair<std::string, mat4>> shapes;
  for_each_shape_node(s, [&](const Node& n, const mat4& w) { shapes.emplace_back(n.name, w); });
  ASSERT_EQ(shapes.size(), 2u);
  EXPECT_EQ(s.meshes.size(), 1u);  // one glTF mesh used twice: shared
  // Parent: T R S applied to (1, 0, 0): scale 2 -> (2,0,0), rotate 90 deg about z -> (0,2,0), + (1,2,3).
  vec3 p = transform_point(shapes[0].second, vec3(1, 0, 0));
  EXPECT_NEAR(p.x, 1.f, 1e-5f);
  EXPECT_NEAR(p.y, 4.f, 1e-5f);
  EXPECT_NEAR(p.z, 3.f, 1e-5f);
  // Child: parent x matrix: (0,0,0) -> (10,0,0) -> parent -> (1, 2+20, 3).
  vec3 c = transform_point(shapes[1].second, vec3(0, 0, 0));
  EXPECT_NEAR(c.x, 1.f, 1e-4f);
  EXPECT_NEAR(c.y, 22.f, 1e-4f);
  EXPECT_NEAR(c.z, 3.f, 1e-4f);
  bool found_empty = false;
  for (const Node& n : s.nodes)
    found_empty |= n.name == "empty" && n.kind == Node::Kind::transform && n.children.empty();
  EXPECT_TRUE(found_empty);
}

TEST_F(GltfFiles, CamerasAndPunctualLights) {
  Quad q;
  std::string top = R"(, "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}},
                   {"type": "orthographic", "orthographic": {"xmag": 3, "ymag": 2, "znear": 0, "zfar": 10}}],
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [
      {"type": "directional", "color": [1, 0.5, 0.25], "intensity": 2},
      {"type": "point", "intensity": 10, "range": 5},
      {"type": "spot", "intensity": 3, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}}]}})";
  std::string j = q.json("", top, R"(, "children": [1, 2, 3, 4, 5])");
  j = replace_all(j, R"("nodes": [{"mesh": 0 , "children": [1, 2, 3, 4, 5]}],)",
                  R"("nodes": [{"mesh": 0, "children": [1, 2, 3, 4, 5], "translation": [0, 0, 10]},
      {"camera": 0},
      {"camera": 1, "rotation": [0, 0.7071068, 0, 0.7071068]},
      {"translation": [1, 2, 3], "rotation": [-0.7071068, 0, 0, 0.7071068], "extensions": {"KHR_lights_punctual": {"light": 0}}},
      {"translation": [4, 5, 6], "extensions": {"KHR_lights_punctual": {"light": 1}}},
      {"extensions": {"KHR_lights_punctual": {"light": 2}}}],)");
  std::vector<std::string> warnings;
  Scene s = load("camlights.gltf", j, &warnings);
  EXPECT_FALSE(any_contains(warnings, "KHR_lights_punctual")) << warnings.front();
  ASSERT_EQ(s.cameras.size(), 2u);
  const Camera& persp = s.cameras[0];
  EXPECT_EQ(persp.projection, Camera::Projection::perspective);
  EXPECT_EQ(persp.aspect, Camera::Aspect::fit);
  EXPECT_NEAR(persp.fov_deg, 0.5 * 180.0 / 3.14159265358979, 1e-4);
  EXPECT_EQ(persp.center, vec3(0, 0, 10));
  EXPECT_EQ(persp.direction, vec3(0, 0, -1));
  EXPECT_EQ(persp.up, vec3(0, 1, 0));
  const Camera& ortho = s.cameras[1];
  EXPECT_EQ(ortho.projection, Camera::Projection::orthographic);
  EXPECT_FLOAT_EQ(ortho.ortho_height, 4.f);     // 2 * ymag
  EXPECT_NEAR(ortho.direction.x, -1.f, 1e-6f);  // 90 degrees about y: -z turns to -x
  ASSERT_EQ(s.lights.size(), 3u);
  const Light& sun = s.lights[0];
  EXPECT_EQ(sun.kind, Light::Kind::directional);
  const float pi = 3.14159265358979f;
  EXPECT_EQ(sun.color, vec3(2, 1, 0.5f) / pi);  // colour x intensity / pi (scene.h's units)
  EXPECT_NEAR(sun.direction.y, -1.f, 1e-6f);    // -90 degrees about x: -z turns to -y
  EXPECT_EQ(sun.falloff, 0.f);
  const Light& point = s.lights[1];
  EXPECT_EQ(point.kind, Light::Kind::point);
  EXPECT_EQ(point.position, vec3(4, 5, 16));
  EXPECT_EQ(point.color, vec3(10.f / pi));  // 10 cd: 10 lx at 1 m, the radiance 10 / pi off white Lambert
  EXPECT_EQ(point.falloff, 1.f);            // inverse square
  EXPECT_EQ(point.range, 5.f);
  const Light& spot = s.lights[2];
  EXPECT_EQ(spot.kind, Light::Kind::spot);
  EXPECT_NEAR(spot.spot_inner_deg, 0.2 * 180.0 / 3.14159265358979, 1e-4);
  EXPECT_NEAR(spot.spot_outer_deg, 0.6 * 180.0 / 3.14159265358979, 1e-4);
  EXPECT_EQ(spot.direction, vec3(0, 0, -1));
  EXPECT_EQ(spot.falloff, 1.f);
  EXPECT_EQ(spot.color, vec3(3.f / pi));
}

TEST_F(GltfFiles, MaterialAsTheFileMeansIt) {
  Quad q;
  std::string top =
      R"(, "extensionsUsed": ["KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_materials_clearcoat"],
    "materials": [{"name": "m", "doubleSided": true, "alphaMode": "MASK", "alphaCutoff": 0.3,
      "emissiveFactor": [0.1, 0.2, 0.3],
      "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}},
      "normalTexture": {"index": 0},
      "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 0.5], "metallicFactor": 0.5, "roughnessFactor": 0.5,
        "baseColorTexture": {"index": 0, "texCoord": 0, "extensions": {"KHR_texture_transform":
          {"offset": [0.1, 0.2], "rotation": 0.3, "scale": [2, 3], "texCoord": 1}}}}}],
    "textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,@PNG@"}])";
  std::string j = q.json(", \"material\": 0", replace_all(top, "@PNG@", png_2x2));
  // give the primitive a TEXCOORD_1 (the transform's override) distinct from TEXCOORD_0
  j = replace_all(j, R"("TEXCOORD_0": 1})", R"("TEXCOORD_0": 1, "TEXCOORD_1": 3})");
  j = replace_all(j, R"({"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"})",
                  R"({"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
                     {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC2"})");
  std::vector<std::string> warnings;
  Scene s = load("material.gltf", j, &warnings);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  EXPECT_EQ(m.name, "m");
  EXPECT_EQ(m.model, Material::Model::metallic_roughness);
  EXPECT_EQ(m.pbr.base_color, vec4(0.5f, 0.25f, 1.f, 0.5f));
  EXPECT_EQ(m.pbr.metallic, 0.5f);
  EXPECT_EQ(m.pbr.roughness, 0.5f);
  EXPECT_EQ(m.pbr.emissive, vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(m.pbr.emissive_strength, 2.f);
  EXPECT_EQ(m.pbr.alpha_mode, PbrMaterial::AlphaMode::mask);
  EXPECT_FLOAT_EQ(m.pbr.alpha_cutoff, 0.3f);
  EXPECT_TRUE(m.double_sided);
  EXPECT_TRUE(m.two_sided_lighting);  // the specification reverses back-face normals
  // The albedo in the Phong fields; nothing else of Phong's.
  EXPECT_EQ(m.diffuse, vec3(0.5f, 0.25f, 1.f));
  EXPECT_EQ(m.specular, vec3(0.f));
  EXPECT_EQ(m.emission, vec3(0.f));
  EXPECT_TRUE(m.texture_modulates);
  // One glTF texture used as colour (base) and as data (normal): two Scene textures.
  ASSERT_EQ(s.textures.size(), 2u);
  const TextureSlot& base = m.pbr.base_color_texture;
  ASSERT_EQ(m.diffuse_texture, base.texture);
  EXPECT_TRUE(s.textures[size_t(base.texture)].srgb);
  EXPECT_FALSE(s.textures[size_t(m.pbr.normal_texture.texture)].srgb);
  EXPECT_EQ(m.pbr.normal_texture.texcoord, 0);
  EXPECT_EQ(s.textures[size_t(base.texture)].wrap_u, Texture::Wrap::repeat);  // no sampler: the default one
  UvTransform expect = gltf_uv_transform_to_scene(vec2(0.1f, 0.2f), 0.3f, vec2(2, 3));
  EXPECT_EQ(base.transform.offset, expect.offset);
  EXPECT_EQ(base.transform.scale, vec2(2, 3));
  EXPECT_FLOAT_EQ(base.transform.rotation, -0.3f);
  EXPECT_EQ(m.uv_transform.offset, expect.offset);
  // texCoord 1 (the extension's override) is the base colour's set; both
  // sets are read: accessor 3 reads the position floats as pairs (0,0) (0,1)
  // (0,0) (1,1), TEXCOORD_0 is the quad's (0,1) (1,1) (1,0) (0,0).
  EXPECT_EQ(base.texcoord, 1);
  const Mesh& mesh = s.meshes.at(0);
  EXPECT_EQ(mesh.uvs1[3], vec2(1, 0));                // (1, 1) flipped
  EXPECT_EQ(mesh.uvs1[1], vec2(0, 0));                // (0, 1) flipped
  EXPECT_EQ(mesh.uvs[3], vec2(0, 1));                 // (0, 0) flipped
  EXPECT_TRUE(warnings.empty()) << warnings.front();  // the normal texture is kept, not "ignored"
}

TEST_F(GltfFiles, PointsAndLinesAreSkippedWithAWarning) {
  Quad q;
  std::string j = q.json(", \"mode\": 1");
  std::vector<std::string> warnings;
  Scene s = load("lines.gltf", j, &warnings);
  EXPECT_TRUE(s.meshes.empty());
  EXPECT_TRUE(any_contains(warnings, "meshes[0].primitives[0]: lines are not rendered"));
  s = load("points.gltf", q.json(", \"mode\": 0"), &warnings);
  EXPECT_TRUE(any_contains(warnings, "points are not rendered"));
}

TEST_F(GltfFiles, MissingImageIsAWarning) {
  Quad q;
  std::string top = R"(, "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
    "textures": [{"source": 0}], "images": [{"uri": "gone.png"}, {"uri": "data:image/png;base64,AAAA"}])";
  std::vector<std::string> warnings;
  Scene s = load("noimage.gltf", q.json(", \"material\": 0", top), &warnings);
  EXPECT_TRUE(any_contains(warnings, "cannot find image file 'gone.png'")) << warnings.front();
  EXPECT_TRUE(any_contains(warnings, "images[1]: cannot decode"));
  EXPECT_TRUE(s.textures.empty());
  EXPECT_EQ(s.materials.at(0).diffuse_texture, invalid);
}

// ---- bad input ---------------------------------------------------------------------------

TEST_F(GltfFiles, IndexOutOfRange) {
  Quad q;
  Bin& b = q.bin;
  // overwrite index 5 (value 3) with 40
  uint16_t forty = 40;
  std::memcpy(b.bytes.data() + q.idx + 10, &forty, 2);
  // two meshes so that the culprit is meshes[1]
  std::string j = q.json();
  j = replace_all(j, R"("meshes": [{"name": "quad", )", R"("meshes": [{"primitives": []}, {"name": "quad", )");
  j = replace_all(j, R"("nodes": [{"mesh": 0 }])", R"("nodes": [{"mesh": 1 }])");
  std::string e = error("badindex.gltf", j);
  EXPECT_EQ(
      e, (dir_ / "badindex.gltf").string() +
             ": meshes[1].primitives[0].indices: index 40 (element 5) is out of range (the primitive has 4 vertices)");
}

TEST_F(GltfFiles, AccessorPastTheEndOfItsBufferView) {
  Quad q;
  std::string j = replace_all(q.json(), R"("count": 4, "type": "VEC3")", R"("count": 5, "type": "VEC3")");
  std::string e = error("pastview.gltf", j);
  EXPECT_NE(e.find("meshes[0].primitives[0].attributes.POSITION (accessors[0]): 5 elements of 12 bytes (stride 12) "
                   "from byte 0 run past the end of bufferViews[0] (48 bytes)"),
            std::string::npos)
      << e;
  std::string offset =
      replace_all(q.json(), R"({"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"})",
                  R"({"bufferView": 1, "byteOffset": 4, "componentType": 5126, "count": 4, "type": "VEC2"})");
  EXPECT_NE(error("offset.gltf", offset).find("attributes.TEXCOORD_0 (accessors[1])"), std::string::npos);
}

TEST_F(GltfFiles, BufferViewPastTheEndOfItsBuffer) {
  Quad q;
  std::string j = replace_all(q.json(), R"("byteOffset": )" + std::to_string(q.idx) + R"(, "byteLength": 12)",
                              R"("byteOffset": )" + std::to_string(q.idx) + R"(, "byteLength": 4000)");
  std::string e = error("pastbuffer.gltf", j);
  EXPECT_NE(e.find("bufferViews[2]: bytes " + std::to_string(q.idx) + " to " + std::to_string(q.idx + 4000) +
                   " lie past the end of buffers[0] (92 bytes)"),
            std::string::npos)
      << e;
}

TEST_F(GltfFiles, MissingBinFile) {
  Quad q;
  std::string j = replace_all(q.json(), data_uri(q.bin), "missing.bin");
  std::string e = error("nobin.gltf", j);
  EXPECT_EQ(
      e, (dir_ / "nobin.gltf").string() + ": buffers[0]: cannot find 'missing.bin' (looked in " + dir_.string() + ")");
  // A .bin of the wrong size.
  std::ofstream(dir_ / "short.bin", std::ios::binary) << "0123";
  EXPECT_NE(error("shortbin.gltf", replace_all(q.json(), data_uri(q.bin), "short.bin"))
                .find("buffers[0]: 'short.bin' has 4 bytes but byteLength is 92"),
            std::string::npos);
}

TEST_F(GltfFiles, RecursiveNodeGraph) {
  Quad q;
  std::string j = replace_all(q.json(), R"("nodes": [{"mesh": 0 }])",
                              R"("nodes": [{"mesh": 0, "children": [1]}, {"children": [2]}, {"children": [1]}])");
  EXPECT_NE(error("cycle.gltf", j).find("nodes[2].children[0]: nodes[1] is its own ancestor (recursive node graph)"),
            std::string::npos)
      << error("cycle.gltf", j);
  std::string self = replace_all(q.json(), R"("nodes": [{"mesh": 0 }])", R"("nodes": [{"mesh": 0, "children": [0]}])");
  EXPECT_NE(error("self.gltf", self).find("recursive node graph"), std::string::npos);
  // No scene: all nodes are children of others.
  std::string noscene = replace_all(replace_all(self, R"("scene": 0,)", ""), R"("scenes": [{"nodes": [0]}],)", "");
  EXPECT_NE(error("noscene.gltf", noscene).find("recursive"), std::string::npos) << error("noscene.gltf", noscene);
  std::string badchild =
      replace_all(q.json(), R"("nodes": [{"mesh": 0 }])", R"("nodes": [{"mesh": 0, "children": [7]}])");
  EXPECT_NE(error("badchild.gltf", badchild).find("nodes[0].children[0]: node 7 does not exist (the file has 1 nodes)"),
            std::string::npos);
}

TEST_F(GltfFiles, VeryDeepHierarchyIsRefused) {
  Quad q;
  std::string nodes = "\"nodes\": [";
  for (int i = 0; i < 5000; ++i) nodes += "{\"children\": [" + std::to_string(i + 1) + "]}, ";
  nodes += "{\"mesh\": 0}]";
  std::string j = replace_all(q.json(), R"("nodes": [{"mesh": 0 }])", nodes);
  EXPECT_NE(error("deep.gltf", j)
                .find("nodes[253].children[0]: the node hierarchy is too deep (a scene holds at most 256 levels)"),
            std::string::npos)
      << error("deep.gltf", j);
}

// The deepest hierarchy a Scene holds loads: root group, 254 glTF levels, shapes.
TEST_F(GltfFiles, DeepestAllowedHierarchyLoads) {
  Quad q;
  std::string nodes = "\"nodes\": [";
  for (int i = 0; i < max_node_depth - 3; ++i) nodes += "{\"children\": [" + std::to_string(i + 1) + "]}, ";
  nodes += "{\"mesh\": 0}]";
  std::string j = replace_all(q.json(), R"("nodes": [{"mesh": 0 }])", nodes);
  Scene s = load("deepest.gltf", j);
  int shapes = 0;
  for_each_shape_node(s, [&](const Node&, const mat4&) { ++shapes; });
  EXPECT_EQ(shapes, 1);
}

TEST_F(GltfFiles, NonFinitePositions) {
  Quad q;
  float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  std::memcpy(q.bin.bytes.data() + q.pos + 4 * 4, &nan, 4);
  EXPECT_NE(error("nan.gltf", q.json()).find("meshes[0].primitives[0].attributes.POSITION: vertex 1 is not finite"),
            std::string::npos)
      << error("nan.gltf", q.json());
  Quad r;
  std::memcpy(r.bin.bytes.data() + r.pos + 4 * 11, &inf, 4);
  EXPECT_NE(error("inf.gltf", r.json()).find("vertex 3 is not finite"), std::string::npos);
  // Non-finite transforms too.
  Quad t;
  std::string j =
      replace_all(t.json(), R"("nodes": [{"mesh": 0 }])", R"("nodes": [{"mesh": 0, "scale": [1, 1e999, 1]}])");
  std::string e = error("infscale.gltf", j);
  EXPECT_FALSE(e.empty());
}

TEST_F(GltfFiles, WrongAccessorTypes) {
  Quad q;
  std::string vec2pos = replace_all(q.json(), R"({"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"})",
                                    R"({"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC2"})");
  EXPECT_NE(error("vec2pos.gltf", vec2pos)
                .find("attributes.POSITION (accessors[0]): accessor is VEC2 of FLOAT, expected VEC3 of FLOAT"),
            std::string::npos)
      << error("vec2pos.gltf", vec2pos);
  std::string floatidx = replace_all(q.json(), R"("componentType": 5123, "count": 6, "type": "SCALAR")",
                                     R"("componentType": 5126, "count": 3, "type": "SCALAR")");
  EXPECT_NE(error("floatidx.gltf", floatidx)
                .find("indices (accessors[2]): accessor is SCALAR of FLOAT, expected SCALAR of UNSIGNED_BYTE"),
            std::string::npos)
      << error("floatidx.gltf", floatidx);
  std::string intuv = replace_all(q.json(), R"({"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"})",
                                  R"({"bufferView": 1, "componentType": 5125, "count": 4, "type": "VEC2"})");
  EXPECT_NE(error("intuv.gltf", intuv).find("TEXCOORD_0 (accessors[1]): accessor is VEC2 of UNSIGNED_INT"),
            std::string::npos);
  std::string noacc = replace_all(q.json(), R"("POSITION": 0)", R"("POSITION": 9)");
  EXPECT_NE(
      error("noacc.gltf", noacc).find("attributes.POSITION: accessor 9 does not exist (the file has 3 accessors)"),
      std::string::npos);
  std::string count = replace_all(q.json(), R"({"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"})",
                                  R"({"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"})");
  EXPECT_NE(error("count.gltf", count).find("TEXCOORD_0: 3 elements, but POSITION has 4"), std::string::npos);
  std::string stride = replace_all(q.json(), R"({"buffer": 0, "byteOffset": 0, "byteLength": 48})",
                                   R"({"buffer": 0, "byteOffset": 0, "byteLength": 48, "byteStride": 8})");
  std::string se = error("stride.gltf", stride);
  EXPECT_TRUE(se.find("byteStride 8 is smaller than one element (12 bytes)") != std::string::npos ||
              se.find("byteStride") != std::string::npos)
      << se;
  std::string mode = q.json(", \"mode\": 9");
  EXPECT_NE(error("mode.gltf", mode).find("meshes[0].primitives[0].mode: 9 is not a primitive mode"),
            std::string::npos);
  std::string mat = q.json(", \"material\": 3");
  EXPECT_NE(error("mat.gltf", mat).find("meshes[0].primitives[0].material: material 3 does not exist"),
            std::string::npos);
  std::string huge = replace_all(q.json(), R"({"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"})",
                                 R"({"componentType": 5126, "count": 4000000000, "type": "VEC2"})");
  EXPECT_NE(error("huge.gltf", huge)
                .find("count 4000000000 without a bufferView: unbacked-elements: 4000000000 is more than the limit"),
            std::string::npos)
      << error("huge.gltf", huge);
}

TEST_F(GltfFiles, BadSparseAccessors) {
  Bin bin;
  size_t base = bin.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  size_t sidx = bin.add(std::vector<uint16_t>{7, 0});
  size_t sval = bin.add(std::vector<float>{5, 0, 0});
  std::string j = R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
       "sparse": {"count": @SC@, "indices": {"bufferView": 1, "componentType": 5123}, "values": {"bufferView": 2}}}],
    "bufferViews": [{"buffer": 0, "byteOffset": @B@, "byteLength": 36}, {"buffer": 0, "byteOffset": @SI@, "byteLength": 4},
                    {"buffer": 0, "byteOffset": @SV@, "byteLength": 12}],
    "buffers": [{"byteLength": @N@, "uri": "@BUF@"}]})";
  j = replace_all(j, "@B@", std::to_string(base));
  j = replace_all(j, "@SI@", std::to_string(sidx));
  j = replace_all(j, "@SV@", std::to_string(sval));
  j = with_buffer(j, bin);
  EXPECT_NE(error("sparse1.gltf", replace_all(j, "@SC@", "1"))
                .find("(accessors[0]).sparse.indices[0]: 7 is past the accessor's 3 elements"),
            std::string::npos)
      << error("sparse1.gltf", replace_all(j, "@SC@", "1"));
  EXPECT_NE(error("sparse2.gltf", replace_all(j, "@SC@", "2")).find(".sparse.values: 2 values run past the end"),
            std::string::npos)
      << error("sparse2.gltf", replace_all(j, "@SC@", "2"));
  EXPECT_NE(error("sparse9.gltf", replace_all(j, "@SC@", "9")).find("sparse.count: 9 is not between 1 and"),
            std::string::npos);
}

TEST_F(GltfFiles, UnsupportedRequiredExtension) {
  Quad q;
  std::string j =
      q.json("", R"(, "extensionsUsed": ["EXT_lights_image_based"], "extensionsRequired": ["EXT_lights_image_based"])");
  EXPECT_NE(error("ibl.gltf", j)
                .find("extensionsRequired[0]: extension 'EXT_lights_image_based' is required by the file but not "
                      "supported"),
            std::string::npos)
      << error("ibl.gltf", j);
  // Required but supported: fine.
  std::string ok =
      q.json("", R"(, "extensionsUsed": ["KHR_texture_transform"], "extensionsRequired": ["KHR_texture_transform"])");
  EXPECT_EQ(error("tt.gltf", ok), "");
}

TEST_F(GltfFiles, NotAGltfAtAll) {
  EXPECT_EQ(
      error("text.gltf", "hello, world"),
      (dir_ / "text.gltf").string() + ": not a glTF file: neither a JSON object nor a binary glTF (GLB) container");
  EXPECT_NE(error("array.gltf", "[1, 2, 3]").find("not a glTF file"), std::string::npos);
  EXPECT_NE(error("broken.gltf", "{\"asset\": {\"version\": \"2.0\"").find("not a glTF file: invalid JSON"),
            std::string::npos)
      << error("broken.gltf", "{\"asset\": {\"version\": \"2.0\"");
  EXPECT_NE(error("noasset.gltf", "{\"nodes\": []}").find("not a glTF file: no \"asset\""), std::string::npos)
      << error("noasset.gltf", "{\"nodes\": []}");
  EXPECT_NE(error("v1.gltf", R"({"asset": {"version": "1.0"}})").find("asset.version is '1.0': only glTF 2.0"),
            std::string::npos);
  EXPECT_EQ(error("empty.gltf", ""), (dir_ / "empty.gltf").string() + ": not a glTF file: the file is empty");
  EXPECT_EQ(error_of((dir_ / "absent.glb").string()), (dir_ / "absent.glb").string() + ": cannot open glTF file");
  // A PNG renamed .glb.
  EXPECT_NE(error("png.glb", "\x89PNG\r\n\x1a\n....").find("not a glTF file"), std::string::npos);
  // Truncated and inconsistent GLB containers.
  Quad q;
  std::vector<uint8_t> glb =
      make_glb(replace_all(q.json(), "\"uri\": \"" + data_uri(q.bin) + "\"", "\"x\": 0"), q.bin.bytes);
  EXPECT_EQ(error_of(write_bytes("good.glb", glb)), "");
  std::vector<uint8_t> cut(glb.begin(), glb.begin() + 30);
  EXPECT_NE(error_of(write_bytes("cut.glb", cut)).find("not a valid binary glTF (GLB)"), std::string::npos)
      << error_of(write_bytes("cut.glb", cut));
  std::vector<uint8_t> lying = glb;
  lying[12] = 0xff;  // JSON chunk length 65535 + ...: beyond the file
  lying[13] = 0xff;
  EXPECT_NE(error_of(write_bytes("lying.glb", lying)).find("not a valid binary glTF (GLB)"), std::string::npos);
  // An empty scene list entry pointing nowhere.
  std::string badscene = replace_all(q.json(), R"("scene": 0,)", R"("scene": 4,)");
  EXPECT_NE(error("badscene.gltf", badscene).find("scene 4 does not exist"), std::string::npos)
      << error("badscene.gltf", badscene);
  std::string badmesh = replace_all(q.json(), R"("nodes": [{"mesh": 0 }])", R"("nodes": [{"mesh": 5 }])");
  EXPECT_NE(error("badmesh.gltf", badmesh).find("nodes[0].mesh: mesh 5 does not exist (the file has 1 meshes)"),
            std::string::npos);
  std::string badcam = replace_all(q.json(), R"("nodes": [{"mesh": 0 }])", R"("nodes": [{"mesh": 0, "camera": 2}])");
  EXPECT_NE(error("badcam.gltf", badcam).find("nodes[0].camera: camera 2 does not exist"), std::string::npos);
}

// Mutated files: each loads or throws rayform::Error, never crashes (and runs
// clean under AddressSanitizer).
TEST_F(GltfFiles, MutatedFilesLoadOrFailCleanly) {
  Quad q;
  std::string top = R"(, "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
    "textures": [{"source": 0, "sampler": 0}], "samplers": [{}], "images": [{"bufferView": 3, "mimeType": "image/png"}])";
  std::vector<uint8_t> png;
  {
    // decode the 2x2 PNG once via a data-URI load
    std::string j =
        q.json(", \"material\": 0", replace_all(top, R"({"bufferView": 3, "mimeType": "image/png"})",
                                                std::string("{\"uri\": \"data:image/png;base64,") + png_2x2 + "\"}"));
    Scene s = load("seed.gltf", j);
    ASSERT_EQ(s.textures.size(), 1u);
  }
  Bin bin = q.bin;
  // raw PNG bytes
  {
    std::string b64 = png_2x2;
    uint32_t acc = 0;
    int bits = 0;
    for (char c : b64) {
      int v = c >= 'A' && c <= 'Z'   ? c - 'A'
              : c >= 'a' && c <= 'z' ? c - 'a' + 26
              : c >= '0' && c <= '9' ? c - '0' + 52
              : c == '+'             ? 62
              : c == '/'             ? 63
                                     : -1;
      if (v < 0) continue;
      acc = (acc << 6) | uint32_t(v);
      bits += 6;
      if (bits >= 8) {
        bits -= 8;
        png.push_back(uint8_t(acc >> bits));
      }
    }
  }
  size_t png_at = bin.add(png);
  std::string j = q.json(", \"material\": 0", top);
  j = replace_all(j, "\"uri\": \"" + data_uri(q.bin) + "\"", "\"x\": 0");
  j = replace_all(j, "{\"buffer\": 0, \"byteOffset\": " + std::to_string(q.idx) + ", \"byteLength\": 12}",
                  "{\"buffer\": 0, \"byteOffset\": " + std::to_string(q.idx) +
                      ", \"byteLength\": 12}, {\"buffer\": 0, "
                      "\"byteOffset\": " +
                      std::to_string(png_at) + ", \"byteLength\": " + std::to_string(png.size()) + "}");
  j = replace_all(j, "\"byteLength\": " + std::to_string(q.bin.bytes.size()) + ",",
                  "\"byteLength\": " + std::to_string(bin.bytes.size()) + ",");
  const std::vector<uint8_t> glb = make_glb(j, bin.bytes);
  {
    Scene s = read_gltf_scene(write_bytes("base.glb", glb));
    ASSERT_EQ(s.textures.size(), 1u);  // the unmutated file is good
  }
  std::mt19937 rng(99);
  int loaded = 0, failed = 0;
  const std::string digits = "0123456789";
  for (int k = 0; k < 600; ++k) {
    std::vector<uint8_t> b = glb;
    int edits = 1 + int(rng() % 3);
    for (int e = 0; e < edits; ++e) {
      size_t at = rng() % b.size();
      if (k % 3 == 0 && at > 20 && at < 20 + j.size()) {
        // In the JSON, change digits to digits so that it stays JSON but the numbers lie.
        size_t d = j.find_first_of(digits, at - 20);
        if (d != std::string::npos) b[20 + d] = uint8_t(digits[rng() % 10]);
      } else if (k % 3 == 1) {
        b[at] = uint8_t(rng());
      } else {
        b.resize(std::max<size_t>(1, at));
      }
    }
    std::string path = write_bytes("mut.glb", b);
    try {
      Scene s = read_gltf_scene(path);
      for (const Mesh& m : s.meshes)
        for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
      for (const Texture& t : s.textures)
        ASSERT_EQ(t.pixels.size(), size_t(t.width) * size_t(t.height) * size_t(t.channels));
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
