// glTF extensions as real tools write them, each in small files built here:
// KHR_mesh_quantization, EXT_meshopt_compression (with fallback buffers
// without data), KHR_draco_mesh_compression (bad streams; good ones are in
// tests/scripts/asset_gltf_variants.sh and tests/compression),
// EXT_mesh_gpu_instancing, morph targets, skins, EXT_texture_webp,
// KHR_texture_basisu, KHR_materials_*, and the extension report.
#include "rayform/importers/gltf/gltf_reader.h"
#include "rayform/importers/gltf/gltf_writer.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/base/error.h"
#include "rayform/scene/node_walk.h"
#include "rayform/scene/scene_stats.h"
#include "test_importers.h"
#include "test_glb.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <webp/encode.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace rayform {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kFloat = 5126, kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125;

// A glTF file under construction: one binary buffer, views and accessors
// appended as they are made; written as .glb (buffer 0 in the BIN chunk).
struct GltfDraft {
  json j = json::object();
  std::vector<uint8_t> bin;

  GltfDraft() {
    j["asset"] = {{"version", "2.0"}};
    j["buffers"] = json::array({json::object()});
    j["bufferViews"] = json::array();
    j["accessors"] = json::array();
    j["scene"] = 0;
  }
  int view(const void* data, size_t bytes, size_t stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (stride) v["byteStride"] = stride;
    const uint8_t* p = static_cast<const uint8_t*>(data);
    bin.insert(bin.end(), p, p + bytes);
    j["bufferViews"].push_back(v);
    return int(j["bufferViews"].size()) - 1;
  }
  template <class T>
  int accessor(const std::vector<T>& values, int component_type, const char* type, size_t count,
               bool normalized = false) {
    json a = {{"bufferView", view(values.data(), values.size() * sizeof(T))},
              {"componentType", component_type},
              {"count", count},
              {"type", type}};
    if (normalized) a["normalized"] = true;
    j["accessors"].push_back(a);
    return int(j["accessors"].size()) - 1;
  }
  // One triangle mesh (a unit right triangle in z = 0 unless given) on node 0 of scene 0.
  void one_mesh(json attributes, json node = json::object(), int indices = -1) {
    json prim = {{"attributes", attributes}};
    if (indices >= 0) prim["indices"] = indices;
    j["meshes"] = json::array({{{"primitives", json::array({prim})}}});
    node["mesh"] = 0;
    j["nodes"] = json::array({node});
    j["scenes"] = json::array({{{"nodes", json::array({0})}}});
  }
  int triangle_positions() { return accessor(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}, kFloat, "VEC3", 3); }

  std::vector<uint8_t> glb() const {
    json out = j;
    out["buffers"][0]["byteLength"] = bin.size();
    return test::make_glb(out.dump(), bin);
  }
};

class GltfExtensions : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::temp_dir("gltf-extensions"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::vector<uint8_t>& bytes) {
    std::ofstream(dir_ / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return (dir_ / name).string();
  }
  Scene load(const GltfDraft& b, std::vector<std::string>* warnings = nullptr,
             std::vector<ExtensionUse>* extensions = nullptr) {
    return read_gltf_scene(write("t.glb", b.glb()), {}, warnings, extensions);
  }
  // The error of loading `b`, with the file name cut off; "" when it loads.
  std::string error(const GltfDraft& b) {
    try {
      load(b);
    } catch (const Error& e) {
      std::string m = e.what();
      const std::string prefix = (dir_ / "t.glb").string() + ": ";
      return m.rfind(prefix, 0) == 0 ? m.substr(prefix.size()) : "(no file name) " + m;
    }
    return "";
  }
  // World-space positions of every mesh instance, in walk order.
  static std::vector<vec3> world_positions(const Scene& s) {
    std::vector<vec3> out;
    for_each_shape_node(s, [&](const Node& n, const mat4& world) {
      if (n.shape_kind != ShapeKind::mesh) return;
      for (uint32_t i : s.meshes[size_t(n.shape)].indices)
        out.push_back(transform_point(world, s.meshes[size_t(n.shape)].positions[i]));
    });
    return out;
  }
  fs::path dir_;
};

