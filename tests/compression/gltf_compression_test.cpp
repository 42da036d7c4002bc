// Compressed glTF geometry (gltf/gltf_compression.h): streams encoded here with
// meshoptimizer's and Draco's own encoders are decoded and compared with what
// was encoded (exactly, or within the quantisation the encoder was asked for);
// bad layouts, truncated, mutated and foreign streams must be an Error whose
// message starts with the caller's `where`, never a crash (these tests also run
// under ASan+UBSan, so they stay small).
#include "rayform/importers/gltf/gltf_compression.h"
#include "rayform/base/error.h"

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <draco/point_cloud/point_cloud_builder.h>
#include <meshoptimizer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace rayform {
namespace {

const std::string kWhere = "model.glb: bufferViews[3].extensions.EXT_meshopt_compression";
const std::string kDracoWhere = "model.glb: meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";

constexpr int kMutations = 500;  // flipped-byte trials per stream
constexpr float kSnorm8Max = 127.f;
constexpr float kSnorm16Max = 32767.f;

// Ok when `f` throws rayform::Error whose message starts with `where` and holds
// every one of `parts`.
testing::AssertionResult fails_with(const std::function<void()>& f, const std::string& where,
                                    const std::vector<std::string>& parts = {}) {
  try {
    f();
  } catch (const Error& e) {
    const std::string m = e.what();
    if (m.rfind(where + ": ", 0) != 0) return testing::AssertionFailure() << "message does not start with where: " << m;
    for (const std::string& p : parts)
      if (m.find(p) == std::string::npos) return testing::AssertionFailure() << "no '" << p << "' in: " << m;
    return testing::AssertionSuccess() << m;
  }
  return testing::AssertionFailure() << "no Error thrown";
}

// ---- meshopt ----------------------------------------------------------------

std::vector<uint8_t> encode_vertices(const std::vector<uint8_t>& data, size_t count, size_t stride) {
  std::vector<uint8_t> out(meshopt_encodeVertexBufferBound(count, stride));
  out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data.data(), count, stride));
  EXPECT_GT(out.size(), 0u);
  return out;
}

std::vector<uint8_t> encode_triangles(const std::vector<uint32_t>& indices, size_t vertex_count) {
  std::vector<uint8_t> out(meshopt_encodeIndexBufferBound(indices.size(), vertex_count));
  out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), indices.data(), indices.size()));
  EXPECT_GT(out.size(), 0u);
  return out;
}

std::vector<uint8_t> encode_sequence(const std::vector<uint32_t>& indices, size_t vertex_count) {
  std::vector<uint8_t> out(meshopt_encodeIndexSequenceBound(indices.size(), vertex_count));
  out.resize(meshopt_encodeIndexSequence(out.data(), out.size(), indices.data(), indices.size()));
  EXPECT_GT(out.size(), 0u);
  return out;
}

std::vector<uint8_t> decode(const std::vector<uint8_t>& s, size_t count, size_t stride, MeshoptMode mode,
                            MeshoptFilter filter = MeshoptFilter::none) {
  return decode_meshopt(s.data(), s.size(), count, stride, mode, filter, kWhere);
}

template <class T>
std::vector<T> as(const std::vector<uint8_t>& bytes) {
  std::vector<T> v(bytes.size() / sizeof(T));
  if (!v.empty()) std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}

template <class T>
std::vector<uint8_t> bytes_of(const std::vector<T>& v) {
  std::vector<uint8_t> b(v.size() * sizeof(T));
  if (!b.empty()) std::memcpy(b.data(), v.data(), b.size());
  return b;
}

// Vertex-like bytes: slowly varying bytes (small deltas), some constant ones
// (zero deltas) and some random ones (full-byte deltas), so that every delta
// encoding of the attribute codec occurs.
std::vector<uint8_t> vertex_bytes(size_t count, size_t stride, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> v(count * stride);
  for (size_t i = 0; i < count; ++i)
    for (size_t b = 0; b < stride; ++b) {
      uint8_t& x = v[i * stride + b];
      switch (b % 3) {
        case 0: x = uint8_t(i * 3 + b + rng() % 4); break;
        case 1: x = uint8_t(b); break;
        default: x = uint8_t(rng()); break;
      }
    }
  return v;
}

// Triangle list of an nx x ny grid of quads; (nx + 1) * (ny + 1) vertices.
std::vector<uint32_t> grid_triangles(uint32_t nx, uint32_t ny) {
  std::vector<uint32_t> t;
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i) {
      const uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      t.insert(t.end(), {a, b, c, a, c, d});
    }
  return t;
}

