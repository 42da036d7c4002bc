// What the benchmark programs' main() functions share: registration over the
// benchmark meshes, the usual timing setup, and running what was registered.
#pragma once

#include "bench_meshes.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <utility>

namespace rayform::bench {

// Calls register_mesh(name) for every benchmark mesh, first noting on stderr
// why a mesh is unavailable (its benchmarks are still registered and report
// the same reason as an error).
template <class F>
void for_each_mesh(F&& register_mesh) {
  for (const std::string& mesh : mesh_names()) {
    std::string why = mesh_unavailable(mesh);
    if (!why.empty()) std::fprintf(stderr, "%s: %s\n", mesh.c_str(), why.c_str());
    register_mesh(mesh);
  }
}

// Registers fn(state, args...) as a benchmark that sets its own iteration
// time (state.SetIterationTime), reported in milliseconds.
template <class Fn, class... Args>
benchmark::internal::Benchmark* register_manual_ms(const std::string& name, Fn&& fn, Args&&... args) {
  return benchmark::RegisterBenchmark(name.c_str(), std::forward<Fn>(fn), std::forward<Args>(args)...)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
}

// The body of main() once everything is registered: parses the command line
// (--benchmark_filter and the like) and runs the selected benchmarks.
inline int run_benchmarks(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace rayform::bench
