#include "rayform/importers/gltf/gltf_accessors.h"

#include "rayform/importers/gltf/gltf_compression.h"
#include "rayform/base/error.h"
#include "rayform/base/limits.h"

#include <algorithm>
#include <cstring>

namespace rayform {

namespace {

const char* component_name(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
  }
  return "unknown component type";
}

int component_size(int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
  }
  return 0;
}

// The formats in `formats`, for messages: "FLOAT or normalized UNSIGNED_BYTE".
std::string format_names(uint32_t formats) {
  static const std::pair<uint32_t, const char*> names[] = {
      {format_float, "FLOAT"},
      {format_unorm8, "normalized UNSIGNED_BYTE"},
      {format_unorm16, "normalized UNSIGNED_SHORT"},
      {format_snorm8, "normalized BYTE"},
      {format_snorm16, "normalized SHORT"},
      {format_uint8, "UNSIGNED_BYTE"},
      {format_uint16, "UNSIGNED_SHORT"},
      {format_int8, "BYTE"},
      {format_int16, "SHORT"},
  };
  std::string out;
  for (const auto& [bit, name] : names)
    if (formats & bit) out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

uint32_t read_index(const unsigned char* p, int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
  return 0;
}

bool is_index_type(int ct) {
  return ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

// A non-negative integer member of a JSON object; `fallback` when absent.
size_t json_size(const tinygltf::Value& obj, const char* key, size_t fallback, const std::string& where,
                 const GltfAccessors& accessors) {
  if (!obj.Has(key)) return fallback;
  const tinygltf::Value& v = obj.Get(key);
  if (!v.IsNumber() || !(v.GetNumberAsDouble() >= 0.0) || v.GetNumberAsDouble() > 9.0e15 ||
      v.GetNumberAsDouble() != double(int64_t(v.GetNumberAsDouble())))
    accessors.fail(where + "." + key + ": expected an integer >= 0");
  return size_t(v.GetNumberAsDouble());
}

}  // namespace

float gltf_normalize_integer(float v, int ct) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v / 255.f;
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(v / 127.f, -1.f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return v / 65535.f;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(v / 32767.f, -1.f);
  }
  return v;
}

namespace {
// The component at p as a float; p need not be aligned. (glTF data is
// little-endian, like every target rayform builds for.)
template <class T>
float unaligned_component(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return float(v);
}
}  // namespace

float gltf_component_value(const unsigned char* p, int ct, bool normalized) {
  float value = 0.f;
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return unaligned_component<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return unaligned_component<uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: value = unaligned_component<uint8_t>(p); break;
    case TINYGLTF_COMPONENT_TYPE_BYTE: value = unaligned_component<int8_t>(p); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: value = unaligned_component<uint16_t>(p); break;
    case TINYGLTF_COMPONENT_TYPE_SHORT: value = unaligned_component<int16_t>(p); break;
  }
  return normalized ? gltf_normalize_integer(value, ct) : value;
}

uint32_t gltf_accessor_format(int ct, bool normalized) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return normalized ? 0u : format_float;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? format_unorm8 : format_uint8;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return normalized ? format_unorm16 : format_uint16;
    case TINYGLTF_COMPONENT_TYPE_BYTE: return normalized ? format_snorm8 : format_int8;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return normalized ? format_snorm16 : format_int16;
  }
  return 0u;
}

int gltf_type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
  }
  return 0;
}

const char* gltf_type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
  }
  return "unknown type";
}

void GltfAccessors::fail(const std::string& what) const { throw Error(file_ + ": " + what); }

const tinygltf::Accessor& GltfAccessors::accessor(int a, const std::string& where) const {
  if (a < 0 || size_t(a) >= model_.accessors.size())
    fail(where + ": accessor " + std::to_string(a) + " does not exist (the file has " +
         std::to_string(model_.accessors.size()) + " accessors)");
  return model_.accessors[size_t(a)];
}