TEST(GltfCompressionMeshopt, ParsesModesAndFilters) {
  const std::string w = "bufferViews[0].extensions.EXT_meshopt_compression.mode";
  EXPECT_EQ(parse_meshopt_mode("ATTRIBUTES", w), MeshoptMode::attributes);
  EXPECT_EQ(parse_meshopt_mode("TRIANGLES", w), MeshoptMode::triangles);
  EXPECT_EQ(parse_meshopt_mode("INDICES", w), MeshoptMode::indices);
  EXPECT_EQ(parse_meshopt_filter("NONE", w), MeshoptFilter::none);
  EXPECT_EQ(parse_meshopt_filter("OCTAHEDRAL", w), MeshoptFilter::octahedral);
  EXPECT_EQ(parse_meshopt_filter("QUATERNION", w), MeshoptFilter::quaternion);
  EXPECT_EQ(parse_meshopt_filter("EXPONENTIAL", w), MeshoptFilter::exponential);
  // The extension's enumerations are exact, upper-case strings.
  for (const char* bad : {"attributes", "", "TRIANGLE_STRIP", "INDICES ", "NONE"})
    EXPECT_TRUE(fails_with([&] { parse_meshopt_mode(bad, w); }, w, {"'" + std::string(bad) + "'", "ATTRIBUTES"}));
  for (const char* bad : {"none", "", "OCT", "ATTRIBUTES"})
    EXPECT_TRUE(fails_with([&] { parse_meshopt_filter(bad, w); }, w, {"'" + std::string(bad) + "'", "EXPONENTIAL"}));
}

TEST(GltfCompressionMeshopt, AttributesRoundTripExactly) {
  for (size_t stride : {4, 8, 12, 16, 32, 64, 256})
    for (size_t count : {0, 1, 15, 16, 17, 100, 257, 1000}) {
      SCOPED_TRACE("stride " + std::to_string(stride) + ", count " + std::to_string(count));
      const std::vector<uint8_t> data = vertex_bytes(count, stride, uint32_t(stride * 1000 + count));
      EXPECT_EQ(decode(encode_vertices(data, count, stride), count, stride, MeshoptMode::attributes), data);
    }
}

// Each triangle rotated to start at its smallest index: meshoptimizer's index
// codec may rotate a triangle's corners (keeping its winding and the order of
// triangles), so decoded lists are compared in this form.
template <class T>
std::vector<T> rotated_to_smallest(std::vector<T> t) {
  for (size_t i = 0; i + 2 < t.size(); i += 3)
    while (t[i] > t[i + 1] || t[i] > t[i + 2])
      std::rotate(t.begin() + long(i), t.begin() + long(i) + 1, t.begin() + long(i) + 3);
  return t;
}

TEST(GltfCompressionMeshopt, TrianglesRoundTrip) {
  std::mt19937 rng(11);
  std::vector<uint32_t> random_tris(300);  // no locality at all: every index coded explicitly
  for (uint32_t& i : random_tris) i = rng() % 70000;
  const std::vector<uint32_t> grid = grid_triangles(7, 5);
  for (int version : {0, 1}) {  // both index codec versions meshoptimizer writes
    SCOPED_TRACE("index codec version " + std::to_string(version));
    meshopt_encodeIndexVersion(version);
    const std::vector<uint8_t> g = encode_triangles(grid, 48);
    EXPECT_EQ(rotated_to_smallest(as<uint32_t>(decode(g, grid.size(), 4, MeshoptMode::triangles))),
              rotated_to_smallest(grid));
    const std::vector<uint16_t> grid16(grid.begin(), grid.end());
    EXPECT_EQ(rotated_to_smallest(as<uint16_t>(decode(g, grid.size(), 2, MeshoptMode::triangles))),
              rotated_to_smallest(grid16));
    const std::vector<uint8_t> r = encode_triangles(random_tris, 70000);
    EXPECT_EQ(rotated_to_smallest(as<uint32_t>(decode(r, random_tris.size(), 4, MeshoptMode::triangles))),
              rotated_to_smallest(random_tris));
    EXPECT_EQ(decode(encode_triangles({}, 0), 0, 4, MeshoptMode::triangles).size(), 0u);
  }
  meshopt_encodeIndexVersion(1);  // the library's default
}

TEST(GltfCompressionMeshopt, IndicesRoundTripExactly) {
  // A triangle strip (two interleaved runs), a line list with large jumps both
  // ways, and lengths that are not multiples of 3.
  std::vector<uint32_t> strip, lines = {0, 1, 1u << 24, 5, 70000, 3, 16777215, 0};
  for (uint32_t i = 0; i < 50; ++i) strip.insert(strip.end(), {i, i + 100});
  for (const auto& seq : {strip, lines, std::vector<uint32_t>{42}, std::vector<uint32_t>{7, 3}}) {
    EXPECT_EQ(as<uint32_t>(decode(encode_sequence(seq, 1u << 25), seq.size(), 4, MeshoptMode::indices)), seq);
  }
  const std::vector<uint16_t> strip16(strip.begin(), strip.end());
  EXPECT_EQ(as<uint16_t>(decode(encode_sequence(strip, 200), strip.size(), 2, MeshoptMode::indices)), strip16);
}