// ---- KHR_mesh_quantization -------------------------------------------------------------------

TEST_F(GltfExtensions, QuantizedAttributesOfEveryComponentTypeAreDequantised) {
  struct Case {
    int component_type;
    bool normalized;
    float one;  // the stored integer that means 1 in the file's units
  };
  const Case cases[] = {{kByte, false, 1.f},  {kUByte, false, 1.f},  {kShort, false, 1.f},    {kUShort, false, 1.f},
                        {kByte, true, 127.f}, {kUByte, true, 255.f}, {kShort, true, 32767.f}, {kUShort, true, 65535.f}};
  for (const Case& c : cases) {
    SCOPED_TRACE("componentType " + std::to_string(c.component_type) + (c.normalized ? " normalized" : ""));
    GltfDraft b;
    const int size = c.component_type == kByte || c.component_type == kUByte ? 1 : 2;
    // Positions (0,0,0) (1,0,0) (0,1,0) in the file's units, padded to 4 bytes per vertex.
    std::vector<uint8_t> pos(3 * 4 * size_t(size), 0);
    auto put = [&](size_t vertex, size_t component, float value) {
      const int v = int(std::lround(value));
      std::memcpy(&pos[(vertex * 4 + component) * size_t(size)], &v, size_t(size));  // little-endian low bytes
    };
    put(1, 0, c.one);
    put(2, 1, c.one);
    json view = {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos.size()}, {"byteStride", 4 * size}};
    b.bin = pos;
    b.j["bufferViews"].push_back(view);
    json a = {{"bufferView", 0}, {"componentType", c.component_type}, {"count", 3}, {"type", "VEC3"}};
    if (c.normalized) a["normalized"] = true;
    b.j["accessors"].push_back(a);
    // The node scales the dequantised positions, as the extension intends.
    b.one_mesh({{"POSITION", 0}}, {{"scale", {2.0, 3.0, 1.0}}});
    b.j["extensionsUsed"] = {"KHR_mesh_quantization"};
    b.j["extensionsRequired"] = {"KHR_mesh_quantization"};
    Scene s = load(b);
    std::vector<vec3> p = world_positions(s);
    ASSERT_EQ(p.size(), 3u);
    EXPECT_EQ(p[0], vec3(0.f));
    EXPECT_NEAR(p[1].x, 2.f, 1e-6f);
    EXPECT_NEAR(p[2].y, 3.f, 1e-6f);
  }
}

TEST_F(GltfExtensions, QuantizedNormalsAndTexcoords) {
  GltfDraft b;
  const int pos = b.triangle_positions();
  // BYTE normalized normals (padded to 4 bytes): -127 is -1.
  const int nrm = b.accessor(std::vector<int8_t>{0, 0, 127, 0, 0, 0, -127, 0, 127, 0, 0, 0}, kByte, "VEC3", 3, true);
  b.j["bufferViews"][size_t(b.j["accessors"][size_t(nrm)]["bufferView"])]["byteStride"] = 4;
  // UNSIGNED_SHORT (not normalized) uvs: the texture transform would scale them; read as they are.
  const int uv = b.accessor(std::vector<uint16_t>{0, 0, 2, 0, 0, 2}, kUShort, "VEC2", 3);
  b.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}}}}});
  b.one_mesh({{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}});
  b.j["meshes"][0]["primitives"][0]["material"] = 0;
  Scene s = load(b);
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.normals[0], vec3(0, 0, 1));
  EXPECT_EQ(m.normals[1], vec3(0, 0, -1));
  EXPECT_EQ(m.normals[2], vec3(1, 0, 0));
  EXPECT_EQ(m.uvs[1], vec2(2, 1));   // v flipped: 1 - 0
  EXPECT_EQ(m.uvs[2], vec2(0, -1));  // 1 - 2
}

