// The chunked OBJ parse shared among parts (obj_parallel_parse.h with a
// WorkShare): 2 and 3 parts, each a thread of this process exchanging through
// shared slots, give every part the result of the parse alone and of one
// LoadObj over the whole text, field by field; what falls back falls back
// on every part, and what throws on one part throws on all (none is left
// waiting in the exchange).
#include "importers/obj_test_texts.h"
#include "test_work_share.h"
#include "rayform/importers/obj/obj_parallel_parse.h"
#include "rayform/base/error.h"
#include "rayform/base/work_share.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace rayform {
namespace {

using test::NoMaterials;
using test::ThreadExchange;

struct PartResult {
  bool chunked = false;
  std::string error;  // what parse_obj_chunked threw
  ObjParse parse;
  int exchanges = 0;
};

// Every part's parse of `text` in chunks of `chunk_bytes`, each on a thread
// of its own; `readers(part)` makes that part's material readers.
template <class Readers>
std::vector<PartResult> parse_shared(const std::string& text, size_t chunk_bytes, int parts, Readers readers) {
  ThreadExchange exchange(parts);
  std::vector<PartResult> results{size_t(parts)};
  std::vector<WorkShare> shares;
  for (int p = 0; p < parts; ++p) shares.push_back(exchange.share(p));
  {
    std::vector<std::jthread> threads;
    for (int p = 0; p < parts; ++p)
      threads.emplace_back([&, p] {
        PartResult& r = results[size_t(p)];
        try {
          r.chunked = parse_obj_chunked(text, readers(p), chunk_bytes, &r.parse, &shares[size_t(p)]);
        } catch (const Error& e) {
          r.error = e.what();
        }
      });
  }
  for (int p = 0; p < parts; ++p) results[size_t(p)].exchanges = exchange.calls(p);
  return results;
}

MaterialReaderFactory no_materials() {
  return [] { return std::make_unique<NoMaterials>(); };
}

std::vector<PartResult> parse_shared(const std::string& text, size_t chunk_bytes, int parts) {
  return parse_shared(text, chunk_bytes, parts, [](int) { return no_materials(); });
}

// The text shared among 2 and 3 parts in chunks of each size: every part
// returns what the parse alone returns and, where that parsed, its ObjParse
// field by field, which is also one LoadObj's (its warnings aside: the
// reader keeps each once). The exchanges each part made: `exchanges` (the
// scans', then the parses' unless the scans fall back).
void expect_shared_same(const std::string& text, const std::vector<size_t>& chunk_sizes, bool chunked,
                        int exchanges = 2) {
  const ObjParse whole = test::load_obj_whole(text);
  for (size_t chunk : chunk_sizes) {
    ObjParse alone;
    ASSERT_EQ(parse_obj_chunked(text, no_materials(), chunk, &alone), chunked) << "chunks of " << chunk;
    for (int parts : {2, 3}) {
      const std::vector<PartResult> results = parse_shared(text, chunk, parts);
      for (int p = 0; p < parts; ++p) {
        const std::string what =
            "part " + std::to_string(p) + " of " + std::to_string(parts) + ", chunks of " + std::to_string(chunk);
        const PartResult& r = results[size_t(p)];
        EXPECT_EQ(r.error, "") << what;
        EXPECT_EQ(r.exchanges, exchanges) << what;
        ASSERT_EQ(r.chunked, chunked) << what;
        if (!chunked) continue;
        test::expect_same_shapes(alone, r.parse, what + " vs alone");
        test::expect_same_vertices(alone, r.parse, what + " vs alone");
        EXPECT_EQ(alone.warn, r.parse.warn) << what;
        test::expect_same_shapes(whole, r.parse, what + " vs LoadObj");
        test::expect_same_vertices(whole, r.parse, what + " vs LoadObj");
      }
    }
  }
}

TEST(ObjSharedParse, TrianglesGroupsAndMaterialsAcrossChunkEnds) {
  const std::string text = test::grid_file(9, true);  // o/g/usemtl/s lines every few faces
  expect_shared_same(text, {1, 16, 100, 1000, text.size() / 3, text.size()}, true);
  expect_shared_same("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 1 1 0 0.5 0.5 0.5\nf 1 2 3\nf 2 4 3\n", {1, 8},
                     true);  // vertex colours
}

TEST(ObjSharedParse, QuadsAndPolygons) {
  const std::string text = test::polygon_file(9);
  expect_shared_same(text, {1, 97, 300, 4096}, true);
}

TEST(ObjSharedParse, FallsBackOnEveryPart) {
  const std::string head = "mtllib m.mtl\n" + test::grid_attributes(3);
  // The scans find it: every part falls back after their exchange, before any parse.
  expect_shared_same(head + "f -9 -8 -6\nf 1 2 3\n", {16}, false, /*exchanges*/ 1);
  // Found once the chunks are parsed: after the exchange, alike on every part.
  expect_shared_same(head + "usemtl red\nf 1 2 5 10\nv 9 9 9\nusemtl green\nf 1 2 3\n", {16}, false);
}

// A long text whose last face is bad: only one part's chunks hold it.
TEST(ObjSharedParse, BadFaceInOnePartsChunks) {
  const std::string grid = test::grid_file(12, false);
  // An index past the last vertex: found when the chunks are joined.
  expect_shared_same(grid + "f 1 2 999999\n", {64, 1000}, false);
  // Index 0: LoadObj fails on that one chunk, and every part falls back.
  const std::string zero = grid + "f 0 1 2\n";
  ObjParse alone;
  ASSERT_FALSE(parse_obj_chunked(zero, no_materials(), 64, &alone));
  for (int parts : {2, 3}) {
    const std::vector<PartResult> results = parse_shared(zero, 64, parts);
    for (int p = 0; p < parts; ++p) {
      EXPECT_FALSE(results[size_t(p)].chunked) << "part " << p << " of " << parts;
      EXPECT_EQ(results[size_t(p)].exchanges, 2) << "part " << p << " of " << parts;
    }
  }
}

// A part whose chunk parse throws: every part throws its message after the
// exchange (none is left waiting for it).
TEST(ObjSharedParse, ThrowOnOnePartThrowsOnEvery) {
  const std::string text = test::grid_file(12, false);
  for (int parts : {2, 3}) {
    const int failing = parts - 1;
    const std::vector<PartResult> results = parse_shared(text, 256, parts, [&](int p) -> MaterialReaderFactory {
      if (p != failing) return no_materials();
      return []() -> std::unique_ptr<tinyobj::MaterialReader> { throw std::runtime_error("no reader here"); };
    });
    for (int p = 0; p < parts; ++p) {
      const PartResult& r = results[size_t(p)];
      EXPECT_EQ(r.exchanges, 2) << "part " << p << " of " << parts;
      EXPECT_NE(r.error.find("part " + std::to_string(failing) + " failed: no reader here"), std::string::npos)
          << "part " << p << " of " << parts << ": " << r.error;
    }
  }
}

// A part whose scan fails (it sends what a part that threw sends): every
// part throws after the scans' exchange, and none parses.
TEST(ObjSharedParse, ScanFailingOnOnePartThrowsOnEvery) {
  const std::string text = test::grid_file(12, false);
  for (int parts : {2, 3}) {
    const int failing = parts - 1;
    ThreadExchange exchange(parts);
    std::vector<std::string> errors(static_cast<size_t>(parts));
    {
      std::vector<std::jthread> threads;
      for (int p = 0; p < parts; ++p)
        threads.emplace_back([&, p] {
          const WorkShare share = exchange.share(p, failing);
          ObjParse out;
          try {
            parse_obj_chunked(text, no_materials(), 256, &out, &share);
          } catch (const Error& e) {
            errors[size_t(p)] = e.what();
          }
        });
    }
    for (int p = 0; p < parts; ++p) {
      EXPECT_EQ(exchange.calls(p), 1) << "part " << p << " of " << parts;
      EXPECT_EQ(errors[size_t(p)], "scanning OBJ text in chunks: part " + std::to_string(failing) + " failed")
          << "part " << p << " of " << parts;
    }
  }
}

// Bytes that do not parse are a bug, reported as an error on every part,
// not read past: part 1's bytes cut short, in the scans' exchange (0) or
// the parses' (1).
TEST(ObjSharedParse, CorruptBytesAreAnError) {
  const std::string text = test::grid_file(6, false);
  for (int stage : {0, 1})
    for (size_t cut : {size_t(1), size_t(9), size_t(100)}) {
      ThreadExchange exchange(2);
      std::vector<WorkShare> shares{exchange.share(0), exchange.share(1)};
      int calls = 0;
      shares[1].exchange = [&, inner = shares[1].exchange](std::vector<std::byte> mine) {
        if (calls++ == stage) mine.resize(mine.size() > cut ? mine.size() - cut : 0);
        return inner(std::move(mine));
      };
      std::vector<std::string> errors(2);
      {
        std::vector<std::jthread> threads;
        for (int p = 0; p < 2; ++p)
          threads.emplace_back([&, p] {
            ObjParse out;
            try {
              parse_obj_chunked(text, no_materials(), 64, &out, &shares[size_t(p)]);
            } catch (const Error& e) {
              errors[size_t(p)] = e.what();
            }
          });
      }
      for (int p = 0; p < 2; ++p) {
        EXPECT_NE(errors[size_t(p)], "") << "part " << p << ", stage " << stage << ", cut " << cut;
        EXPECT_EQ(exchange.calls(p), stage + 1) << "part " << p << ", stage " << stage << ", cut " << cut;
      }
    }
}

}  // namespace
}  // namespace rayform
