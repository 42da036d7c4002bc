#include "rayform/importers/gltf/gltf_file_access.h"
#include "rayform/base/memory_budget.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace rayform {
namespace fs = std::filesystem;

std::string percent_decode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// ---- the container and JSON that tinygltf refuses ------------------------------

GltfContainer read_gltf_container(const std::vector<unsigned char>& bytes, bool glb) {
  GltfContainer out;
  if (!glb) {
    out.json = GltfJsonChunk{0, bytes.size()};
    return out;
  }
  auto u32 = [&](size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, bytes.data() + at, 4);
    return uint64_t(v);
  };
  constexpr size_t header = 12, chunk_header = 8;
  constexpr uint64_t json_type = 0x4E4F534A;  // "JSON"
  // The JSON chunk comes first, inside the file (what the header's total
  // length says of it is the container's problem, below).
  if (bytes.size() >= header + chunk_header && u32(header + 4) == json_type &&
      u32(header) <= bytes.size() - header - chunk_header)
    out.json = GltfJsonChunk{header + chunk_header, size_t(u32(header))};
  if (bytes.size() < header) {
    out.problem = "the file is shorter than the 12-byte GLB header";
    return out;
  }
  const uint64_t total = u32(8);
  if (total > bytes.size()) {
    out.problem =
        "the header says the file has " + std::to_string(total) + " bytes, it has " + std::to_string(bytes.size());
    return out;
  }
  int k = 0;
  for (uint64_t at = header; at < total; ++k) {
    if (at + chunk_header > total) {
      out.problem = "chunk " + std::to_string(k) + " has no room for its 8-byte header";
      return out;
    }
    const uint64_t length = u32(size_t(at));
    if (at + chunk_header + length > total) {
      out.problem = "chunk " + std::to_string(k) + " of " + std::to_string(length) + " bytes runs past the file's " +
                    std::to_string(total) + " bytes";
      return out;
    }
    at += chunk_header + length;
  }
  return out;
}

std::string json_too_deep(const std::vector<unsigned char>& bytes, const GltfContainer& container, uint64_t max_depth) {
  if (!container.json) return "";  // tinygltf reports the broken container
  const GltfJsonChunk& chunk = *container.json;
  uint64_t depth = 0, line = 1;
  size_t line_start = chunk.offset;
  bool in_string = false;
  for (size_t i = chunk.offset; i < chunk.offset + chunk.length; ++i) {
    const unsigned char c = bytes[i];
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '\n') {
      ++line;
      line_start = i + 1;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return "line " + std::to_string(line) + ", column " + std::to_string(i - line_start + 1);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return "";
}

namespace {

// ---- tinygltf callbacks -------------------------------------------------------

// Whether the file may be read (tinygltf asks before it reads): joined to the
// model's folder and passing referenced_file_problem; the first refusal is
// kept for the reader's message.
bool fs_file_exists(const std::string& path, void* user) {
  GltfFileAccess* ctx = static_cast<GltfFileAccess*>(user);
  if (path.rfind(ctx->base + "/", 0) != 0) return false;
  const std::string name = path.substr(ctx->base.size() + 1);
  if (std::string problem = referenced_file_problem(ctx->scene_file, "uri", name, path, ctx->access);
      !problem.empty()) {
    if (ctx->problem.empty()) ctx->problem = problem;
    return false;
  }
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string fs_expand(const std::string& path, void*) { return path; }

bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (!fs_file_exists(path, user)) {
    if (err) *err += "cannot read " + path;
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (err) *err += "cannot open " + path;
    return false;
  }
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  job_memory().credit_input(out->size());
  return true;
}

bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported by the reader";
  return false;
}

}  // namespace

bool adapt_json_for_tinygltf(std::vector<unsigned char>& bytes, bool glb, GltfContainer& container) {
  if (!container.json) return false;
  const GltfJsonChunk chunk = *container.json;
  const char* text = reinterpret_cast<const char*>(bytes.data() + chunk.offset);
  const std::string_view view(text, chunk.length);
  if (view.find("EXT_meshopt_compression") == std::string_view::npos &&
      view.find("KHR_draco_mesh_compression") == std::string_view::npos)
    return false;
  nlohmann::json j = nlohmann::json::parse(text, text + chunk.length, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return false;
  bool changed = false;
  auto extension = [](nlohmann::json& object, const char* name) -> nlohmann::json* {
    if (!object.is_object() || !object.contains("extensions") || !object["extensions"].is_object() ||
        !object["extensions"].contains(name) || !object["extensions"][name].is_object())
      return nullptr;
    return &object["extensions"][name];
  };
  if (j.contains("buffers") && j["buffers"].is_array()) {
    for (size_t i = 0; i < j["buffers"].size(); ++i) {
      nlohmann::json& b = j["buffers"][i];
      if (!b.is_object() || b.contains("uri") || (glb && i == 0)) continue;
      const nlohmann::json* ext = extension(b, "EXT_meshopt_compression");
      if (!ext || !ext->contains("fallback") || (*ext)["fallback"] != true) continue;
      b["uri"] = "data:application/octet-stream;base64,AA==";  // one zero byte
      b["byteLength"] = 1;
      changed = true;
    }
  }
  if (j.contains("meshes") && j["meshes"].is_array()) {
    for (nlohmann::json& mesh : j["meshes"]) {
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
      for (nlohmann::json& prim : mesh["primitives"]) {
        nlohmann::json* draco = extension(prim, "KHR_draco_mesh_compression");
        if (draco && draco->contains("attributes") && (*draco)["attributes"].is_object())
          for (auto& [name, id] : (*draco)["attributes"].items())
            if (id.is_number() && !(id.is_number_unsigned() && id.get<uint64_t>() <= uint64_t(INT32_MAX))) {
              id = id.dump();  // tinygltf would cast it to int (2^40 to 0)
              changed = true;
            }
        if (!draco || !prim.contains("indices")) continue;
        (*draco)[draco_indices_key] = prim["indices"];
        prim.erase("indices");
        changed = true;
      }
    }
  }
  if (!changed) return false;
  std::string json = j.dump();
  if (!glb) {
    bytes.assign(json.begin(), json.end());
    container.json = GltfJsonChunk{0, bytes.size()};
    return true;
  }
  while (json.size() % 4 != 0) json += ' ';
  std::vector<unsigned char> out(bytes.begin(), bytes.begin() + 12);
  const uint32_t json_length = uint32_t(json.size());
  const unsigned char* type = bytes.data() + 16;
  out.insert(out.end(), reinterpret_cast<const unsigned char*>(&json_length),
             reinterpret_cast<const unsigned char*>(&json_length) + 4);
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), json.begin(), json.end());
  // The chunks after the JSON one (the BIN chunk), as they were; the JSON
  // chunk's end is padded to 4 bytes in a valid file.
  size_t rest = chunk.offset + ((chunk.length + 3) / 4) * 4;
  if (rest < bytes.size()) out.insert(out.end(), bytes.begin() + long(rest), bytes.end());
  const uint32_t total = uint32_t(out.size());
  std::memcpy(out.data() + 8, &total, 4);
  bytes = std::move(out);
  container.json = GltfJsonChunk{20, json.size()};
  return true;
}

tinygltf::FsCallbacks GltfFileAccess::callbacks() {
  return tinygltf::FsCallbacks{&fs_file_exists, &fs_expand, &fs_read, &fs_write, this};
}

}  // namespace rayform
