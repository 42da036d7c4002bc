// The glTF reader's loading (GltfReader, gltf_reader_internal.h): the
// file's bytes checked before tinygltf sees them (JSON or GLB, the GLB
// container, JSON depth), tinygltf's load with file access and image decoding
// of our own, its warnings passed on and its failures explained.
#include "rayform/importers/gltf/gltf_file_access.h"
#include "rayform/base/memory_budget.h"
#include "rayform/importers/gltf/gltf_images.h"
#include "rayform/importers/gltf/gltf_reader_internal.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

namespace rayform::gltf_detail {
namespace fs = std::filesystem;

void GltfReader::load() {
  std::vector<unsigned char> bytes;
  {
    std::ifstream in(path_, std::ios::binary);
    if (!in) fail("cannot open glTF file");
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) fail("cannot read glTF file");
  }
  if (bytes.empty()) fail("not a glTF file: the file is empty");
  job_memory().credit_input(bytes.size());
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) fail("file too large for a glTF (4 GiB or more)");
  const bool glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  if (!glb) {
    size_t first = 0;
    while (first < bytes.size() && std::isspace(bytes[first])) ++first;
    // A UTF-8 byte order mark is tolerated.
    if (first + 3 <= bytes.size() && bytes[first] == 0xEF && bytes[first + 1] == 0xBB && bytes[first + 2] == 0xBF)
      first += 3;
    if (first >= bytes.size() || bytes[first] != '{')
      fail("not a glTF file: neither a JSON object nor a binary glTF (GLB) container");
  }

  GltfContainer container = read_gltf_container(bytes, glb);
  if (!container.problem.empty()) fail("not a valid binary glTF (GLB): " + container.problem);
  if (const std::string at = json_too_deep(bytes, container, options_.limits.json_depth); !at.empty())
    fail(std::string(glb ? "JSON chunk, " : "") + at + ": arrays and objects nest more than " +
         std::to_string(options_.limits.json_depth) + " levels deep (raise the limit with --limit json-depth=N)");
  adapt_json_for_tinygltf(bytes, glb, container);

  GltfFileAccess fsctx;
  fsctx.base = fs::path(path_).parent_path().string();
  if (fsctx.base.empty()) fsctx.base = ".";
  fsctx.scene_file = path_;
  fsctx.access = options_.access;
  tinygltf::FsCallbacks callbacks = fsctx.callbacks();
  GltfImageContext images;
  images.model = &model_;
  images.decode.max_texels = options_.limits.texture_texels;

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(callbacks);
  loader.SetImageLoader(&gltf_load_image, &images);
  std::string err, warn_text;
  bool ok =
      glb ? loader.LoadBinaryFromMemory(&model_, &err, &warn_text, bytes.data(), unsigned(bytes.size()), fsctx.base)
          : loader.LoadASCIIFromString(&model_, &err, &warn_text, reinterpret_cast<const char*>(bytes.data()),
                                       unsigned(bytes.size()), fsctx.base);
  if (!fsctx.problem.empty()) fail(fsctx.problem);
  if (!ok) diagnose_load_failure(bytes, container, glb, err);
  decode_gltf_images(images, model_);
  for (const std::string& w : images.warnings) warn(w);
  ktx2_images_.insert(images.ktx2_images.begin(), images.ktx2_images.end());
  std::istringstream wl(warn_text);
  std::string l;
  while (std::getline(wl, l)) {
    l = gltf_one_line(l);
    if (l.empty()) continue;
    // Missing image files: tinygltf says "File not found : x.png" then
    // "Failed to load external 'uri' for image[0] ...": say it once, plainly.
    if (l.rfind("File not found : ", 0) == 0) {
      warn("cannot find image file '" + l.substr(17) + "'; textures using it are dropped");
      continue;
    }
    if (l.rfind("Failed to load external 'uri' for image", 0) == 0) continue;
    warn(l);
  }
}

// Turns tinygltf's message into one that names the element at fault.
void GltfReader::diagnose_load_failure(const std::vector<unsigned char>& bytes, const GltfContainer& container,
                                       bool glb, const std::string& err) {
  std::string e = gltf_one_line(err);
  if (glb && (e.find("Invalid glTF binary") != std::string::npos || e.find("Too short") != std::string::npos ||
              e.find("Chunk") != std::string::npos || e.find("Invalid magic") != std::string::npos))
    fail("not a valid binary glTF (GLB): " + e);
  // Which buffer is missing? tinygltf reports only the file name.
  if (e.find("File not found") != std::string::npos || e.find("File size mismatch") != std::string::npos ||
      e.find("File is empty") != std::string::npos) {
    try {
      std::string json_text;  // empty without a JSON chunk (tinygltf refuses such a .glb first)
      if (container.json)
        json_text.assign(bytes.begin() + long(container.json->offset),
                         bytes.begin() + long(container.json->offset + container.json->length));
      nlohmann::json j = nlohmann::json::parse(json_text);
      if (j.contains("buffers") && j["buffers"].is_array()) {
        fs::path dir = fs::path(path_).parent_path();
        for (size_t i = 0; i < j["buffers"].size(); ++i) {
          const auto& b = j["buffers"][i];
          if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
          std::string uri = b["uri"].get<std::string>();
          if (is_data_uri(uri)) continue;
          fs::path file = dir / percent_decode(uri);
          std::error_code ec;
          if (!fs::is_regular_file(file, ec))
            fail(idx("buffers", long(i)) + ": cannot find '" + uri + "' (looked in " +
                 (dir.empty() ? std::string(".") : dir.string()) + ")");
          uintmax_t size = fs::file_size(file, ec);
          if (b.contains("byteLength") && b["byteLength"].is_number_unsigned() &&
              b["byteLength"].get<uintmax_t>() != size)
            fail(idx("buffers", long(i)) + ": '" + uri + "' has " + std::to_string(size) + " bytes but byteLength is " +
                 std::to_string(b["byteLength"].get<uintmax_t>()));
        }
      }
    } catch (const nlohmann::json::exception&) {
    }
  }
  if (e.find("parse_error") != std::string::npos || e.find("Failed to parse JSON") != std::string::npos ||
      e.find("Root element is not a JSON object") != std::string::npos)
    fail("not a glTF file: invalid JSON: " + e);
  if (e.find("\"asset\" object not found") != std::string::npos)
    fail("not a glTF file: no \"asset\" object with a \"version\"");
  fail("invalid glTF: " + (e.empty() ? std::string("tinygltf gave no reason") : e));
}

}  // namespace rayform::gltf_detail