TEST_F(GltfExtensions, AttributeFormatsOutsideTheSpecificationAreRefused) {
  GltfDraft b;
  const int pos = b.accessor(std::vector<uint32_t>{0, 0, 0, 1, 0, 0, 0, 1, 0}, kUInt, "VEC3", 3);
  b.one_mesh({{"POSITION", pos}});
  EXPECT_NE(error(b).find("meshes[0].primitives[0].attributes.POSITION (accessors[0]): accessor is VEC3 of "
                          "UNSIGNED_INT, expected VEC3 of FLOAT, normalized UNSIGNED_BYTE"),
            std::string::npos)
      << error(b);
  GltfDraft n;
  const int p2 = n.triangle_positions();
  const int nrm = n.accessor(std::vector<uint8_t>(12, 0), kUByte, "VEC3", 3, true);  // unsigned normals: not allowed
  n.one_mesh({{"POSITION", p2}, {"NORMAL", nrm}});
  EXPECT_NE(error(n).find("attributes.NORMAL (accessors[1]): accessor is VEC3 of UNSIGNED_BYTE (normalized)"),
            std::string::npos)
      << error(n);
}

// ---- EXT_meshopt_compression -----------------------------------------------------------------

// A .glb whose positions (ATTRIBUTES) and indices (TRIANGLES) are meshopt
// compressed in buffer 0, with buffer 1 the fallback that has no data.
GltfDraft meshopt_file(std::vector<float> positions, std::vector<uint32_t> indices) {
  GltfDraft b;
  const size_t vertices = positions.size() / 3;
  std::vector<uint8_t> vbuf(meshopt_encodeVertexBufferBound(vertices, 12));
  vbuf.resize(meshopt_encodeVertexBuffer(vbuf.data(), vbuf.size(), positions.data(), vertices, 12));
  std::vector<uint8_t> ibuf(meshopt_encodeIndexBufferBound(indices.size(), vertices));
  ibuf.resize(meshopt_encodeIndexBuffer(ibuf.data(), ibuf.size(), indices.data(), indices.size()));
  b.view(vbuf.data(), vbuf.size());  // views 0 and 1: the compressed bytes
  b.view(ibuf.data(), ibuf.size());
  auto compressed_view = [&](int of, size_t count, size_t stride, const char* mode) {
    const json& raw = b.j["bufferViews"][size_t(of)];
    json v = {{"buffer", 1},
              {"byteOffset", 0},
              {"byteLength", count * stride},
              {"extensions",
               {{"EXT_meshopt_compression",
                 {{"buffer", 0},
                  {"byteOffset", raw["byteOffset"]},
                  {"byteLength", raw["byteLength"]},
                  {"byteStride", stride},
                  {"count", count},
                  {"mode", mode}}}}}};
    if (std::string(mode) == "ATTRIBUTES") v["byteStride"] = stride;
    b.j["bufferViews"].push_back(v);
    return int(b.j["bufferViews"].size()) - 1;
  };
  const int pv = compressed_view(0, vertices, 12, "ATTRIBUTES");
  const int iv = compressed_view(1, indices.size(), 4, "TRIANGLES");
  b.j["accessors"].push_back({{"bufferView", pv}, {"componentType", kFloat}, {"count", vertices}, {"type", "VEC3"}});
  b.j["accessors"].push_back(
      {{"bufferView", iv}, {"componentType", kUInt}, {"count", indices.size()}, {"type", "SCALAR"}});
  b.j["buffers"].push_back({{"byteLength", vertices * 12 + indices.size() * 4},
                            {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
  b.one_mesh({{"POSITION", 0}}, json::object(), 1);
  b.j["extensionsUsed"] = {"EXT_meshopt_compression"};
  b.j["extensionsRequired"] = {"EXT_meshopt_compression"};
  return b;
}

TEST_F(GltfExtensions, MeshoptCompressedViewsWithADatalessFallbackBuffer) {
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5f, 0.5f, 2};
  const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3, 0, 1, 4, 1, 2, 4};
  std::vector<ExtensionUse> used;
  Scene s = load(meshopt_file(positions, indices), nullptr, &used);
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 5u);
  for (size_t i = 0; i < 5; ++i)
    EXPECT_EQ(m.positions[i], vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]));
  // The index codec may rotate a triangle's corners; the triangles are the same.
  ASSERT_EQ(m.indices.size(), indices.size());
  for (size_t t = 0; t < indices.size() / 3; ++t) {
    std::array<uint32_t, 3> want{indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};
    std::array<uint32_t, 3> got{m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]};
    bool rotated = false;
    for (int r = 0; r < 3; ++r)
      rotated |= got == std::array<uint32_t, 3>{want[size_t(r)], want[size_t(r + 1) % 3], want[size_t(r + 2) % 3]};
    EXPECT_TRUE(rotated) << "triangle " << t;
  }
  ASSERT_EQ(used.size(), 1u);
  EXPECT_EQ(used[0].name, "EXT_meshopt_compression");
  EXPECT_EQ(used[0].support, ExtensionUse::Support::read);
}