GltfAccessors::View GltfAccessors::view(int v, const std::string& where) {
  if (v < 0 || size_t(v) >= model_.bufferViews.size())
    fail(where + ": bufferView " + std::to_string(v) + " does not exist (the file has " +
         std::to_string(model_.bufferViews.size()) + " bufferViews)");
  const tinygltf::BufferView& bv = model_.bufferViews[size_t(v)];
  const std::string vw = gltf_path("bufferViews", v);
  auto buffer_bytes = [&](int b, size_t offset, size_t length, const std::string& bw) {
    if (b < 0 || size_t(b) >= model_.buffers.size())
      fail(bw + ".buffer: buffer " + std::to_string(b) + " does not exist (the file has " +
           std::to_string(model_.buffers.size()) + " buffers)");
    const tinygltf::Buffer& buf = model_.buffers[size_t(b)];
    if (!fits_in(offset, length, buf.data.size()))
      fail(bw + ": bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
           " lie past the end of " + gltf_path("buffers", b) + " (" + std::to_string(buf.data.size()) + " bytes)");
    return buf.data.data() + offset;
  };
  auto ext = bv.extensions.find("EXT_meshopt_compression");
  if (ext == bv.extensions.end())
    return View{buffer_bytes(bv.buffer, bv.byteOffset, bv.byteLength, vw), bv.byteLength, bv.byteStride};

  // EXT_meshopt_compression: the view's own buffer is (or may be) a fallback
  // without data; the compressed bytes are in the extension's range.
  auto cached = decoded_views_.find(v);
  if (cached == decoded_views_.end()) {
    const std::string ew = vw + ".extensions.EXT_meshopt_compression";
    const tinygltf::Value& e = ext->second;
    if (!e.IsObject()) fail(ew + ": expected an object");
    if (!e.Has("buffer") || !e.Get("buffer").IsNumber()) fail(ew + ".buffer: expected a buffer index");
    const size_t offset = json_size(e, "byteOffset", 0, ew, *this);
    const size_t length = json_size(e, "byteLength", SIZE_MAX, ew, *this);
    const size_t stride = json_size(e, "byteStride", SIZE_MAX, ew, *this);
    const size_t count = json_size(e, "count", SIZE_MAX, ew, *this);
    if (length == SIZE_MAX || stride == SIZE_MAX || count == SIZE_MAX)
      fail(ew + ": byteLength, byteStride and count are required");
    std::string mode, filter = "NONE";
    if (!e.Has("mode") || !e.Get("mode").IsString()) fail(ew + ".mode: expected ATTRIBUTES, TRIANGLES or INDICES");
    mode = e.Get("mode").Get<std::string>();
    if (e.Has("filter")) {
      if (!e.Get("filter").IsString()) fail(ew + ".filter: expected a string");
      filter = e.Get("filter").Get<std::string>();
    }
    const unsigned char* bytes = buffer_bytes(e.Get("buffer").GetNumberAsInt(), offset, length, ew);
    const std::string fw = file_ + ": " + ew;
    std::vector<uint8_t> decoded = decode_meshopt(bytes, length, count, stride, parse_meshopt_mode(mode, fw + ".mode"),
                                                  parse_meshopt_filter(filter, fw + ".filter"), fw);
    cached = decoded_views_.emplace(v, std::move(decoded)).first;
  }
  const std::vector<uint8_t>& d = cached->second;
  if (bv.byteLength > d.size())
    fail(vw + ".byteLength: " + std::to_string(bv.byteLength) + " is more than the " + std::to_string(d.size()) +
         " bytes its EXT_meshopt_compression stream decodes to");
  return View{d.data(), bv.byteLength, bv.byteStride};
}

const tinygltf::Accessor& GltfAccessors::check_format(int a, const std::string& where, std::initializer_list<int> types,
                                                      uint32_t formats) const {
  const tinygltf::Accessor& acc = accessor(a, where);
  const std::string aw = where + " (" + gltf_path("accessors", a) + ")";
  const bool type_ok = std::find(types.begin(), types.end(), acc.type) != types.end();
  const bool format_ok = (gltf_accessor_format(acc.componentType, acc.normalized) & formats) != 0;
  if (!type_ok || !format_ok) {
    std::string want;
    for (int t : types) want += std::string(want.empty() ? "" : " or ") + gltf_type_name(t);
    fail(aw + ": accessor is " + gltf_type_name(acc.type) + " of " + component_name(acc.componentType) +
         (acc.normalized ? " (normalized)" : "") + ", expected " + want + " of " + format_names(formats));
  }
  return acc;
}

GltfAccessors::Floats GltfAccessors::read_floats(int a, const std::string& where, std::initializer_list<int> types,
                                                 uint32_t formats) {
  const tinygltf::Accessor& acc = check_format(a, where, types, formats);
  const std::string aw = where + " (" + gltf_path("accessors", a) + ")";
  Floats out;
  out.components = gltf_type_components(acc.type);
  out.count = acc.count;
  const int cs = component_size(acc.componentType);
  const size_t nc = size_t(out.components);
  read_elements(
      acc, aw, out.components, [&](size_t count) { out.values.assign(count * nc, 0.f); },
      [&](size_t i, const unsigned char* p) {
        for (size_t c = 0; c < nc; ++c)
          out.values[i * nc + c] = gltf_component_value(p + c * size_t(cs), acc.componentType, acc.normalized);
      });
  return out;
}

