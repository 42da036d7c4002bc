// The glTF writer's output (GltfWriter, gltf_writer_internal.h): the model written
// by tinygltf into a temporary folder (.gltf with its .bin, or .glb), each
// file checked for its whole length and synced, then all renamed into place.
#include "rayform/importers/gltf/gltf_writer_internal.h"
#include "rayform/image/checked_write.h"
#include "rayform/base/error.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <filesystem>
#include <fstream>

namespace rayform::gltf_detail {
namespace fs = std::filesystem;

namespace {

// Keeps every image's URI as set here (tinygltf would otherwise re-encode).
bool keep_image_uri(const std::string*, const std::string*, const tinygltf::Image* image, bool, std::string* out_uri,
                    void*) {
  *out_uri = image->uri;
  return true;
}

// The length a .glb's header declares (0 when the header is missing).
uint64_t glb_length(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  unsigned char head[12] = {};
  if (!in.read(reinterpret_cast<char*>(head), sizeof head)) return 0;
  return uint64_t(head[8]) | uint64_t(head[9]) << 8 | uint64_t(head[10]) << 16 | uint64_t(head[11]) << 24;
}

// tinygltf writes a buffer beside the .gltf under the buffer's URI: a buffer
// in a side folder elsewhere gets its URI here, after the write.
void set_buffer_uri(const std::string& gltf, const std::string& uri) {
  nlohmann::json j;
  {
    std::ifstream in(gltf, std::ios::binary);
    j = nlohmann::json::parse(in, nullptr, /*allow_exceptions*/ false);
  }
  if (j.is_discarded()) return;  // a short file: check_written says so
  j["buffers"][0]["uri"] = uri;
  std::ofstream(gltf, std::ios::binary | std::ios::trunc) << j.dump(2);
}

}  // namespace

std::string GltfWriter::side_uri(const std::string& file) const {
  static const char* hex = "0123456789ABCDEF";
  std::string uri;
  for (unsigned char c : context_.out.side_reference(file)) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') uri += char(c);
    else uri.append(1, '%').append(1, hex[c >> 4]).append(1, hex[c & 15]);
  }
  return uri;
}

// A file tinygltf wrote: `bytes` long (when not 0), complete JSON (when
// `json`), then synced; else the write failed (a full disk, most likely).
void GltfWriter::check_written(const std::string& file, uint64_t bytes, bool json) const {
  std::error_code ec;
  const uint64_t size = fs::file_size(file, ec);
  bool complete = !ec && size > 0 && (bytes == 0 || size == bytes);
  if (complete && json) {
    std::ifstream in(file, std::ios::binary);
    complete = nlohmann::json::accept(in);
  }
  std::string error = complete ? "" : "the file was cut short (disk full?)";
  if (complete && !sync_file(file, &error)) complete = false;
  if (!complete) throw Error(context_.path + ": cannot write (" + error + ")");
}

SaveResult GltfWriter::save() {
  if (!buffer_.empty()) {
    tinygltf::Buffer b;
    b.data = std::move(buffer_);
    if (!options_.binary && !options_.embed) b.uri = context_.stem + ".bin";
    model_.buffers.push_back(std::move(b));
  }
  const std::string dir = context_.out.temp_dir();
  const std::string ext = options_.binary ? ".glb" : ".gltf";
  const std::string temp_main = (fs::path(dir) / (context_.stem + ext)).string();
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(&keep_image_uri, nullptr);
  if (!writer.WriteGltfSceneToFile(&model_, temp_main, /*embedImages*/ false, /*embedBuffers*/ options_.embed,
                                   /*prettyPrint*/ true, /*writeBinary*/ options_.binary))
    throw Error(context_.path + ": cannot write (tinygltf failed to write '" + temp_main + "')");
  std::error_code ec;
  if (!fs::is_regular_file(temp_main, ec)) throw Error(context_.path + ": cannot write (tinygltf wrote nothing)");
  const std::string bin_name = model_.buffers.empty() ? "" : model_.buffers[0].uri;
  if (!bin_name.empty() && context_.out.side_reference(bin_name) != bin_name)
    set_buffer_uri(temp_main, side_uri(bin_name));
  // tinygltf does not check its writes: a full disk leaves short files. Each
  // is checked for its whole length, then synced (image/checked_write.h).
  check_written(temp_main, options_.binary ? glb_length(temp_main) : 0, !options_.binary);
  if (!bin_name.empty()) {
    std::string bin = (fs::path(dir) / bin_name).string();
    if (!fs::is_regular_file(bin, ec)) throw Error(context_.path + ": cannot write the buffer file " + bin_name);
    check_written(bin, model_.buffers[0].data.size(), false);
    context_.out.add_written(context_.out.side_path(bin_name), bin);
  }
  context_.out.add_written(context_.path, temp_main);
  SaveResult r;
  r.files = context_.out.commit();
  for (const tinygltf::Mesh& m : model_.meshes)  // as readers count: each mesh once, every primitive
    for (const tinygltf::Primitive& p : m.primitives)
      r.stored_triangles += model_.accessors[size_t(p.indices)].count / 3;
  return r;
}

}  // namespace rayform::gltf_detail