TEST_F(GltfExtensions, CorruptMeshoptStreamsAreErrorsNamingTheView) {
  GltfDraft b = meshopt_file({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
  GltfDraft truncated = b;
  truncated.j["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 3;
  EXPECT_NE(error(truncated).find("bufferViews[2].extensions.EXT_meshopt_compression"), std::string::npos)
      << error(truncated);
  GltfDraft outside = b;
  outside.j["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 100000;
  EXPECT_NE(error(outside).find("bufferViews[2].extensions.EXT_meshopt_compression: bytes 100000 to"),
            std::string::npos)
      << error(outside);
  GltfDraft mode = b;
  mode.j["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["mode"] = "SHUFFLE";
  EXPECT_NE(error(mode).find("bufferViews[2].extensions.EXT_meshopt_compression.mode"), std::string::npos)
      << error(mode);
  GltfDraft longer = b;  // the view claims more bytes than the stream decodes to
  longer.j["bufferViews"][2]["byteLength"] = 1000;
  EXPECT_NE(error(longer).find("bufferViews[2].byteLength: 1000 is more than the 36 bytes"), std::string::npos)
      << error(longer);
}

// ---- KHR_draco_mesh_compression (bad streams) ---------------------------------------------------

TEST_F(GltfExtensions, CorruptDracoStreamIsAnErrorNamingThePrimitive) {
  GltfDraft b;
  const std::vector<uint8_t> garbage = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 1, 0, 0, 0, 9, 9, 9, 9};
  const int view = b.view(garbage.data(), garbage.size());
  b.j["accessors"].push_back({{"componentType", kFloat}, {"count", 3}, {"type", "VEC3"}});
  b.one_mesh({{"POSITION", 0}});
  b.j["meshes"][0]["primitives"][0]["extensions"] = {
      {"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", {{"POSITION", 0}}}}}};
  EXPECT_NE(error(b).find("meshes[0].primitives[0].extensions.KHR_draco_mesh_compression"), std::string::npos)
      << error(b);
  GltfDraft missing = b;  // an attribute the primitive has no accessor for
  missing.j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 1;
  EXPECT_NE(error(missing).find("KHR_draco_mesh_compression.attributes.NORMAL: the primitive has no accessor"),
            std::string::npos)
      << error(missing);
}

TEST_F(GltfExtensions, DracoAttributeIdOutOfRangeIsRefusedNotWrapped) {
  GltfDraft b;
  const std::vector<uint8_t> garbage = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 1, 0, 0, 0, 9, 9, 9, 9};
  const int view = b.view(garbage.data(), garbage.size());
  b.j["accessors"].push_back({{"componentType", kFloat}, {"count", 3}, {"type", "VEC3"}});
  b.one_mesh({{"POSITION", 0}});
  // 2^40: tinygltf would read it as the int 0.
  b.j["meshes"][0]["primitives"][0]["extensions"] = {
      {"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", {{"POSITION", uint64_t(1) << 40}}}}}};
  EXPECT_NE(error(b).find("meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.attributes.POSITION: "
                          "expected a Draco attribute id (an integer from 0 to 2147483647), got 1099511627776"),
            std::string::npos)
      << error(b);
  b.j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["POSITION"] = -1;
  EXPECT_NE(
      error(b).find("attributes.POSITION: expected a Draco attribute id (an integer from 0 to 2147483647), got -1"),
      std::string::npos)
      << error(b);
}

// ---- EXT_mesh_gpu_instancing ----------------------------------------------------------------------