// Unit vectors: the axes, the octahedron's edges and a spiral over the sphere
// (both hemispheres, so the negative-z fold is exercised); w = +-1 (tangents).
std::vector<float> unit_vectors_xyzw() {
  std::vector<float> v = {1, 0, 0, 1, -1, 0, 0, -1, 0, 1, 0, 1, 0, -1, 0, -1, 0, 0, 1, 1, 0, 0, -1, -1};
  const float s = std::sqrt(0.5f);
  for (float a : {s, -s}) v.insert(v.end(), {a, 0, a, 1, 0, a, -a, -1});
  constexpr int kSpiral = 60;
  for (int i = 0; i < kSpiral; ++i) {
    const float z = 1.f - 2.f * (float(i) + 0.5f) / kSpiral, r = std::sqrt(1.f - z * z);
    const float phi = 2.39996323f * float(i);  // golden angle, radians
    v.insert(v.end(), {r * std::cos(phi), r * std::sin(phi), z, i % 2 ? 1.f : -1.f});
  }
  return v;
}

TEST(GltfCompressionMeshopt, OctahedralFilterDecodesUnitVectors) {
  const std::vector<float> v = unit_vectors_xyzw();
  const size_t count = v.size() / 4;
  struct Case {
    size_t stride;
    int bits;
    float tolerance;  // per component, of the decoded unit vector
  };
  for (Case c : {Case{4, 8, 0.03f}, Case{8, 10, 0.006f}, Case{8, 16, 2e-4f}}) {
    SCOPED_TRACE("stride " + std::to_string(c.stride) + ", bits " + std::to_string(c.bits));
    std::vector<uint8_t> filtered(count * c.stride);
    meshopt_encodeFilterOct(filtered.data(), count, c.stride, c.bits, v.data());
    const std::vector<uint8_t> d = decode(encode_vertices(filtered, count, c.stride), count, c.stride,
                                          MeshoptMode::attributes, MeshoptFilter::octahedral);
    ASSERT_EQ(d.size(), filtered.size());
    const float max = c.stride == 4 ? kSnorm8Max : kSnorm16Max;
    for (size_t i = 0; i < count; ++i) {
      float n[4];
      for (int k = 0; k < 4; ++k)
        n[k] = c.stride == 4 ? float(as<int8_t>(d)[i * 4 + k]) / max : float(as<int16_t>(d)[i * 4 + k]) / max;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[k], v[i * 4 + k], c.tolerance) << "vector " << i << " component " << k;
      EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.f, c.tolerance) << "vector " << i;
      EXPECT_EQ(n[3], v[i * 4 + 3]) << "w is passed through, vector " << i;
    }
  }
}

TEST(GltfCompressionMeshopt, QuaternionFilterDecodesRotations) {
  std::vector<float> q = {0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1};
  std::mt19937 rng(5);
  std::normal_distribution<float> g;
  for (int i = 0; i < 40; ++i) {
    float c[4] = {g(rng), g(rng), g(rng), g(rng)};
    const float len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]);
    for (float x : c) q.push_back(x / len);
  }
  const size_t count = q.size() / 4;
  for (auto [bits, tolerance] : {std::pair{8, 0.01f}, std::pair{12, 8e-4f}, std::pair{16, 1e-4f}}) {
    SCOPED_TRACE("bits " + std::to_string(bits));
    std::vector<uint8_t> filtered(count * 8);
    meshopt_encodeFilterQuat(filtered.data(), count, 8, bits, q.data());
    const std::vector<int16_t> d = as<int16_t>(
        decode(encode_vertices(filtered, count, 8), count, 8, MeshoptMode::attributes, MeshoptFilter::quaternion));
    ASSERT_EQ(d.size(), q.size());
    for (size_t i = 0; i < count; ++i) {
      // q and -q are the same rotation; the encoding keeps its largest component positive.
      float dot = 0;
      for (int k = 0; k < 4; ++k) dot += float(d[i * 4 + k]) / kSnorm16Max * q[i * 4 + k];
      const float sign = dot < 0 ? -1.f : 1.f;
      for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(sign * float(d[i * 4 + k]) / kSnorm16Max, q[i * 4 + k], tolerance) << "quaternion " << i;
    }
  }
}

TEST(GltfCompressionMeshopt, ExponentialFilterDecodesFloats) {
  const std::vector<float> v = {0.f, 1.f, -1.f, 0.001f, 12345.678f, -0.5f, 3.14159265f, 1e-6f, -2e5f,
                                0.f, 0.f, 0.f,  7.25f,  -7.25f,     1e4f,  0.0625f,     -3.f,  100.f};
  struct Case {
    size_t stride;  // one exponent per stride / 4 floats
    int bits;       // mantissa bits, sign included
  };
  for (Case c : {Case{4, 23}, Case{4, 12}, Case{12, 15}, Case{24, 20}}) {
    SCOPED_TRACE("stride " + std::to_string(c.stride) + ", bits " + std::to_string(c.bits));
    const size_t per = c.stride / 4, count = v.size() / per;
    std::vector<uint8_t> filtered(count * c.stride);
    meshopt_encodeFilterExp(filtered.data(), count, c.stride, c.bits, v.data());
    const std::vector<float> d = as<float>(decode(encode_vertices(filtered, count, c.stride), count, c.stride,
                                                  MeshoptMode::attributes, MeshoptFilter::exponential));
    ASSERT_EQ(d.size(), v.size());
    for (size_t i = 0; i < count; ++i) {
      // A shared exponent: the error is relative to the vector's largest
      // component, half a step of its (bits - 1)-bit magnitude; twice that here.
      float largest = 0;
      for (size_t k = 0; k < per; ++k) largest = std::max(largest, std::abs(v[i * per + k]));
      const float tolerance = largest * std::ldexp(1.f, 2 - c.bits);
      for (size_t k = 0; k < per; ++k)
        EXPECT_NEAR(d[i * per + k], v[i * per + k], tolerance) << "element " << i << " component " << k;
    }
  }
}

