// Every read of glTF accessor data, in one place: type and component-type
// checks (core glTF plus KHR_mesh_quantization), bufferView and buffer bounds,
// byteStride, sparse substitution, normalised integers, and buffer views
// compressed with EXT_meshopt_compression (decoded once, on first use).
// Errors are rayform::Error "file: path: what", the path naming the element
// at fault, e.g. "duck.glb: meshes[0].primitives[0].attributes.POSITION
// (accessors[2]): 24 elements ... run past the end of bufferViews[1]".
#pragma once

#include "rayform/importers/gltf/gltf_messages.h"

// Debian's tinygltf is a prebuilt library: never define TINYGLTF_IMPLEMENTATION here.
#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace rayform {

// The (componentType, normalized) pairs an attribute may use, as bits.
enum AccessorFormat : uint32_t {
  format_float = 1u << 0,
  format_unorm8 = 1u << 1,   // UNSIGNED_BYTE, normalized: c / 255
  format_unorm16 = 1u << 2,  // UNSIGNED_SHORT, normalized: c / 65535
  format_snorm8 = 1u << 3,   // BYTE, normalized: max(c / 127, -1)
  format_snorm16 = 1u << 4,  // SHORT, normalized: max(c / 32767, -1)
  format_uint8 = 1u << 5,    // UNSIGNED_BYTE as its integer value
  format_uint16 = 1u << 6,
  format_int8 = 1u << 7,  // BYTE as its integer value
  format_int16 = 1u << 8,
};
// What each attribute semantic accepts: the core specification's formats plus
// KHR_mesh_quantization's (accepted whether or not the file declares it; the
// values are what they are, and positions are scaled by the node transform).
inline constexpr uint32_t formats_position = format_float | format_unorm8 | format_unorm16 | format_snorm8 |
                                             format_snorm16 | format_uint8 | format_uint16 | format_int8 | format_int16;
inline constexpr uint32_t formats_normal = format_float | format_snorm8 | format_snorm16;
inline constexpr uint32_t formats_texcoord = formats_position;
inline constexpr uint32_t formats_color = format_float | format_unorm8 | format_unorm16;
inline constexpr uint32_t formats_weights = format_float | format_unorm8 | format_unorm16;
inline constexpr uint32_t formats_joints = format_uint8 | format_uint16;
inline constexpr uint32_t formats_morph_delta =
    format_float | format_snorm8 | format_snorm16 | format_int8 | format_int16;
// EXT_mesh_gpu_instancing: ROTATION may be normalized (as gltfpack writes it).
inline constexpr uint32_t formats_rotation = format_float | format_snorm8 | format_snorm16;

// A component of type `component_type` as float, normalised or not.
float gltf_component_value(const unsigned char* p, int component_type, bool normalized);
// An integer component's value (as float) normalised as its type says: the
// value itself for FLOAT.
float gltf_normalize_integer(float value, int component_type);
// The AccessorFormat bit of (component_type, normalized), 0 when none.
uint32_t gltf_accessor_format(int component_type, bool normalized);
int gltf_type_components(int type);
const char* gltf_type_name(int type);

class GltfAccessors {
 public:
  // `file` prefixes every error message. An accessor backed by bytes is
  // bounded by them; those without a bufferView (zeros, perhaps with sparse
  // values) may hold at most `max_unbacked_elements`
  // (Limits::unbacked_elements) together, summed over every read (a mesh
  // copied per morph weights reads its accessors again): a 700-byte file
  // could otherwise ask for gigabytes of zeros.
  GltfAccessors(const tinygltf::Model& model, std::string file, uint64_t max_unbacked_elements)
      : model_(model), file_(std::move(file)), max_unbacked_elements_(max_unbacked_elements) {}

  // Accessor `a`; `where` names the reference to it.
  const tinygltf::Accessor& accessor(int a, const std::string& where) const;

  // Checks accessor `a`'s type is one of `types` and its component type one
  // of `formats`; returns it.
  const tinygltf::Accessor& check_format(int a, const std::string& where, std::initializer_list<int> types,
                                         uint32_t formats) const;

  struct Floats {
    std::vector<float> values;  // count * components
    int components = 0;
    size_t count = 0;
  };
  // Accessor `a` as floats, after checking its type is one of `types` and its
  // component type one of `formats`. Sparse values substituted.
  Floats read_floats(int a, const std::string& where, std::initializer_list<int> types, uint32_t formats);

  // A SCALAR accessor of UNSIGNED_BYTE/SHORT/INT as indices (not checked
  // against any vertex count).
  std::vector<uint32_t> read_indices(int a, const std::string& where);

  // The bytes of bufferView `v` (decoded when EXT_meshopt_compression
  // compresses it), checked against its buffer.
  struct View {
    const unsigned char* data = nullptr;
    size_t length = 0;
    size_t stride = 0;  // 0: tightly packed
  };
  View view(int v, const std::string& where);

  [[noreturn]] void fail(const std::string& what) const;

 private:
  template <class Alloc, class Put>
  void read_elements(const tinygltf::Accessor& acc, const std::string& aw, int components, Alloc&& alloc, Put&& put);

  const tinygltf::Model& model_;
  std::string file_;
  uint64_t max_unbacked_elements_;
  uint64_t unbacked_elements_ = 0;                     // read so far, in elements
  std::map<int, std::vector<uint8_t>> decoded_views_;  // EXT_meshopt_compression, per bufferView
};

// a + b <= limit without overflow.
inline bool fits_in(uint64_t a, uint64_t b, uint64_t limit) { return a <= limit && b <= limit - a; }

}  // namespace rayform