GltfDraft instanced(size_t count) {
  GltfDraft b;
  const int pos = b.triangle_positions();
  std::vector<float> t, s;
  for (size_t i = 0; i < count; ++i) {
    t.insert(t.end(), {float(i) * 10.f, 0.f, 0.f});
    s.insert(s.end(), {1.f, 1.f + float(i), 1.f});
  }
  const int ta = b.accessor(t, kFloat, "VEC3", count);
  const int sa = b.accessor(s, kFloat, "VEC3", count);
  b.one_mesh({{"POSITION", pos}},
             {{"translation", {0.0, 0.0, 5.0}},
              {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", ta}, {"SCALE", sa}}}}}}}});
  b.j["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  return b;
}

TEST_F(GltfExtensions, GpuInstancesShareOneMeshAndOneBvh) {
  Scene s = load(instanced(3));
  EXPECT_EQ(s.meshes.size(), 1u);
  const SceneStats st = scene_stats(s);
  EXPECT_EQ(st.instances, 3u);
  std::vector<vec3> p = world_positions(s);
  ASSERT_EQ(p.size(), 9u);
  for (size_t i = 0; i < 3; ++i) {  // node T(0,0,5) after instance T(10 i, 0, 0) S(1, 1 + i, 1)
    EXPECT_EQ(p[3 * i + 0], vec3(10.f * float(i), 0.f, 5.f));
    EXPECT_EQ(p[3 * i + 1], vec3(10.f * float(i) + 1.f, 0.f, 5.f));
    EXPECT_EQ(p[3 * i + 2], vec3(10.f * float(i), 1.f + float(i), 5.f));
  }
  PreparedScene prepared = prepare_scene(s);
  EXPECT_EQ(prepared.instances.size(), 3u);
  size_t built = 0;
  for (const MeshAccel& m : prepared.meshes) built += !m.triangles.empty();
  EXPECT_EQ(built, 1u);
}

TEST_F(GltfExtensions, TenThousandInstancesCostInstanceRecordsNotMeshes) {
  Scene s = load(instanced(10000));
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(scene_stats(s).instances, 10000u);
  // One transform node per instance, over one shared shape node.
  EXPECT_EQ(s.nodes.size(), 1u + 1u + 10000u + 1u);  // root, the glTF node, instances, shape
}

TEST_F(GltfExtensions, BadInstancingAttributesAreErrors) {
  GltfDraft count = instanced(3);
  count.j["accessors"][2]["count"] = 2;  // SCALE: 2 of 3
  EXPECT_NE(error(count).find("nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.SCALE: 2 instances, but "
                              "TRANSLATION has 3"),
            std::string::npos)
      << error(count);
  GltfDraft nan = instanced(2);
  const float q = std::nanf("");
  std::memcpy(&nan.bin[size_t(nan.j["bufferViews"][1]["byteOffset"])], &q, 4);
  EXPECT_NE(error(nan).find("EXT_mesh_gpu_instancing.attributes.TRANSLATION: a value is not finite"), std::string::npos)
      << error(nan);
  GltfDraft none = instanced(2);
  none.j["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = json::object();
  EXPECT_NE(error(none).find("nodes[0].extensions.EXT_mesh_gpu_instancing: expected an object with \"attributes\""),
            std::string::npos)
      << error(none);
}

// ---- morph targets and skins --------------------------------------------------------------------

TEST_F(GltfExtensions, MorphTargetsAtTheDefaultWeights) {
  GltfDraft b;
  const int pos = b.triangle_positions();
  const int delta = b.accessor(std::vector<float>{0, 0, 2, 0, 0, 4, 0, 0, 0}, kFloat, "VEC3", 3);
  b.one_mesh({{"POSITION", pos}});
  b.j["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", delta}}});
  b.j["meshes"][0]["weights"] = {0.5};
  Scene s = load(b);
  EXPECT_EQ(s.meshes[0].positions[0], vec3(0, 0, 1));
  EXPECT_EQ(s.meshes[0].positions[1], vec3(1, 0, 2));
  b.j["nodes"][0]["weights"] = {0.25};  // the node's weights win
  s = load(b);
  EXPECT_EQ(s.meshes[0].positions[1], vec3(1, 0, 1));
}

TEST_F(GltfExtensions, SkinnedMeshesArePosedByTheirJoints) {
  GltfDraft b;
  const int pos = b.triangle_positions();
  const int joints = b.accessor(std::vector<uint8_t>{0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0}, kUByte, "VEC4", 3);
  const int weights = b.accessor(std::vector<float>{1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0}, kFloat, "VEC4", 3);
  // Inverse bind matrices: identity for joint 0, T(0, 0, -1) for joint 1 (bound at z = 1).
  const int ibm = b.accessor(std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0,  1,  //
                                                1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1},
                             kFloat, "MAT4", 2);
  b.one_mesh({{"POSITION", pos}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}},
             {{"skin", 0}, {"translation", {100.0, 0.0, 0.0}}});
  b.j["nodes"].push_back({{"translation", {0.0, 0.0, 10.0}}});                    // joint 0 (node 1)
  b.j["nodes"].push_back({{"translation", {0.0, 0.0, 1.0}}, {"children", {3}}});  // node 2, parent of joint 1
  b.j["nodes"].push_back({{"translation", {0.0, 2.0, 0.0}}});                     // joint 1 (node 3): world T(0, 2, 1)
  b.j["skins"] = json::array({{{"joints", {1, 3}}, {"inverseBindMatrices", ibm}}});
  b.j["scenes"][0]["nodes"] = {0, 1, 2};
  Scene s = load(b);
  std::vector<vec3> p = world_positions(s);
  ASSERT_EQ(p.size(), 3u);
  // The skinned node's own translation (100, 0, 0) is ignored.
  EXPECT_EQ(p[0], vec3(0, 0, 10));  // joint 0: T(0,0,10)
  EXPECT_EQ(p[1], vec3(1, 1, 5));   // half T(0,0,10), half T(0,2,1) T(0,0,-1) = T(0,2,0)
  EXPECT_EQ(p[2], vec3(0, 3, 0));   // joint 1: T(0,2,0)
  GltfDraft bad = b;
  bad.j["skins"][0]["joints"] = {1};  // joint index 1 now out of range
  EXPECT_NE(error(bad).find("attributes.JOINTS_0: vertex 1 names joint 1 but the skin has 1"), std::string::npos)
      << error(bad);
}