TEST(GltfCompressionMeshopt, RejectsLayoutsTheExtensionForbids) {
  const std::vector<uint8_t> s = encode_vertices(vertex_bytes(30, 12, 1), 30, 12);
  using M = MeshoptMode;
  using F = MeshoptFilter;
  struct Case {
    size_t count, stride;
    MeshoptMode mode;
    MeshoptFilter filter;
    const char* says;
  };
  const Case cases[] = {
      {30, 0, M::attributes, F::none, "multiple of 4, from 4 to 256, found 0"},
      {30, 6, M::attributes, F::none, "found 6"},
      {30, 260, M::attributes, F::none, "found 260"},
      {30, 512, M::attributes, F::none, "found 512"},
      {30, 1, M::triangles, F::none, "TRIANGLES needs byteStride 2 or 4, found 1"},
      {30, 3, M::triangles, F::none, "found 3"},
      {30, 8, M::triangles, F::none, "found 8"},
      {30, 0, M::indices, F::none, "INDICES needs byteStride 2 or 4, found 0"},
      {10, 4, M::triangles, F::none, "multiple of 3, found 10"},
      {30, 4, M::triangles, F::octahedral, "OCTAHEDRAL is only allowed with mode ATTRIBUTES"},
      {30, 4, M::indices, F::exponential, "EXPONENTIAL is only allowed with mode ATTRIBUTES"},
      {30, 12, M::attributes, F::octahedral, "OCTAHEDRAL needs byteStride 4 or 8, found 12"},
      {30, 16, M::attributes, F::octahedral, "found 16"},
      {30, 4, M::attributes, F::quaternion, "QUATERNION needs byteStride 8, found 4"},
      {30, 12, M::attributes, F::quaternion, "found 12"},
  };
  for (const Case& c : cases)
    EXPECT_TRUE(fails_with([&] { decode(s, c.count, c.stride, c.mode, c.filter); }, kWhere, {c.says})) << c.says;
}

TEST(GltfCompressionMeshopt, RefusesAbsurdSizesBeforeAllocating) {
  const std::vector<uint8_t> s = encode_vertices(vertex_bytes(30, 4, 2), 30, 4);
  EXPECT_TRUE(fails_with([&] { decode(s, SIZE_MAX, 4, MeshoptMode::attributes); }, kWhere, {"MiB"}));
  EXPECT_TRUE(fails_with([&] { decode(s, SIZE_MAX / 2, 256, MeshoptMode::attributes); }, kWhere, {"MiB"}));
  EXPECT_TRUE(
      fails_with([&] { decode(s, max_decoded_geometry_bytes / 4 + 1, 4, MeshoptMode::attributes); }, kWhere, {"MiB"}));
  EXPECT_TRUE(fails_with([&] { decode(s, (max_decoded_geometry_bytes / 12) * 3 + 3, 4, MeshoptMode::triangles); },
                         kWhere, {"MiB"}));
  // Within the limit but far more than the stream's bytes can describe: the
  // bitstream's minimum size refuses it (no 1 GiB buffer is made).
  EXPECT_TRUE(fails_with([&] { decode(s, max_decoded_geometry_bytes / 4, 4, MeshoptMode::attributes); }, kWhere,
                         {"truncated", "at least"}));
  EXPECT_TRUE(fails_with([&] { decode(s, 3000000, 4, MeshoptMode::triangles); }, kWhere, {"truncated"}));
  EXPECT_TRUE(fails_with([&] { decode(s, 3000000, 2, MeshoptMode::indices); }, kWhere, {"truncated"}));
  EXPECT_TRUE(
      fails_with([&] { decode_meshopt(nullptr, 0, 1, 4, MeshoptMode::attributes, MeshoptFilter::none, kWhere); },
                 kWhere, {"truncated"}));
}

// Streams of every mode, with their layouts, for the corruption tests.
struct Stream {
  std::vector<uint8_t> bytes;
  size_t count, stride;
  MeshoptMode mode;
  MeshoptFilter filter;
};

