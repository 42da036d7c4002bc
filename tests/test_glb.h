// Binary glTF (GLB) containers for importer tests that make their files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rayform::test {

// A GLB container: JSON chunk (space padded) and, if given, a BIN chunk.
inline std::vector<uint8_t> make_glb(std::string json, const std::vector<uint8_t>& bin) {
  while (json.size() % 4) json += ' ';
  std::vector<uint8_t> b = bin;
  while (b.size() % 4) b.push_back(0);
  auto u32 = [](std::vector<uint8_t>& out, uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k)));
  };
  std::vector<uint8_t> out = {'g', 'l', 'T', 'F'};
  u32(out, 2);
  u32(out, uint32_t(12 + 8 + json.size() + (b.empty() ? 0 : 8 + b.size())));
  u32(out, uint32_t(json.size()));
  u32(out, 0x4E4F534A);
  out.insert(out.end(), json.begin(), json.end());
  if (!b.empty()) {
    u32(out, uint32_t(b.size()));
    u32(out, 0x004E4942);
    out.insert(out.end(), b.begin(), b.end());
  }
  return out;
}

}  // namespace rayform::test