// ---- textures: EXT_texture_webp, KHR_texture_basisu -----------------------------------------------

// A textured triangle whose texture 0 is given by `texture` over the images `images`.
GltfDraft textured(json texture, json images) {
  GltfDraft b;
  const int pos = b.triangle_positions();
  const int uv = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 3);
  b.one_mesh({{"POSITION", pos}, {"TEXCOORD_0", uv}});
  b.j["meshes"][0]["primitives"][0]["material"] = 0;
  b.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.j["textures"] = json::array({texture});
  b.j["images"] = images;
  return b;
}

// 2x2 RGBA pixels: red, green / blue, white.
const std::vector<uint8_t> pixels_2x2 = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};

std::vector<uint8_t> webp_2x2() {
  uint8_t* out = nullptr;
  const size_t size = WebPEncodeLosslessRGBA(pixels_2x2.data(), 2, 2, 8, &out);
  std::vector<uint8_t> bytes(out, out + size);
  WebPFree(out);
  return bytes;
}

TEST_F(GltfExtensions, WebpTexturesDecodeThroughLibwebp) {
  GltfDraft b = textured({{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}, json::array());
  const std::vector<uint8_t> webp = webp_2x2();
  b.j["images"] = json::array({{{"bufferView", b.view(webp.data(), webp.size())}, {"mimeType", "image/webp"}}});
  b.j["extensionsUsed"] = {"EXT_texture_webp"};
  b.j["extensionsRequired"] = {"EXT_texture_webp"};
  Scene s = load(b);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].width, 2);
  EXPECT_EQ(s.textures[0].channels, 4);
  EXPECT_EQ(s.textures[0].pixels, pixels_2x2);
}