std::vector<Stream> sample_streams() {
  std::vector<Stream> s;
  s.push_back({encode_vertices(vertex_bytes(40, 12, 3), 40, 12), 40, 12, MeshoptMode::attributes, MeshoptFilter::none});
  const std::vector<float> n = unit_vectors_xyzw();
  std::vector<uint8_t> oct(n.size() / 4 * 8);
  meshopt_encodeFilterOct(oct.data(), n.size() / 4, 8, 12, n.data());
  s.push_back(
      {encode_vertices(oct, n.size() / 4, 8), n.size() / 4, 8, MeshoptMode::attributes, MeshoptFilter::octahedral});
  const std::vector<uint32_t> tris = grid_triangles(6, 4);
  s.push_back({encode_triangles(tris, 35), tris.size(), 4, MeshoptMode::triangles, MeshoptFilter::none});
  const std::vector<uint32_t> seq = {3, 9, 1000, 2, 7, 7, 65535, 0, 12, 13};
  s.push_back({encode_sequence(seq, 65536), seq.size(), 2, MeshoptMode::indices, MeshoptFilter::none});
  return s;
}

TEST(GltfCompressionMeshopt, EveryTruncationIsAnError) {
  for (const Stream& s : sample_streams()) {
    SCOPED_TRACE(std::string("mode ") + std::to_string(int(s.mode)) + ", " + std::to_string(s.bytes.size()) + " bytes");
    ASSERT_NO_THROW(decode(s.bytes, s.count, s.stride, s.mode, s.filter));
    for (size_t n = 0; n < s.bytes.size(); ++n) {
      const std::vector<uint8_t> prefix(s.bytes.begin(), s.bytes.begin() + long(n));  // exactly n bytes, for ASan
      EXPECT_TRUE(fails_with([&] { decode(prefix, s.count, s.stride, s.mode, s.filter); }, kWhere)) << n << " bytes";
    }
  }
}

TEST(GltfCompressionMeshopt, WrongCountsStridesAndModesAreErrors) {
  const std::vector<Stream> all = sample_streams();
  const Stream& a = all[0];  // ATTRIBUTES, 40 x 12 bytes
  const Stream& t = all[2];  // TRIANGLES
  const Stream& i = all[3];  // INDICES
  const std::vector<std::string> corrupt = {"corrupt or truncated (meshopt error"};
  EXPECT_TRUE(fails_with([&] { decode(a.bytes, 20, 12, MeshoptMode::attributes); }, kWhere, corrupt));
  EXPECT_TRUE(fails_with([&] { decode(a.bytes, 100, 12, MeshoptMode::attributes); }, kWhere));
  EXPECT_TRUE(fails_with([&] { decode(a.bytes, 40, 16, MeshoptMode::attributes); }, kWhere));
  EXPECT_TRUE(fails_with([&] { decode(a.bytes, 40, 8, MeshoptMode::attributes); }, kWhere));
  EXPECT_TRUE(fails_with([&] { decode(t.bytes, t.count + 3, 4, MeshoptMode::triangles); }, kWhere));
  EXPECT_TRUE(fails_with([&] { decode(t.bytes, t.count - 3, 4, MeshoptMode::triangles); }, kWhere, corrupt));
  EXPECT_TRUE(fails_with([&] { decode(i.bytes, i.count + 1, 2, MeshoptMode::indices); }, kWhere));
  EXPECT_TRUE(fails_with([&] { decode(i.bytes, i.count - 1, 2, MeshoptMode::indices); }, kWhere, corrupt));
  // Each mode's header byte differs: a stream of one mode is not one of another.
  EXPECT_TRUE(fails_with([&] { decode(t.bytes, 12, 4, MeshoptMode::attributes); }, kWhere, corrupt));
  EXPECT_TRUE(fails_with([&] { decode(a.bytes, 30, 4, MeshoptMode::triangles); }, kWhere, corrupt));
  EXPECT_TRUE(fails_with([&] { decode(t.bytes, t.count, 4, MeshoptMode::indices); }, kWhere));
  // A byte too many is as wrong as one too few.
  for (const Stream& s : all) {
    std::vector<uint8_t> longer = s.bytes;
    longer.push_back(0);
    EXPECT_TRUE(fails_with([&] { decode(longer, s.count, s.stride, s.mode, s.filter); }, kWhere));
  }
}

TEST(GltfCompressionMeshopt, FlippedBytesDecodeOrFailNeverCrash) {
  std::mt19937 rng(2024);
  int errors = 0, decoded = 0;
  for (const Stream& s : sample_streams()) {
    std::vector<uint8_t> header_changed = s.bytes;  // an unknown header (or version) is always refused
    header_changed[0] ^= 0x40;
    EXPECT_TRUE(fails_with([&] { decode(header_changed, s.count, s.stride, s.mode, s.filter); }, kWhere));
    for (int m = 0; m < kMutations; ++m) {
      std::vector<uint8_t> b = s.bytes;
      const int flips = 1 + int(rng() % 4);
      for (int f = 0; f < flips; ++f) b[rng() % b.size()] ^= uint8_t(1 + rng() % 255);
      try {
        EXPECT_EQ(decode(b, s.count, s.stride, s.mode, s.filter).size(), s.count * s.stride);
        ++decoded;
      } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(kWhere + ": ", 0), 0u) << e.what();
        ++errors;
      }
    }
  }
  // Both outcomes occur: the attribute codec has no checksum, the others fail on most changes.
  EXPECT_GT(errors, 0);
  EXPECT_GT(decoded, 0);
}

