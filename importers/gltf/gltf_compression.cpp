#include "rayform/importers/gltf/gltf_compression.h"

#include "rayform/base/error.h"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <memory>
#include <new>
#include <stdexcept>

namespace rayform {

namespace {

// ---- EXT_meshopt_compression bitstream facts (the extension's Appendix A) ------

constexpr size_t meshopt_header_bytes = 1;               // 0xa0 / 0xe1 / 0xd1, every mode
constexpr size_t meshopt_max_attribute_stride = 256;     // bytes; ATTRIBUTES' byteStride limit
constexpr size_t meshopt_attribute_stride_align = 4;     // bytes; ATTRIBUTES' byteStride multiple
constexpr size_t meshopt_elements_per_header_byte = 64;  // 16-element groups, 2 header bits each
constexpr size_t meshopt_attribute_tail_min_bytes = 32;  // baseline element, padded to 32 bytes
constexpr size_t meshopt_triangles_tail_bytes = 16;      // the codeaux lookup table
constexpr size_t meshopt_indices_tail_bytes = 4;         // reserved zero bytes
constexpr size_t triangles_indices_per_code = 3;         // one code byte per triangle
constexpr size_t index_stride16 = 2;                     // bytes: TRIANGLES / INDICES as 16-bit indices
constexpr size_t index_stride32 = 4;                     // bytes: ... as 32-bit indices
constexpr size_t octahedral_stride8 = 4;                 // bytes: four 8-bit components
constexpr size_t octahedral_stride16 = 8;                // bytes: four 16-bit components
constexpr size_t quaternion_stride = 8;                  // bytes: four 16-bit components
constexpr size_t exponential_stride_align = 4;           // bytes: 32-bit values

const char* mode_name(MeshoptMode m) {
  switch (m) {
    case MeshoptMode::attributes: return "ATTRIBUTES";
    case MeshoptMode::triangles: return "TRIANGLES";
    case MeshoptMode::indices: return "INDICES";
  }
  return "unknown mode";
}

const char* filter_name(MeshoptFilter f) {
  switch (f) {
    case MeshoptFilter::none: return "NONE";
    case MeshoptFilter::octahedral: return "OCTAHEDRAL";
    case MeshoptFilter::quaternion: return "QUATERNION";
    case MeshoptFilter::exponential: return "EXPONENTIAL";
  }
  return "unknown filter";
}

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw Error(where + ": " + what); }

std::string bytes_text(size_t n) { return std::to_string(n) + (n == 1 ? " byte" : " bytes"); }

// The extension's validity rules on (mode, filter, byteStride, count), so that
// the decoder (whose own checks are asserts) only ever sees what it supports.
void check_meshopt_layout(size_t count, size_t stride, MeshoptMode mode, MeshoptFilter filter,
                          const std::string& where) {
  const std::string found = ", found " + std::to_string(stride);
  if (mode == MeshoptMode::attributes) {
    if (stride == 0 || stride % meshopt_attribute_stride_align != 0 || stride > meshopt_max_attribute_stride)
      fail(where, "mode ATTRIBUTES needs a byteStride that is a multiple of 4, from 4 to 256" + found);
  } else {
    if (stride != index_stride16 && stride != index_stride32)
      fail(where, std::string("mode ") + mode_name(mode) + " needs byteStride 2 or 4" + found);
    if (filter != MeshoptFilter::none)
      fail(where, std::string("filter ") + filter_name(filter) + " is only allowed with mode ATTRIBUTES, not " +
                      mode_name(mode));
    if (mode == MeshoptMode::triangles && count % triangles_indices_per_code != 0)
      fail(where, "mode TRIANGLES needs a count that is a multiple of 3, found " + std::to_string(count));
  }
  switch (filter) {
    case MeshoptFilter::none: break;
    case MeshoptFilter::octahedral:
      if (stride != octahedral_stride8 && stride != octahedral_stride16)
        fail(where, "filter OCTAHEDRAL needs byteStride 4 or 8" + found);
      break;
    case MeshoptFilter::quaternion:
      if (stride != quaternion_stride) fail(where, "filter QUATERNION needs byteStride 8" + found);
      break;
    case MeshoptFilter::exponential:
      if (stride % exponential_stride_align != 0)
        fail(where, "filter EXPONENTIAL needs a byteStride that is a multiple of 4" + found);
      break;
  }
}

// The fewest bytes a well-formed stream of `count` elements can have (header,
// the least each element costs, tail). With the size limit checked first this
// cannot overflow; it lets a tiny stream that claims a huge count be refused
// before count * stride bytes are allocated.
size_t meshopt_min_stream_bytes(size_t count, size_t stride, MeshoptMode mode) {
  switch (mode) {
    case MeshoptMode::attributes:
      // Each attribute block holds, per byte of the element, 2 header bits per
      // group of 16 elements, rounded up to whole bytes.
      return meshopt_header_bytes +
             stride * ((count + meshopt_elements_per_header_byte - 1) / meshopt_elements_per_header_byte) +
             std::max(stride, meshopt_attribute_tail_min_bytes);
    case MeshoptMode::triangles:
      return meshopt_header_bytes + count / triangles_indices_per_code + meshopt_triangles_tail_bytes;
    case MeshoptMode::indices:
      return meshopt_header_bytes + count + meshopt_indices_tail_bytes;  // at least one varint byte per index
  }
  return 0;
}

[[noreturn]] void draco_fail(const std::string& where, const std::string& why) {
  fail(where, "Draco stream cannot be decoded (" + why + ")");
}

}  // namespace