TEST_F(GltfExtensions, BrokenWebpFallsBackToTheCoreSourceOrIsAnError) {
  std::vector<uint8_t> webp = webp_2x2();
  webp.resize(webp.size() / 2);  // truncated
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAAE0lEQVR4nGP4z8DwHwyBNAg0AABJSQl4KKDbdwAAAABJRU5ErkJggg==";
  GltfDraft b = textured({{"source", 1}, {"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}, json::array());
  b.j["images"] = json::array({{{"bufferView", b.view(webp.data(), webp.size())}, {"mimeType", "image/webp"}},
                               {{"uri", "data:image/png;base64," + png}}});
  std::vector<std::string> warnings;
  Scene s = load(b, &warnings);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].width, 2);  // the PNG
  EXPECT_TRUE(
      test::any_contains(warnings, "images[0]: cannot decode (the WebP data is truncated (its RIFF header declares "));
  b.j["textures"][0].erase("source");
  EXPECT_NE(error(b).find("textures[0].extensions.EXT_texture_webp: images[0] does not decode as WebP and the texture "
                          "has no PNG/JPEG fallback source"),
            std::string::npos)
      << error(b);
}

// Images are decoded by the core's image_decode.h under the texel limit of
// GltfReadOptions::images: a larger one is dropped with a warning, as an
// undecodable one is.
TEST_F(GltfExtensions, ImagesOverTheTexelLimitAreDroppedWithAWarning) {
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAAE0lEQVR4nGP4z8DwHwyBNAg0AABJSQl4KKDbdwAAAABJRU5ErkJggg==";
  GltfDraft b = textured({{"source", 0}}, json::array());
  b.j["images"] = json::array({{{"uri", "data:image/png;base64," + png}}});
  GltfReadOptions options;
  options.limits.texture_texels = 4;
  Scene s = read_gltf_scene(write("t.glb", b.glb()), options);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].width, 2);
  EXPECT_EQ(s.textures[0].channels, 4);  // RGBA, as tinygltf's loader gave
  options.limits.texture_texels = 3;
  std::vector<std::string> warnings;
  s = read_gltf_scene(write("t.glb", b.glb()), options, &warnings);
  EXPECT_TRUE(s.textures.empty());
  EXPECT_TRUE(test::any_contains(warnings,
                                 "images[0]: texture is 2x2 (16 bytes decoded), more than the limit of 3 texels "
                                 "(raise it with --limit texture-texels=N); textures using it are dropped"));
}

