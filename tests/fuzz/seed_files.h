// Helpers of the seed generators (make_seeds.cpp, make_draco_seeds.cpp): seed
// files under OUT/<target>/, glTF data URIs and GLB containers, glTF arrays of
// a generated mesh.
#pragma once

#include "rayform/scene/scene.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace rayform::fuzz {

inline std::filesystem::path out_root;
inline int written = 0;

inline void seed(const std::string& target, const std::string& name, const std::string& bytes) {
  if (bytes.size() > (size_t(1) << 20)) return;  // over the targets' input cap
  std::filesystem::create_directories(out_root / target);
  std::ofstream(out_root / target / name, std::ios::binary) << bytes;
  ++written;
}

inline std::string base64(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    unsigned v = (uint8_t(in[i]) << 16) | (uint8_t(in[i + 1]) << 8) | uint8_t(in[i + 2]);
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
  }
  if (i + 1 == in.size()) {
    unsigned v = uint8_t(in[i]) << 16;
    out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    unsigned v = (uint8_t(in[i]) << 16) | (uint8_t(in[i + 1]) << 8);
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
  }
  return out;
}

inline std::string data_uri(const std::string& bytes) {
  return "data:application/octet-stream;base64," + base64(bytes);
}

template <class T>
inline std::string bytes_of(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

inline void pad4(std::string& s, char fill) {
  while (s.size() % 4) s += fill;
}

inline std::string glb(std::string json, std::string bin) {
  pad4(json, ' ');
  pad4(bin, '\0');
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  std::string out = "glTF" + u32(2) + u32(uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
  out += u32(uint32_t(json.size())) + "JSON" + json;
  if (!bin.empty()) out += u32(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
  return out;
}

struct GltfMesh {
  std::vector<float> positions, normals;
  std::vector<uint32_t> indices;
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
};

inline GltfMesh gltf_mesh(const Mesh& m) {
  GltfMesh g;
  for (const vec3& p : m.positions) {
    for (int k = 0; k < 3; ++k) {
      g.positions.push_back(p[k]);
      g.lo[k] = std::min(g.lo[k], p[k]);
      g.hi[k] = std::max(g.hi[k], p[k]);
    }
  }
  for (const vec3& n : m.normals) g.normals.insert(g.normals.end(), {n.x, n.y, n.z});
  g.indices = m.indices;
  return g;
}

inline std::string minmax(const GltfMesh& g) {
  std::ostringstream s;
  s << "\"min\":[" << g.lo[0] << "," << g.lo[1] << "," << g.lo[2] << "],\"max\":[" << g.hi[0] << "," << g.hi[1] << ","
    << g.hi[2] << "]";
  return s.str();
}

inline const char* gltf_head = R"("asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)";

}  // namespace rayform::fuzz
