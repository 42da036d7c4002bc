// Writes the benchmarks' procedural bumpy torus (make_bumpy_torus(TRIANGLES, 1))
// as a plain OBJ file, `v` and `f` lines only, for scripts/bench-process.
// Coordinates are written shortest round-trip (std::to_chars), so reading the
// file back gives the very same floats. Written to OUT.obj.tmp, then renamed.
//
// usage: rayform_write_torus_obj TRIANGLES OUT.obj
#include "rayform/scene/procedural_mesh.h"

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

using namespace rayform;

namespace {

// Appends text to a 4 MiB buffer, written out whenever it fills up.
class Writer {
 public:
  explicit Writer(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "wb")) {
    if (!f_) throw std::runtime_error(path + ": cannot open for writing");
    buf_.resize(size_t(4) << 20);
  }
  ~Writer() {
    if (f_) std::fclose(f_);
  }
  // Room for one line (at most 3 numbers of 16 characters and a few more).
  char* line() {
    if (buf_.size() - used_ < 128) flush();
    return buf_.data() + used_;
  }
  void done(char* end) { used_ = size_t(end - buf_.data()); }
  void close() {
    flush();
    if (std::fclose(f_) != 0) throw std::runtime_error(path_ + ": cannot write");
    f_ = nullptr;
  }

 private:
  void flush() {
    if (std::fwrite(buf_.data(), 1, used_, f_) != used_) throw std::runtime_error(path_ + ": cannot write");
    used_ = 0;
  }
  std::string path_;
  std::FILE* f_;
  std::vector<char> buf_;
  size_t used_ = 0;
};

template <typename T>
char* put(char* p, T value) {
  *p++ = ' ';
  return std::to_chars(p, p + 32, value).ptr;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc != 3) {
      std::fprintf(stderr, "usage: rayform_write_torus_obj TRIANGLES OUT.obj\n");
      return 2;
    }
    const Mesh m = make_bumpy_torus(std::strtoull(argv[1], nullptr, 10), 1);
    const std::string out = argv[2], tmp = out + ".tmp";
    Writer w(tmp);
    for (const vec3& v : m.positions) {
      char* p = w.line();
      *p++ = 'v';
      p = put(put(put(p, v.x), v.y), v.z);
      *p++ = '\n';
      w.done(p);
    }
    for (size_t t = 0; t < m.indices.size(); t += 3) {
      char* p = w.line();
      *p++ = 'f';
      for (int k = 0; k < 3; ++k) p = put(p, m.indices[t + k] + 1);  // OBJ counts from 1
      *p++ = '\n';
      w.done(p);
    }
    w.close();
    std::filesystem::rename(tmp, out);
    std::fprintf(stderr, "%s: %zu vertices, %zu triangles\n", out.c_str(), m.positions.size(), m.triangle_count());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rayform_write_torus_obj: %s\n", e.what());
    return 1;
  }
}