MeshoptMode parse_meshopt_mode(const std::string& mode, const std::string& where) {
  if (mode == "ATTRIBUTES") return MeshoptMode::attributes;
  if (mode == "TRIANGLES") return MeshoptMode::triangles;
  if (mode == "INDICES") return MeshoptMode::indices;
  fail(where, "'" + mode + "' is not an EXT_meshopt_compression mode (expected ATTRIBUTES, TRIANGLES or INDICES)");
}

MeshoptFilter parse_meshopt_filter(const std::string& filter, const std::string& where) {
  if (filter == "NONE") return MeshoptFilter::none;
  if (filter == "OCTAHEDRAL") return MeshoptFilter::octahedral;
  if (filter == "QUATERNION") return MeshoptFilter::quaternion;
  if (filter == "EXPONENTIAL") return MeshoptFilter::exponential;
  fail(where, "'" + filter +
                  "' is not an EXT_meshopt_compression filter (expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL)");
}

std::vector<uint8_t> decode_meshopt(const uint8_t* compressed, size_t compressed_size, size_t count, size_t stride,
                                    MeshoptMode mode, MeshoptFilter filter, const std::string& where) {
  check_meshopt_layout(count, stride, mode, filter, where);
  // stride is now 2 to 256, so count * stride cannot overflow below the limit.
  if (count > max_decoded_geometry_bytes / stride)
    fail(where, std::to_string(count) + " elements of " + bytes_text(stride) + " exceed the " +
                    std::to_string(max_decoded_geometry_bytes >> 20) + " MiB a compressed buffer view may decode to");
  const size_t min_size = meshopt_min_stream_bytes(count, stride, mode);
  if (compressed == nullptr || compressed_size < min_size)
    fail(where, "the compressed stream is truncated: " + bytes_text(compressed_size) + " cannot hold " +
                    std::to_string(count) + " elements in mode " + mode_name(mode) + " (at least " +
                    bytes_text(min_size) + " needed)");

  std::vector<uint8_t> out(count * stride);
  int rc = 0;
  switch (mode) {
    case MeshoptMode::attributes:
      rc = meshopt_decodeVertexBuffer(out.data(), count, stride, compressed, compressed_size);
      break;
    case MeshoptMode::triangles:
      rc = meshopt_decodeIndexBuffer(out.data(), count, stride, compressed, compressed_size);
      break;
    case MeshoptMode::indices:
      rc = meshopt_decodeIndexSequence(out.data(), count, stride, compressed, compressed_size);
      break;
  }
  if (rc != 0)
    fail(where, "the compressed stream is corrupt or truncated (meshopt error " + std::to_string(rc) + ", mode " +
                    mode_name(mode) + ", " + std::to_string(count) + " elements of " + bytes_text(stride) + ")");

  // Filters work in place on whole elements; results for out-of-range inputs
  // are unspecified by the extension but stay within the buffer.
  switch (filter) {
    case MeshoptFilter::none: break;
    case MeshoptFilter::octahedral: meshopt_decodeFilterOct(out.data(), count, stride); break;
    case MeshoptFilter::quaternion: meshopt_decodeFilterQuat(out.data(), count, stride); break;
    case MeshoptFilter::exponential: meshopt_decodeFilterExp(out.data(), count, stride); break;
  }
  return out;
}