// ---- Draco ------------------------------------------------------------------

// A corner of a face: position, uv, normal.
struct Corner {
  std::array<float, 3> p;
  std::array<float, 2> uv;
  std::array<float, 3> n;
};
using Face = std::array<Corner, 3>;

constexpr int kGrid = 4;             // quads per side: (kGrid + 1)^2 distinct vertices
constexpr uint32_t kPositionId = 4;  // Draco unique ids, deliberately not the attribute indices 0, 1, 2
constexpr uint32_t kUvId = 7;
constexpr uint32_t kNormalId = 1;
constexpr uint32_t kColorId = 9;
constexpr int kPositionBits = 14;  // quantisation, when asked for
constexpr int kUvBits = 12;
constexpr int kNormalBits = 10;

// A saddle z = x y / 4 over [-1, 1]^2 as triangles (counter-clockwise seen
// from +z), with uvs in [0, 1]^2 and exact unit normals.
std::vector<Face> saddle_faces() {
  auto corner = [](int i, int j) {
    const float x = 2.f * float(i) / kGrid - 1.f, y = 2.f * float(j) / kGrid - 1.f;
    const float nx = -0.25f * y, ny = -0.25f * x, len = std::sqrt(nx * nx + ny * ny + 1.f);
    return Corner{{x, y, 0.25f * x * y}, {float(i) / kGrid, float(j) / kGrid}, {nx / len, ny / len, 1.f / len}};
  };
  std::vector<Face> f;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      f.push_back({corner(i, j), corner(i + 1, j), corner(i + 1, j + 1)});
      f.push_back({corner(i, j), corner(i + 1, j + 1), corner(i, j + 1)});
    }
  return f;
}

// Per-vertex colour of the saddle's corner, as stored (normalised UNSIGNED_BYTE).
std::array<uint8_t, 4> saddle_color(const Corner& c) {
  return {uint8_t(std::lround(c.uv[0] * 255.f)), uint8_t(std::lround(c.uv[1] * 255.f)), 7, 255};
}

std::unique_ptr<draco::Mesh> saddle_mesh(bool with_color) {
  const std::vector<Face> faces = saddle_faces();
  draco::TriangleSoupMeshBuilder b;
  b.Start(int(faces.size()));
  const int pos = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int uv = b.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  const int nrm = b.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int col = with_color ? b.AddAttribute(draco::GeometryAttribute::COLOR, 4, draco::DT_UINT8, true) : -1;
  for (size_t f = 0; f < faces.size(); ++f) {
    const Face& c = faces[f];
    const draco::FaceIndex fi{uint32_t(f)};
    b.SetAttributeValuesForFace(pos, fi, c[0].p.data(), c[1].p.data(), c[2].p.data());
    b.SetAttributeValuesForFace(uv, fi, c[0].uv.data(), c[1].uv.data(), c[2].uv.data());
    b.SetAttributeValuesForFace(nrm, fi, c[0].n.data(), c[1].n.data(), c[2].n.data());
    if (with_color) {
      const auto c0 = saddle_color(c[0]), c1 = saddle_color(c[1]), c2 = saddle_color(c[2]);
      b.SetAttributeValuesForFace(col, fi, c0.data(), c1.data(), c2.data());
    }
  }
  std::unique_ptr<draco::Mesh> mesh = b.Finalize();
  mesh->attribute(pos)->set_unique_id(kPositionId);
  mesh->attribute(uv)->set_unique_id(kUvId);
  mesh->attribute(nrm)->set_unique_id(kNormalId);
  if (with_color) mesh->attribute(col)->set_unique_id(kColorId);
  return mesh;
}

std::vector<uint8_t> encode_draco(const draco::Mesh& mesh, int method, bool quantise) {
  draco::Encoder enc;
  enc.SetEncodingMethod(method);
  if (quantise) {
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, kPositionBits);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, kUvBits);
    enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, kNormalBits);
  }
  draco::EncoderBuffer buf;
  const draco::Status st = enc.EncodeMeshToBuffer(mesh, &buf);
  EXPECT_TRUE(st.ok()) << st.error_msg_string();
  return std::vector<uint8_t>(reinterpret_cast<const uint8_t*>(buf.data()),
                              reinterpret_cast<const uint8_t*>(buf.data()) + buf.size());
}

DracoMesh decode_draco(const std::vector<uint8_t>& s, const std::vector<int>& ids) {
  return rayform::decode_draco(s.data(), s.size(), ids, kDracoWhere);
}

template <size_t N>
bool near(const std::array<float, N>& a, const float* b, float tolerance) {
  for (size_t k = 0; k < N; ++k)
    if (!(std::abs(a[k] - b[k]) <= tolerance)) return false;
  return true;
}