std::vector<uint32_t> GltfAccessors::read_indices(int a, const std::string& where) {
  const tinygltf::Accessor& acc = accessor(a, where);
  const std::string aw = where + " (" + gltf_path("accessors", a) + ")";
  if (acc.type != TINYGLTF_TYPE_SCALAR || !is_index_type(acc.componentType))
    fail(aw + ": accessor is " + gltf_type_name(acc.type) + " of " + component_name(acc.componentType) +
         ", expected SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  std::vector<uint32_t> out;
  read_elements(
      acc, aw, 1, [&](size_t count) { out.assign(count, 0u); },
      [&](size_t i, const unsigned char* p) { out[i] = read_index(p, acc.componentType); });
  return out;
}

// The element walk shared by both readers: bounds of bufferView, stride and
// buffer checked, then sparse values substituted.
template <class Alloc, class Put>
void GltfAccessors::read_elements(const tinygltf::Accessor& acc, const std::string& aw, int nc, Alloc&& alloc,
                                  Put&& put) {
  const int cs = component_size(acc.componentType);
  const size_t elem = size_t(cs) * size_t(nc);
  // Without a bufferView the elements are zeros (sparse may then set some):
  // nothing in the file bounds the count but the limit, on all such reads.
  if (acc.bufferView == -1) {
    if (!fits_in(unbacked_elements_, acc.count, max_unbacked_elements_)) {
      const uint64_t total = acc.count > UINT64_MAX - unbacked_elements_ ? UINT64_MAX : unbacked_elements_ + acc.count;
      fail(aw + ": count " + std::to_string(acc.count) + " without a bufferView" +
           (unbacked_elements_ ? " (after " + std::to_string(unbacked_elements_) + " read before)" : std::string()) +
           ": " + limit_exceeded("unbacked-elements", total, max_unbacked_elements_));
    }
    unbacked_elements_ += acc.count;
    alloc(acc.count);
  } else {
    View bytes = view(acc.bufferView, aw + ".bufferView");
    size_t stride = bytes.stride;
    if (stride != 0 && stride < elem)
      fail(aw + ": " + gltf_path("bufferViews", acc.bufferView) + ".byteStride " + std::to_string(stride) +
           " is smaller than one element (" + std::to_string(elem) + " bytes)");
    if (stride == 0) stride = elem;
    if (acc.count > 0) {
      // offset + stride (count - 1) + elem <= length, without overflow
      uint64_t last = uint64_t(stride) * uint64_t(acc.count - 1);
      if (!fits_in(acc.byteOffset, last, bytes.length) || !fits_in(acc.byteOffset + last, elem, bytes.length))
        fail(aw + ": " + std::to_string(acc.count) + " elements of " + std::to_string(elem) + " bytes (stride " +
             std::to_string(stride) + ") from byte " + std::to_string(acc.byteOffset) + " run past the end of " +
             gltf_path("bufferViews", acc.bufferView) + " (" + std::to_string(bytes.length) + " bytes)");
    }
    alloc(acc.count);
    for (size_t i = 0; i < acc.count; ++i) put(i, bytes.data + acc.byteOffset + i * stride);
  }
  if (!acc.sparse.isSparse) return;
  const std::string sw = aw + ".sparse";
  const int sc = acc.sparse.count;
  if (sc < 1 || size_t(sc) > acc.count)
    fail(sw + ".count: " + std::to_string(sc) + " is not between 1 and the accessor's count " +
         std::to_string(acc.count));
  const int ict = acc.sparse.indices.componentType;
  if (!is_index_type(ict))
    fail(sw + ".indices.componentType: " + std::to_string(ict) +
         " is not UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0) fail(sw + ": negative byteOffset");
  View ib = view(acc.sparse.indices.bufferView, sw + ".indices.bufferView");
  View vb = view(acc.sparse.values.bufferView, sw + ".values.bufferView");
  const size_t isize = size_t(component_size(ict));
  if (!fits_in(size_t(acc.sparse.indices.byteOffset), isize * size_t(sc), ib.length))
    fail(sw + ".indices: " + std::to_string(sc) + " indices run past the end of " +
         gltf_path("bufferViews", acc.sparse.indices.bufferView) + " (" + std::to_string(ib.length) + " bytes)");
  if (!fits_in(size_t(acc.sparse.values.byteOffset), elem * size_t(sc), vb.length))
    fail(sw + ".values: " + std::to_string(sc) + " values run past the end of " +
         gltf_path("bufferViews", acc.sparse.values.bufferView) + " (" + std::to_string(vb.length) + " bytes)");
  const unsigned char* indices = ib.data + acc.sparse.indices.byteOffset;
  const unsigned char* values = vb.data + acc.sparse.values.byteOffset;
  for (size_t j = 0; j < size_t(sc); ++j) {
    uint32_t target = read_index(indices + j * isize, ict);
    if (target >= acc.count)
      fail(sw + ".indices[" + std::to_string(j) + "]: " + std::to_string(target) + " is past the accessor's " +
           std::to_string(acc.count) + " elements");
    put(target, values + j * elem);
  }
}

}  // namespace rayform