DracoMesh decode_draco(const uint8_t* data, size_t size, const std::vector<int>& unique_ids, const std::string& where) {
  if (data == nullptr || size == 0) draco_fail(where, "the stream is empty");

  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  std::unique_ptr<draco::Mesh> mesh;
  try {
    // The geometry type first (on a copy: it consumes the header), so that a
    // point cloud is named as such rather than as an unsupported type.
    draco::DecoderBuffer probe(buffer);
    auto type = draco::Decoder::GetEncodedGeometryType(&probe);
    if (!type.ok()) draco_fail(where, type.status().error_msg_string());
    if (type.value() == draco::POINT_CLOUD) fail(where, "the Draco stream holds a point cloud, not a triangle mesh");
    if (type.value() != draco::TRIANGULAR_MESH) draco_fail(where, "unknown geometry type");
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) draco_fail(where, decoded.status().error_msg_string());
    mesh = std::move(decoded).value();
  } catch (const std::bad_alloc&) {
    draco_fail(where, "out of memory: the stream claims more data than can be held");
  } catch (const std::length_error& e) {
    draco_fail(where, std::string("it claims an impossible size: ") + e.what());
  }
  if (!mesh) draco_fail(where, "the decoder returned no mesh");

  DracoMesh out;
  out.vertex_count = mesh->num_points();
  const size_t face_count = mesh->num_faces();
  constexpr size_t corners = 3;  // indices per triangle
  if (face_count > max_decoded_geometry_bytes / (corners * sizeof(uint32_t)))
    fail(where, "the Draco mesh has " + std::to_string(face_count) + " triangles, more than rayform accepts");
  out.indices.reserve(face_count * corners);
  for (size_t f = 0; f < face_count; ++f) {
    const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(uint32_t(f)));
    for (size_t k = 0; k < corners; ++k) {
      const uint32_t p = face[k].value();
      if (p >= out.vertex_count)
        fail(where, "Draco triangle " + std::to_string(f) + " uses vertex " + std::to_string(p) + " but the mesh has " +
                        std::to_string(out.vertex_count) + " vertices");
      out.indices.push_back(p);
    }
  }

  for (int id : unique_ids) {
    const std::string what = "Draco attribute with unique id " + std::to_string(id);
    const int att_id = id < 0 ? -1 : mesh->GetAttributeIdByUniqueId(uint32_t(id));
    if (att_id < 0) fail(where, "the stream has no " + what);
    draco::PointAttribute* att = mesh->attribute(att_id);
    if (att == nullptr) fail(where, "the stream has no " + what);
    const int components = att->num_components();
    if (components <= 0) fail(where, what + " has no components");
    if (out.vertex_count > max_decoded_geometry_bytes / (size_t(components) * sizeof(float)))
      fail(where, what + ": " + std::to_string(out.vertex_count) + " vertices of " + std::to_string(components) +
                      " components are more than rayform accepts");
    if (!att->is_mapping_identity() && att->indices_map_size() < out.vertex_count)
      fail(where, what + " maps fewer points than the mesh has");
    // Integers as they are: glTF's accessor says whether they are normalised,
    // and the caller applies that.
    att->set_normalized(false);

    DracoAttribute a;
    a.unique_id = id;
    a.components = components;
    a.values.resize(out.vertex_count * size_t(components));
    for (size_t i = 0; i < out.vertex_count; ++i) {
      const draco::AttributeValueIndex v = att->mapped_index(draco::PointIndex(uint32_t(i)));
      if (v.value() >= att->size())
        fail(where, what + ": vertex " + std::to_string(i) + " refers to value " + std::to_string(v.value()) + " of " +
                        std::to_string(att->size()));
      if (!att->ConvertValue<float>(v, int8_t(components), a.values.data() + i * size_t(components)))
        fail(where, what + ": value " + std::to_string(v.value()) + " cannot be converted to floats");
    }
    out.attributes.push_back(std::move(a));
  }
  return out;
}

}  // namespace rayform