// Decodes position, uv and normal and checks that the decoded triangles are the
// encoded ones: each matched once, up to a rotation of its corners (Draco may
// reorder faces and vertices, never the winding), within the tolerances.
void expect_saddle(const std::vector<uint8_t>& stream, float tol_p, float tol_uv, float tol_n) {
  const DracoMesh m = decode_draco(stream, {int(kPositionId), int(kUvId), int(kNormalId)});
  const std::vector<Face> faces = saddle_faces();
  EXPECT_EQ(m.vertex_count, size_t((kGrid + 1) * (kGrid + 1)));  // shared corners stay shared
  ASSERT_EQ(m.indices.size(), 3 * faces.size());
  ASSERT_EQ(m.attributes.size(), 3u);
  const int components[3] = {3, 2, 3};
  const uint32_t ids[3] = {kPositionId, kUvId, kNormalId};
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(m.attributes[a].unique_id, int(ids[a]));
    ASSERT_EQ(m.attributes[a].components, components[a]);
    ASSERT_EQ(m.attributes[a].values.size(), m.vertex_count * size_t(components[a]));
  }
  for (uint32_t i : m.indices) ASSERT_LT(i, m.vertex_count);
  std::vector<bool> used(faces.size(), false);
  for (size_t f = 0; f < faces.size(); ++f) {
    bool found = false;
    for (size_t d = 0; d < faces.size() && !found; ++d) {
      if (used[d]) continue;
      for (int r = 0; r < 3 && !found; ++r) {
        bool all = true;
        for (int k = 0; k < 3 && all; ++k) {
          const uint32_t v = m.indices[3 * d + (k + r) % 3];
          const Corner& c = faces[f][k];
          all = near(c.p, &m.attributes[0].values[3 * v], tol_p) &&
                near(c.uv, &m.attributes[1].values[2 * v], tol_uv) && near(c.n, &m.attributes[2].values[3 * v], tol_n);
        }
        if (all) found = used[d] = true;
      }
    }
    EXPECT_TRUE(found) << "encoded triangle " << f << " is not among the decoded ones";
  }
}

// Quantisation error bounds: half a step over the attribute's range, plus a
// margin; Draco's octahedral normals lose a little more.
constexpr float kPositionRange = 2.f;  // [-1, 1]
constexpr float kTolPosition = kPositionRange / ((1 << kPositionBits) - 1);
constexpr float kTolUv = 1.f / ((1 << kUvBits) - 1);
constexpr float kTolNormal = 4.f / ((1 << kNormalBits) - 1);

TEST(GltfCompressionDraco, SequentialLosslessRoundTrip) {
  expect_saddle(encode_draco(*saddle_mesh(false), draco::MESH_SEQUENTIAL_ENCODING, false), 0.f, 0.f, 0.f);
}

TEST(GltfCompressionDraco, EdgebreakerLosslessRoundTrip) {
  expect_saddle(encode_draco(*saddle_mesh(false), draco::MESH_EDGEBREAKER_ENCODING, false), 0.f, 0.f, 0.f);
}

TEST(GltfCompressionDraco, SequentialQuantisedRoundTrip) {
  expect_saddle(encode_draco(*saddle_mesh(false), draco::MESH_SEQUENTIAL_ENCODING, true), kTolPosition, kTolUv,
                kTolNormal);
}

TEST(GltfCompressionDraco, EdgebreakerQuantisedRoundTrip) {
  expect_saddle(encode_draco(*saddle_mesh(false), draco::MESH_EDGEBREAKER_ENCODING, true), kTolPosition, kTolUv,
                kTolNormal);
}

TEST(GltfCompressionDraco, IntegerAttributesKeepTheirValues) {
  // A normalised UNSIGNED_BYTE colour comes back as 0..255, not 0..1: the
  // glTF accessor says how to normalise, and the caller applies it.
  const std::vector<uint8_t> s = encode_draco(*saddle_mesh(true), draco::MESH_EDGEBREAKER_ENCODING, true);
  const DracoMesh m = decode_draco(s, {int(kColorId), int(kUvId)});
  ASSERT_EQ(m.attributes.size(), 2u);
  const DracoAttribute& col = m.attributes[0];
  const DracoAttribute& uv = m.attributes[1];
  ASSERT_EQ(col.components, 4);
  ASSERT_EQ(col.values.size(), m.vertex_count * 4);
  ASSERT_EQ(uv.values.size(), m.vertex_count * 2);
  for (size_t v = 0; v < m.vertex_count; ++v) {
    Corner c{};
    c.uv = {uv.values[2 * v], uv.values[2 * v + 1]};
    const std::array<uint8_t, 4> want = saddle_color(c);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(col.values[4 * v + size_t(k)], float(want[size_t(k)])) << "vertex " << v;
  }
}

TEST(GltfCompressionDraco, AttributesComeInTheOrderAsked) {
  const std::vector<uint8_t> s = encode_draco(*saddle_mesh(false), draco::MESH_SEQUENTIAL_ENCODING, false);
  const DracoMesh m = decode_draco(s, {int(kNormalId), int(kPositionId), int(kNormalId)});
  ASSERT_EQ(m.attributes.size(), 3u);
  EXPECT_EQ(m.attributes[0].unique_id, int(kNormalId));
  EXPECT_EQ(m.attributes[1].unique_id, int(kPositionId));
  EXPECT_EQ(m.attributes[2].values, m.attributes[0].values);
  for (size_t v = 0; v < m.vertex_count; ++v) {  // unit normals, saddle positions
    const float* n = &m.attributes[0].values[3 * v];
    const float* p = &m.attributes[1].values[3 * v];
    EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.f, 1e-6f);
    EXPECT_FLOAT_EQ(p[2], 0.25f * p[0] * p[1]);
  }
  const DracoMesh none = decode_draco(s, {});
  EXPECT_TRUE(none.attributes.empty());
  EXPECT_EQ(none.indices, m.indices);
}