TEST_F(GltfExtensions, BasisuUsesTheFallbackSourceOrIsAnErrorNamingTheTexture) {
  const std::vector<uint8_t> ktx2 = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n', 0, 0, 0, 0};
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAAE0lEQVR4nGP4z8DwHwyBNAg0AABJSQl4KKDbdwAAAABJRU5ErkJggg==";
  GltfDraft b = textured({{"source", 1}, {"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}}, json::array());
  b.j["images"] = json::array({{{"bufferView", b.view(ktx2.data(), ktx2.size())}, {"mimeType", "image/ktx2"}},
                               {{"uri", "data:image/png;base64," + png}}});
  b.j["extensionsUsed"] = {"KHR_texture_basisu"};
  std::vector<ExtensionUse> used;
  Scene s = read_gltf_scene(write("basisu.glb", b.glb()), {}, nullptr, &used);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].width, 2);
  ASSERT_EQ(used.size(), 1u);
  EXPECT_EQ(used[0].support, ExtensionUse::Support::approximated);
  b.j["textures"][0].erase("source");
  EXPECT_NE(error(b).find("textures[0].extensions.KHR_texture_basisu: KTX2 / Basis Universal images cannot be decoded"),
            std::string::npos)
      << error(b);
}

// ---- KHR_materials_* ------------------------------------------------------------------------------

// The extensions' values are kept as the file gives them (PbrMaterial), and
// a written .glb gives them back.
TEST_F(GltfExtensions, MaterialExtensionsAreKept) {
  GltfDraft b;
  b.one_mesh({{"POSITION", b.triangle_positions()}});
  json pbr = {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}};
  b.j["materials"] = json::array({
      {{"pbrMetallicRoughness", pbr}, {"extensions", {{"KHR_materials_unlit", json::object()}}}},
      {{"pbrMetallicRoughness", pbr}, {"extensions", {{"KHR_materials_ior", {{"ior", 3.0}}}}}},
      {{"pbrMetallicRoughness", pbr},
       {"extensions",
        {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}, {"KHR_materials_ior", {{"ior", 1.3}}}}}},
      {{"extensions",
        {{"KHR_materials_pbrSpecularGlossiness",
          {{"diffuseFactor", {0.2, 0.4, 0.6, 1.0}}, {"specularFactor", {0.1, 0.1, 0.1}}, {"glossinessFactor", 0.5}}}}}},
      {{"pbrMetallicRoughness", pbr},
       {"extensions",
        {{"KHR_materials_sheen", {{"sheenColorFactor", {0.3, 0.2, 0.1}}, {"sheenRoughnessFactor", 0.4}}}}}},
  });
  std::vector<std::string> warnings;
  std::vector<ExtensionUse> used;
  Scene s = load(b, &warnings, &used);
  ASSERT_GE(s.materials.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(s.materials[size_t(i)].model, Material::Model::metallic_roughness) << i;
  EXPECT_TRUE(s.materials[0].unlit);
  EXPECT_FALSE(s.materials[1].unlit);
  EXPECT_FLOAT_EQ(s.materials[1].pbr.ior, 3.f);
  EXPECT_FLOAT_EQ(s.materials[1].pbr.roughness, 0.5f);
  EXPECT_FLOAT_EQ(s.materials[2].pbr.ior, 1.3f);
  EXPECT_FLOAT_EQ(s.materials[2].pbr.transmission, 1.f);
  EXPECT_EQ(s.materials[3].pbr.base_color, vec4(0.2f, 0.4f, 0.6f, 1.f));
  EXPECT_FLOAT_EQ(s.materials[3].pbr.roughness, 0.5f);  // 1 - glossiness
  EXPECT_EQ(s.materials[4].pbr.sheen_color, vec3(0.3f, 0.2f, 0.1f));
  EXPECT_FLOAT_EQ(s.materials[4].pbr.sheen_roughness, 0.4f);
  auto support = [&](const std::vector<ExtensionUse>& uses, const std::string& name) {
    for (const ExtensionUse& u : uses)
      if (u.name == name) return int(u.support);
    return -1;
  };
  EXPECT_EQ(support(used, "KHR_materials_unlit"), int(ExtensionUse::Support::read));
  EXPECT_EQ(support(used, "KHR_materials_transmission"), int(ExtensionUse::Support::read));
  EXPECT_EQ(support(used, "KHR_materials_sheen"), int(ExtensionUse::Support::read));
  EXPECT_EQ(support(used, "KHR_materials_pbrSpecularGlossiness"), int(ExtensionUse::Support::approximated));
  // Written back as glTF, the materials read the same.
  const std::string written = (dir_ / "written.glb").string();
  std::vector<std::string> messages;
  GltfWriteOptions glb;
  glb.binary = true;
  write_gltf_scene(s, written, glb, &messages);
  std::vector<ExtensionUse> used_again;
  Scene again = read_gltf_scene(written, {}, nullptr, &used_again);
  ASSERT_GE(again.materials.size(), 5u);
  EXPECT_TRUE(again.materials[0].unlit);
  EXPECT_FALSE(again.materials[1].unlit);
  EXPECT_FLOAT_EQ(again.materials[1].pbr.ior, 3.f);
  EXPECT_FLOAT_EQ(again.materials[2].pbr.transmission, 1.f);
  EXPECT_FLOAT_EQ(again.materials[2].pbr.ior, 1.3f);
  EXPECT_EQ(again.materials[3].pbr.base_color, s.materials[3].pbr.base_color);
  EXPECT_EQ(again.materials[4].pbr.sheen_color, s.materials[4].pbr.sheen_color);
  EXPECT_EQ(support(used_again, "KHR_materials_sheen"), int(ExtensionUse::Support::read));
  GltfDraft bad = b;
  bad.j["materials"][1]["extensions"]["KHR_materials_ior"]["ior"] = 0.5;
  EXPECT_NE(error(bad).find("materials[1].extensions.KHR_materials_ior.ior: 0.500000 is neither 0 nor a number >= 1"),
            std::string::npos)
      << error(bad);
}

}  // namespace
}  // namespace rayform
