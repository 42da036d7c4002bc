// Compressed glTF geometry: EXT_meshopt_compression (meshoptimizer) and
// KHR_draco_mesh_compression (libdraco). Plain functions over byte ranges that
// the caller has already bounds-checked; every failure is a rayform::Error
// whose message starts with `where` (the JSON path of the extension object,
// e.g. "bufferViews[3].extensions.EXT_meshopt_compression"), never a crash:
// these decoders see untrusted bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rayform {

// The most bytes one decode may produce (1 GiB): a meshopt buffer view's
// count * byteStride, or a Draco mesh's indices or one of its attributes as
// floats. Far beyond any asset rayform renders; larger requests are an Error
// before anything is allocated, so a few hostile bytes cannot ask for
// terabytes.
inline constexpr size_t max_decoded_geometry_bytes = size_t(1) << 30;

// EXT_meshopt_compression's modes and filters, as the extension spells them.
enum class MeshoptMode : uint8_t { attributes, triangles, indices };
enum class MeshoptFilter : uint8_t { none, octahedral, quaternion, exponential };

// Parses "ATTRIBUTES" / "TRIANGLES" / "INDICES" and "NONE" / "OCTAHEDRAL" /
// "QUATERNION" / "EXPONENTIAL"; anything else is an Error naming `where`.
MeshoptMode parse_meshopt_mode(const std::string& mode, const std::string& where);
MeshoptFilter parse_meshopt_filter(const std::string& filter, const std::string& where);

// Decodes `count` elements of `stride` bytes from `compressed` into count *
// stride bytes, then applies `filter` in place. The extension's constraints
// are checked first: ATTRIBUTES needs stride a multiple of 4 and <= 256;
// TRIANGLES and INDICES need stride 2 or 4 (and TRIANGLES a count that is a
// multiple of 3); OCTAHEDRAL needs stride 4 or 8, QUATERNION 8, EXPONENTIAL a
// multiple of 4; filters only with ATTRIBUTES. Then count * stride above
// max_decoded_geometry_bytes, and a stream shorter than the bitstream's least
// size for `count` elements, are refused before anything is allocated.
// Truncated or corrupt streams are an Error; decoded values are not checked
// (indices may be out of range: the caller checks them against its vertices).
std::vector<uint8_t> decode_meshopt(const uint8_t* compressed, size_t compressed_size, size_t count, size_t stride,
                                    MeshoptMode mode, MeshoptFilter filter, const std::string& where);

// One decoded Draco attribute: `components` floats per vertex, the values the
// Draco stream holds (dequantised if Draco quantised them; integer attributes
// converted to float as they are, not normalised, even when Draco marks them
// normalised: the glTF accessor says how to interpret them).
struct DracoAttribute {
  int unique_id = -1;
  int components = 0;
  std::vector<float> values;  // vertex_count * components
};

// A decoded Draco triangle mesh: indices into its vertices, three per face,
// and the attributes asked for, in the order of `unique_ids`.
struct DracoMesh {
  size_t vertex_count = 0;
  std::vector<uint32_t> indices;
  std::vector<DracoAttribute> attributes;
};

// Decodes a Draco mesh (edgebreaker or sequential) and the attributes whose
// Draco unique ids are `unique_ids` (the extension's "attributes" values).
// A stream that is not a Draco triangle mesh, is truncated or corrupt, has a
// face index outside its vertices, or lacks one of the ids is an Error naming
// `where`; indices are always < vertex_count.
DracoMesh decode_draco(const uint8_t* data, size_t size, const std::vector<int>& unique_ids, const std::string& where);

}  // namespace rayform