TEST(GltfCompressionDraco, MissingUniqueIdIsAnError) {
  const std::vector<uint8_t> s = encode_draco(*saddle_mesh(false), draco::MESH_EDGEBREAKER_ENCODING, true);
  EXPECT_TRUE(fails_with([&] { decode_draco(s, {int(kPositionId), 99}); }, kDracoWhere, {"unique id 99"}));
  EXPECT_TRUE(fails_with([&] { decode_draco(s, {-1}); }, kDracoWhere, {"unique id -1"}));
  EXPECT_TRUE(fails_with([&] { decode_draco(s, {int(kColorId)}); }, kDracoWhere, {"unique id 9"}));
}

TEST(GltfCompressionDraco, PointCloudIsAnError) {
  draco::PointCloudBuilder b;
  constexpr int kPoints = 10;
  b.Start(kPoints);
  const int pos = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (int i = 0; i < kPoints; ++i) {
    const float p[3] = {float(i), float(i * i), 1.f};
    b.SetAttributeValueForPoint(pos, draco::PointIndex(uint32_t(i)), p);
  }
  std::unique_ptr<draco::PointCloud> pc = b.Finalize(false);
  draco::Encoder enc;
  draco::EncoderBuffer buf;
  ASSERT_TRUE(enc.EncodePointCloudToBuffer(*pc, &buf).ok());
  const std::vector<uint8_t> s(buf.data(), buf.data() + buf.size());
  EXPECT_TRUE(fails_with([&] { decode_draco(s, {0}); }, kDracoWhere, {"point cloud"}));
}

TEST(GltfCompressionDraco, ForeignBytesAreAnError) {
  const std::string text = "{\"asset\":{\"version\":\"2.0\"}}";
  const std::vector<uint8_t> json(text.begin(), text.end()), zeros(100, 0);
  const std::vector<std::string> says = {"Draco stream cannot be decoded ("};
  EXPECT_TRUE(fails_with([&] { decode_draco(json, {0}); }, kDracoWhere, says));
  EXPECT_TRUE(fails_with([&] { decode_draco(zeros, {0}); }, kDracoWhere, says));
  EXPECT_TRUE(fails_with([&] { rayform::decode_draco(nullptr, 0, {0}, kDracoWhere); }, kDracoWhere, says));
  // A meshopt stream is not a Draco one.
  EXPECT_TRUE(
      fails_with([&] { decode_draco(encode_vertices(vertex_bytes(30, 8, 4), 30, 8), {0}); }, kDracoWhere, says));
}

TEST(GltfCompressionDraco, EveryTruncationIsAnError) {
  for (int method : {draco::MESH_SEQUENTIAL_ENCODING, draco::MESH_EDGEBREAKER_ENCODING}) {
    const std::vector<uint8_t> s = encode_draco(*saddle_mesh(false), method, true);
    SCOPED_TRACE("method " + std::to_string(method) + ", " + std::to_string(s.size()) + " bytes");
    for (size_t n = 0; n < s.size(); ++n) {
      const std::vector<uint8_t> prefix(s.begin(), s.begin() + long(n));
      EXPECT_TRUE(fails_with(
          [&] {
            decode_draco(prefix, {int(kPositionId), int(kNormalId)});
          },
          kDracoWhere))
          << n << " bytes";
    }
  }
}

TEST(GltfCompressionDraco, FlippedBytesDecodeOrFailNeverCrash) {
  std::mt19937 rng(77);
  int errors = 0;
  for (int method : {draco::MESH_SEQUENTIAL_ENCODING, draco::MESH_EDGEBREAKER_ENCODING}) {
    const std::vector<uint8_t> s = encode_draco(*saddle_mesh(false), method, true);
    for (int m = 0; m < kMutations; ++m) {
      std::vector<uint8_t> b = s;
      const int flips = 1 + int(rng() % 4);
      for (int f = 0; f < flips; ++f) b[rng() % b.size()] ^= uint8_t(1 + rng() % 255);
      try {
        const DracoMesh d = decode_draco(b, {int(kPositionId), int(kUvId)});
        // Whatever decodes keeps the promised shape.
        for (uint32_t i : d.indices) ASSERT_LT(i, d.vertex_count);
        ASSERT_EQ(d.attributes.size(), 2u);
        for (const DracoAttribute& a : d.attributes) EXPECT_EQ(a.values.size(), d.vertex_count * size_t(a.components));
      } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(kDracoWhere + ": ", 0), 0u) << e.what();
        ++errors;
      }
    }
  }
  EXPECT_GT(errors, 0);
}

}  // namespace
}  // namespace rayform
