#include "rayform/render/texture_decode_share.h"

#include "rayform/base/error.h"

#include <tbb/parallel_for.h>

#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

namespace rayform {
namespace {

// Bytes of the exchange, per part: for each of its items in order, one status
// byte (1 decoded, 0 failed), then the image (width, height, wrap, filter,
// lookup, to_linear, rgba8, rgbaf) or the error's message. Sizes are
// uint64_t, in this machine's byte order (the parts run the same program).
class Writer {
 public:
  explicit Writer(std::vector<std::byte>& out) : out_(out) {}
  void raw(const void* p, size_t n) {
    const size_t at = out_.size();
    out_.resize(at + n);
    if (n) std::memcpy(out_.data() + at, p, n);
  }
  template <class T>
  void value(const T& v) {
    raw(&v, sizeof v);
  }
  template <class T>
  void array(const std::vector<T>& v) {
    value(uint64_t(v.size()));
    raw(v.data(), v.size() * sizeof(T));
  }

 private:
  std::vector<std::byte>& out_;
};

class Reader {
 public:
  explicit Reader(const std::vector<std::byte>& in) : in_(in) {}
  void raw(void* p, size_t n) {
    if (n > in_.size() - at_) throw std::logic_error("decode_textures: a part's bytes end early");
    if (n) std::memcpy(p, in_.data() + at_, n);
    at_ += n;
  }
  template <class T>
  T value() {
    T v;
    raw(&v, sizeof v);
    return v;
  }
  template <class T>
  void array(std::vector<T>& v) {
    const uint64_t n = value<uint64_t>();
    if (n > (in_.size() - at_) / sizeof(T)) throw std::logic_error("decode_textures: a part's bytes end early");
    if constexpr (sizeof(T) == 1) {  // bytes: copied without zeroing first
      const T* from = reinterpret_cast<const T*>(in_.data() + at_);
      v.assign(from, from + n);
      at_ += size_t(n);
    } else {  // floats, at any alignment in the bytes
      v.resize(size_t(n));
      raw(v.data(), size_t(n) * sizeof(T));
    }
  }

 private:
  const std::vector<std::byte>& in_;
  size_t at_ = 0;
};

void write_image(Writer& w, const TextureImage& t) {
  w.value(int32_t(t.width));
  w.value(int32_t(t.height));
  w.value(t.wrap_u);
  w.value(t.wrap_v);
  w.value(t.filter);
  w.value(t.lookup);
  w.value(t.to_linear);
  w.array(t.rgba8);
  w.array(t.rgbaf);
}

void read_image(Reader& r, TextureImage& t) {
  t.width = r.value<int32_t>();
  t.height = r.value<int32_t>();
  t.wrap_u = r.value<Texture::Wrap>();
  t.wrap_v = r.value<Texture::Wrap>();
  t.filter = r.value<Texture::Filter>();
  t.lookup = r.value<Texture::Lookup>();
  t.to_linear = r.value<std::array<float, 256>>();
  r.array(t.rgba8);
  r.array(t.rgbaf);
}

}  // namespace

void decode_textures(const Scene& scene, const std::vector<TextureDecodeItem>& items, const DecodeOptions& options,
                     const WorkShare* share) {
  auto decode = [&](size_t j) { *items[j].second = decode_texture(scene.textures[size_t(items[j].first)], options); };
  if (!share || !share->shared() || items.size() < 2) {
    // Decoded in parallel (PNG/JPEG decoding dominates preparing textured scenes).
    tbb::parallel_for(size_t(0), items.size(), decode);
    return;
  }
  const size_t parts = size_t(share->parts), part = size_t(share->part);
  std::vector<size_t> own;
  for (size_t j = part; j < items.size(); j += parts) own.push_back(j);
  std::vector<std::string> errors(own.size());
  tbb::parallel_for(size_t(0), own.size(), [&](size_t k) {
    try {
      decode(own[k]);
    } catch (const std::exception& e) {
      errors[k] = e.what();
      if (errors[k].empty()) errors[k] = "texture decoding failed";
    }
  });
  // One allocation for the bytes sent (the images are megabytes each).
  size_t bytes = 0;
  for (size_t k = 0; k < own.size(); ++k) {
    const TextureImage& t = *items[own[k]].second;
    bytes += 64 + sizeof t.to_linear + errors[k].size() + t.rgba8.size() + t.rgbaf.size() * sizeof(float);
  }
  std::vector<std::byte> mine;
  mine.reserve(bytes);
  Writer w(mine);
  for (size_t k = 0; k < own.size(); ++k) {
    w.value(uint8_t(errors[k].empty() ? 1 : 0));
    if (!errors[k].empty()) {
      w.value(uint64_t(errors[k].size()));
      w.raw(errors[k].data(), errors[k].size());
    } else {
      write_image(w, *items[own[k]].second);
    }
  }
  const std::vector<std::vector<std::byte>> all = share->exchange(std::move(mine));
  if (all.size() != parts) throw std::logic_error("decode_textures: the exchange lost parts");
  std::vector<Reader> readers;
  for (const std::vector<std::byte>& bytes : all) readers.emplace_back(bytes);
  for (size_t j = 0; j < items.size(); ++j) {  // in item order: the first failure is every part's
    const size_t p = j % parts;
    if (p == part) {  // decoded here: the image is in place
      if (!errors[j / parts].empty()) throw Error(errors[j / parts]);
      continue;
    }
    Reader& r = readers[p];
    if (r.value<uint8_t>() == 1) {
      read_image(r, *items[j].second);
      continue;
    }
    std::string message(size_t(r.value<uint64_t>()), '\0');
    r.raw(message.data(), message.size());
    throw Error(message);
  }
}

}  // namespace rayform
