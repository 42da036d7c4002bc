// Image writing times (scripts and docs/performance.md "Writing images"):
// rayform_write_image_bench IMAGE [ROUNDS] [OUT_FOLDER] [ONLY]
// IMAGE (a rendered frame, PNG) is read once; each round then times, one after
// another (interleaved, so that load changes hit every variant alike):
//   png-stb          stb_image_write's PNG encoder (the writer before png_writer.h), in memory
//   png-tN           encode_png on N threads (limit_threads), in memory
//   png-file-tN      write_png: encode, write, fsync, close (checked_write.h)
//   png-nosync-tN    the same bytes written and closed without fsync
//   exr-tN           write_image_temporary to .exr (exr_writer.h), renamed into place
//   exr-lL-tN        encode_exr at libdeflate level L, in memory
//   exr-oiio-tN      OpenImageIO's writer (the writer before exr_writer.h), its fsync included
// IMAGE may be an .exr (a float render; its PNG is then the sRGB-quantised
// values, as the renderer writes them) or an 8-bit PNG (its EXR then v / 255).
// and prints the median wall time of each (ms, Mpixel/s) and the median CPU
// time of the process (all threads). N is 1 and 2. ONLY: the variants whose
// name contains it.
#include "rayform/base/thread_limit.h"
#include "rayform/image/checked_write.h"
#include "rayform/image/exr_writer.h"
#include "rayform/image/image.h"
#include "rayform/image/oiio_plugin.h"
#include "rayform/image/png_writer.h"
#include "rayform/image/quantize.h"
#include "rayform/render/color_output.h"

#include <stb_image_write.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

using namespace rayform;

namespace {
double seconds(const std::function<void()>& f) {
  const auto t = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// User and system time of the whole process (every thread), in seconds.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void write_without_sync(const std::string& path, const std::vector<uint8_t>& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0 || ::write(fd, bytes.data(), bytes.size()) != ssize_t(bytes.size()) || ::close(fd) != 0)
    std::perror(path.c_str());
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s IMAGE [ROUNDS] [OUT_FOLDER] [ONLY]\n", argv[0]);
    return 2;
  }
  const int rounds = argc > 2 ? std::max(1, std::atoi(argv[2])) : 11;
  const std::string out = argc > 3 ? argv[3] : std::filesystem::temp_directory_path().string();
  const std::string only = argc > 4 ? argv[4] : "";  // runs only the variants whose name holds this
  const DecodedImage decoded = read_image_file(argv[1]);
  const Image floats = to_float_image(decoded);
  Image8 img{decoded.width, decoded.height, decoded.channels, decoded.bytes};
  if (decoded.bits != 8) {
    img.pixels.resize(floats.pixels.size());
    const SrgbQuantizer& q = srgb_quantizer();
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = q(floats.pixels[i]);
  }
  const double mpixels = double(img.width) * img.height / 1e6;

  struct Variant {
    std::string name;
    std::function<size_t()> run;  // returns the file's size
    std::vector<double> wall = {}, cpu = {};
    size_t size = 0;
  };
  std::vector<Variant> variants;
  std::string error;
  const std::string png = out + "/rayform_write_bench.png", exr = out + "/rayform_write_bench.exr";
  variants.push_back({"png-stb", [&] {
                        std::vector<uint8_t> bytes;
                        auto append = [](void* context, void* data, int size) {
                          auto* o = static_cast<std::vector<uint8_t>*>(context);
                          o->insert(o->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
                        };
                        stbi_write_png_to_func(append, &bytes, img.width, img.height, img.channels, img.pixels.data(),
                                               img.width * img.channels);
                        return bytes.size();
                      }});
  for (int threads : {1, 2}) {
    const std::string t = "-t" + std::to_string(threads);
    auto bounded = [threads](std::function<size_t()> f) {
      return [threads, f] {
        const auto bound = limit_threads(threads);
        return f();
      };
    };
    variants.push_back({"png" + t, bounded([&] { return encode_png(img).size(); })});
    variants.push_back({"png-file" + t, bounded([&] {
                          if (!write_png(png, img, &error))
                            std::fprintf(stderr, "%s: %s\n", png.c_str(), error.c_str());
                          return size_t(std::filesystem::file_size(png));
                        })});
    variants.push_back({"png-nosync" + t, bounded([&] {
                          write_without_sync(png, encode_png(img));
                          return size_t(std::filesystem::file_size(png));
                        })});
    for (int level : {1, 2, 4, 6}) {
      ExrOptions options;
      options.level = level;
      variants.push_back(
          {"exr-l" + std::to_string(level) + t, bounded([&, options] { return encode_exr(floats, options).size(); })});
    }
    variants.push_back({"exr" + t, bounded([&] {
                          commit_temporary(write_image_temporary(exr, floats), exr);
                          return size_t(std::filesystem::file_size(exr));
                        })});
    variants.push_back({"exr-oiio" + t, bounded([&] {
                          if (!oiio_write(exr, exr, floats, &error))
                            std::fprintf(stderr, "%s: %s\n", exr.c_str(), error.c_str());
                          return size_t(std::filesystem::file_size(exr));
                        })});
  }
  if (!only.empty())
    variants.erase(std::remove_if(variants.begin(), variants.end(),
                                  [&](const Variant& v) { return v.name.find(only) == std::string::npos; }),
                   variants.end());
  oiio_write(exr, exr, floats, &error);  // loads OpenImageIO once, outside the timings
  for (int r = 0; r < rounds; ++r)
    for (Variant& v : variants) {
      const double cpu0 = cpu_seconds();
      v.wall.push_back(seconds([&] { v.size = v.run(); }));
      v.cpu.push_back(cpu_seconds() - cpu0);
    }
  std::printf("%s: %dx%dx%d, %d rounds; medians of wall time and of process CPU time\n", argv[1], img.width, img.height,
              img.channels, rounds);
  for (Variant& v : variants) {
    std::sort(v.wall.begin(), v.wall.end());
    std::sort(v.cpu.begin(), v.cpu.end());
    const double wall = v.wall[v.wall.size() / 2], cpu = v.cpu[v.cpu.size() / 2];
    std::printf("%-14s wall %7.1f ms %6.1f Mpixel/s  cpu %7.1f ms  %9zu bytes\n", v.name.c_str(), wall * 1e3,
                mpixels / wall, cpu * 1e3, v.size);
  }
  return 0;
}
