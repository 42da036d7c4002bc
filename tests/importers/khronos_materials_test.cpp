// The Khronos glTF sample models in $RAYFORM_SHARED/assets/khronos drawn as
// the file means them (issue 30), through the command line at its default
// options: no white silhouettes, every texture kind seen, blended surfaces
// composited, glass tinted, flat models framed, punctual lights in their
// units. Each test renders a sample and, where it asks whether a field
// matters, the same sample with that field edited out (the JSON of the
// .gltf or of the .glb's first chunk), and compares the two pictures.
#include "rayform/image/image.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace rayform {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The sample's .gltf or .glb (glTF/ or glTF-Binary/ folder).
fs::path sample(const std::string& model) {
  for (const char* folder : {"glTF", "glTF-Binary"}) {
    const fs::path dir = test::shared_dir() / "assets" / "khronos" / model / folder;
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".gltf" || e.path().extension() == ".glb") return e.path();
  }
  return {};
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

uint32_t u32(const std::string& s, size_t at) {
  uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

void put_u32(std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

// A copy of the sample (its whole folder, for the side files) under `dir`,
// with `edit` applied to its JSON; returns the copy's path.
fs::path edited_copy(const fs::path& original, const fs::path& dir, const std::function<void(json&)>& edit) {
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(original.parent_path()))
    fs::copy(e.path(), dir / e.path().filename(), fs::copy_options::overwrite_existing);
  const fs::path copy = dir / original.filename();
  std::string bytes = read_bytes(original);
  std::string out;
  if (original.extension() == ".glb") {
    const uint32_t json_length = u32(bytes, 12);
    json doc = json::parse(bytes.substr(20, json_length));
    edit(doc);
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    const std::string rest = bytes.substr(20 + json_length);  // the BIN chunk, as it was
    out = "glTF";
    put_u32(out, 2);
    put_u32(out, uint32_t(12 + 8 + text.size() + rest.size()));
    put_u32(out, uint32_t(text.size()));
    put_u32(out, 0x4E4F534Au);  // "JSON"
    out += text + rest;
  } else {
    json doc = json::parse(bytes);
    edit(doc);
    out = doc.dump();
  }
  std::ofstream(copy, std::ios::binary) << out;
  return copy;
}

// Removes `key` from every material (and from pbrMetallicRoughness).
std::function<void(json&)> without(const std::string& key) {
  return [key](json& doc) {
    for (json& m : doc["materials"]) {
      m.erase(key);
      if (m.contains("pbrMetallicRoughness")) m["pbrMetallicRoughness"].erase(key);
      if (m.contains("extensions")) m["extensions"].erase(key);
    }
  };
}

// The picture `rayform render IN -o OUT.png` makes at 256x256 with `extra`
// options (RGBA when --transparent is among them).
DecodedImage render(const fs::path& in, const fs::path& out, const std::string& extra = "") {
  const std::string command = "'" + test::rayform_binary() + "' render '" + in.string() + "' -o '" + out.string() +
                              "' --size 256x256 --threads 2 -q " + extra + " 2>'" + out.string() + ".log'";
  EXPECT_EQ(std::system(command.c_str()), 0) << command << "\n" << read_bytes(out.string() + ".log");
  return read_image_file(out.string());
}

struct PixelCounts {
  double covered = 0;    // pixels a surface covers (alpha > 0; all of them without alpha)
  double white = 0;      // of those, with every channel >= 254
  double saturated = 0;  // of those, with some channel at 255
  double dark = 0;       // of those, with every channel < 8
};

PixelCounts count(const DecodedImage& image) {
  PixelCounts c;
  const int n = image.channels;
  for (size_t i = 0; i + size_t(n) <= image.bytes.size(); i += size_t(n)) {
    const uint8_t* p = &image.bytes[i];
    if (n == 4 && p[3] == 0) continue;
    c.covered += 1;
    if (p[0] >= 254 && p[1] >= 254 && p[2] >= 254) c.white += 1;
    if (p[0] == 255 || p[1] == 255 || p[2] == 255) c.saturated += 1;
    if (p[0] < 8 && p[1] < 8 && p[2] < 8) c.dark += 1;
  }
  return c;
}

// The fraction of the pixels of two pictures of the same size that differ
// by more than 8 steps (of 255) in some channel.
double changed_fraction(const DecodedImage& a, const DecodedImage& b) {
  EXPECT_EQ(a.bytes.size(), b.bytes.size());
  if (a.bytes.size() != b.bytes.size() || a.bytes.empty()) return 0;
  const size_t n = size_t(a.channels);
  double changed = 0;
  for (size_t i = 0; i < a.bytes.size(); i += n) {
    bool differs = false;
    for (size_t k = 0; k < n; ++k) differs |= std::abs(int(a.bytes[i + k]) - int(b.bytes[i + k])) > 8;
    changed += differs ? 1 : 0;
  }
  return changed / double(a.bytes.size() / n);
}

class KhronosMaterials : public ::testing::Test {
 protected:
  void SetUp() override {
    RAYFORM_REQUIRE_SHARED();
    if (!fs::is_directory(test::shared_dir() / "assets" / "khronos")) {
      if (std::getenv("CI")) FAIL() << "assets/khronos not found in " << test::shared_dir();
      GTEST_SKIP() << "assets/khronos not found in " << test::shared_dir();
    }
    dir_ = test::temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  fs::path dir_;
};

// An emissive texture is sampled: the models whose emissiveFactor is white
// are no longer white silhouettes (at most 3 % of their pixels white, at the
// default options and at 16 samples a pixel).
TEST_F(KhronosMaterials, EmissiveTexturesLeaveNoWhiteSilhouettes) {
  for (const char* model : {"MultiUVTest", "BoomBoxWithAxes", "TextureEncodingTest", "LightsPunctualLamp"}) {
    const fs::path in = sample(model);
    ASSERT_FALSE(in.empty()) << model;
    for (const char* options : {"--transparent", "--transparent --spp 16"}) {
      const PixelCounts c = count(render(in, dir_ / (std::string(model) + ".png"), options));
      ASSERT_GT(c.covered, 0) << model;
      std::printf("%s %s: %.4f of the model's pixels white\n", model, options, c.white / c.covered);
      EXPECT_LT(c.white / c.covered, 0.03)
          << model << " " << options << ": " << c.white << " of " << c.covered << " model pixels are white";
    }
  }
}

// Each texture kind changes the picture: removing it from the file changes
// at least 1 % of the pixels (by more than 8 steps).
TEST_F(KhronosMaterials, NormalMetallicRoughnessAndOcclusionTexturesAreDrawn) {
  struct Case {
    const char* model;
    const char* key;
  };
  for (const Case& c :
       {Case{"NormalTangentTest", "normalTexture"}, Case{"NormalTangentMirrorTest", "normalTexture"},
        Case{"BoomBoxWithAxes", "metallicRoughnessTexture"}, Case{"NormalTangentTest", "occlusionTexture"}}) {
    const fs::path in = sample(c.model);
    ASSERT_FALSE(in.empty()) << c.model;
    const DecodedImage with = render(in, dir_ / "with.png");
    const fs::path edited = edited_copy(in, dir_ / (std::string(c.model) + "-" + c.key), without(c.key));
    const DecodedImage without_it = render(edited, dir_ / "without.png");
    const double changed = changed_fraction(with, without_it);
    std::printf("%s without its %s: %.4f of the pixels change\n", c.model, c.key, changed);
    EXPECT_GT(changed, 0.01) << c.model << " without its " << c.key;
  }
}

// AlphaBlendModeTest's BLEND materials composite: the picture is neither
// the one with those materials OPAQUE nor the one with them cut out at 0.5
// (each differs in at least 0.5 % of the pixels: the model fills a strip of
// the picture, its blended panes a tenth of that).
TEST_F(KhronosMaterials, BlendIsNeitherOpaqueNorMask) {
  const fs::path in = sample("AlphaBlendModeTest");
  ASSERT_FALSE(in.empty());
  const DecodedImage blend = render(in, dir_ / "blend.png");
  auto as = [&](const std::string& mode) {
    const fs::path edited = edited_copy(in, dir_ / mode, [&](json& doc) {
      for (json& m : doc["materials"])
        if (m.value("alphaMode", "") == "BLEND") {
          m["alphaMode"] = mode;
          if (mode == "MASK") m["alphaCutoff"] = 0.5;
        }
    });
    return render(edited, dir_ / (mode + ".png"));
  };
  const double opaque = changed_fraction(blend, as("OPAQUE")), mask = changed_fraction(blend, as("MASK"));
  std::printf("BLEND against OPAQUE: %.4f, against MASK 0.5: %.4f of the pixels differ\n", opaque, mask);
  EXPECT_GT(opaque, 0.005);
  EXPECT_GT(mask, 0.005);
}

// Glass at the default options: TransmissionTest's transmissive surfaces
// are not black (under 10 % of the model's pixels near black), and
// AttenuationTest's volumes tint what is seen through them (removing
// KHR_materials_volume changes at least 1 % of the pixels).
TEST_F(KhronosMaterials, GlassIsSeenThroughAndTinted) {
  const fs::path transmission = sample("TransmissionTest");
  ASSERT_FALSE(transmission.empty());
  const PixelCounts c = count(render(transmission, dir_ / "transmission.png", "--transparent"));
  ASSERT_GT(c.covered, 0);
  std::printf("TransmissionTest: %.4f of the model's pixels near black\n", c.dark / c.covered);
  EXPECT_LT(c.dark / c.covered, 0.10) << c.dark << " of " << c.covered << " model pixels are near black";

  const fs::path attenuation = sample("AttenuationTest");
  ASSERT_FALSE(attenuation.empty());
  const DecodedImage tinted = render(attenuation, dir_ / "attenuation.png");
  const DecodedImage clear =
      render(edited_copy(attenuation, dir_ / "no-volume", without("KHR_materials_volume")), dir_ / "clear.png");
  const double tint = changed_fraction(tinted, clear);
  std::printf("AttenuationTest without KHR_materials_volume: %.4f of the pixels change\n", tint);
  EXPECT_GT(tint, 0.01);
}

// The default camera sees a model lying in a coordinate plane: at least a
// fifth of TwoSidedPlane's picture is the plane.
TEST_F(KhronosMaterials, FlatModelIsFramed) {
  const fs::path in = sample("TwoSidedPlane");
  ASSERT_FALSE(in.empty());
  const DecodedImage image = render(in, dir_ / "plane.png", "--transparent");
  const PixelCounts c = count(image);
  std::printf("TwoSidedPlane covers %.4f of the picture\n", c.covered / (double(image.width) * image.height));
  EXPECT_GT(c.covered / (double(image.width) * image.height), 0.2);
}

// Punctual lights in candela: the lamp without its emission (the lights
// alone) is not blown out (under 20 % of its pixels saturated).
TEST_F(KhronosMaterials, LampLightsAreInPhysicalUnits) {
  const fs::path in = sample("LightsPunctualLamp");
  ASSERT_FALSE(in.empty());
  const fs::path dark = edited_copy(in, dir_ / "no-emission", [](json& doc) {
    for (json& m : doc["materials"]) {
      m.erase("emissiveFactor");
      m.erase("emissiveTexture");
      if (m.contains("extensions")) m["extensions"].erase("KHR_materials_emissive_strength");
    }
  });
  const PixelCounts c = count(render(dark, dir_ / "lamp.png", "--transparent"));
  ASSERT_GT(c.covered, 0);
  std::printf("LightsPunctualLamp without emission: %.4f of the model's pixels saturated\n", c.saturated / c.covered);
  EXPECT_LT(c.saturated / c.covered, 0.20) << c.saturated << " of " << c.covered << " model pixels saturated";
}

}  // namespace
}  // namespace rayform
