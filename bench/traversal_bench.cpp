// Traversal throughput, single thread: closest hit (intersect_mesh, and
// intersect_mesh8 on camera rays, vs rtcIntersect1) and any hit (occluded_mesh vs rtcOccluded1) on the very same
// rays and triangles, in the same process. Each iteration traces the whole
// ray set with ours and then with Embree (interleaved, so that both see the
// same machine load); thread CPU time is measured for each.
//
// Counters: ours and embree in Mrays/s, ratio = ours / embree (> 1: we are
// faster), mismatches = rays on which the two disagree (checked before timing).
#include "bench_main.h"
#include "bench_meshes.h"

using namespace rayform;
using namespace rayform::bench;

namespace {

// A ray set and how far ours and Embree agree on it (checked once, before timing).
struct RaySet {
  std::vector<Ray> rays;
  Agreement agreement;
};

struct Fixture {
  const BenchMesh* mesh = nullptr;
  MeshAccel ours;
  EmbreeScene embree;
  std::map<std::string, RaySet> ray_sets;  // by kind: "camera", "random"
};

// One mesh's structures at a time (the 10M mesh is large): benchmarks run mesh by mesh.
Fixture& get_fixture(const BenchMesh& m) {
  static std::unique_ptr<Fixture> current;
  if (current && current->mesh == &m) return *current;
  current.reset();
  current = std::make_unique<Fixture>();
  current->mesh = &m;
  current->ours = build_mesh_accel(m.vertex_span(), m.indices);
  current->embree = EmbreeScene(m, RTC_BUILD_QUALITY_MEDIUM);
  return *current;
}

const RaySet& get_ray_set(Fixture& f, const std::string& kind) {
  auto it = f.ray_sets.find(kind);
  if (it == f.ray_sets.end()) {
    RaySet s;
    s.rays = make_rays(*f.mesh, kind);
    s.agreement = compare_with_embree(f.ours, f.embree.scene, s.rays);
    it = f.ray_sets.emplace(kind, std::move(s)).first;
  }
  return it->second;
}

enum class Query { closest, closest8, any };

void bm_traversal(benchmark::State& state, std::string mesh, std::string kind, Query query) {
  const bool closest = query != Query::any;
  const BenchMesh* m = mesh_or_skip(state, mesh);
  if (!m) return;
  Fixture& f = get_fixture(*m);
  const RaySet& set = get_ray_set(f, kind);
  const std::vector<Ray>& rays = set.rays;
  const Agreement& a = set.agreement;
  size_t mismatches = closest ? a.closest_mismatches : a.any_mismatches;
  if (mismatches * 1000 > rays.size()) {
    std::string msg =
        "ours and Embree disagree on " + std::to_string(mismatches) + " of " + std::to_string(rays.size()) + " rays";
    state.SkipWithError(msg.c_str());
    return;
  }

  double ours_s = 0., embree_s = 0.;
  for (auto _ : state) {
    double t0 = thread_cpu_seconds();
    if (query == Query::closest) benchmark::DoNotOptimize(ours_closest(f.ours, rays));
    else if (query == Query::closest8) benchmark::DoNotOptimize(ours_closest8(f.ours, rays));
    else benchmark::DoNotOptimize(ours_any(f.ours, rays));
    double t1 = thread_cpu_seconds();
    if (closest) benchmark::DoNotOptimize(embree_closest(f.embree.scene, rays));
    else benchmark::DoNotOptimize(embree_any(f.embree.scene, rays));
    double t2 = thread_cpu_seconds();
    ours_s += t1 - t0;
    embree_s += t2 - t1;
    state.SetIterationTime(t1 - t0);
  }
  double n = double(rays.size()) * double(state.iterations());
  double ours = n / ours_s * 1e-6, emb = n / embree_s * 1e-6;
  state.counters["ours"] = ours;
  state.counters["embree"] = emb;
  state.counters["ratio"] = ours / emb;
  state.counters["mismatches"] = double(mismatches);
  state.counters["rays"] = double(rays.size());
  state.counters["hit_fraction"] = double(a.hits) / double(rays.size());
  state.counters["triangles"] = double(m->triangle_count());
  state.SetLabel("Mrays/s");
}

}  // namespace

int main(int argc, char** argv) {
  for_each_mesh([](const std::string& mesh) {
    for (const char* kind : {"camera", "random"})
      for (Query q : {Query::closest, Query::closest8, Query::any}) {
        if (q == Query::closest8 && std::string(kind) != "camera") continue;  // packets are for coherent rays
        const char* name = q == Query::closest ? "closest/" : q == Query::closest8 ? "closest8/" : "any/";
        register_manual_ms(std::string("traversal/") + name + kind + "/" + mesh, bm_traversal, mesh, std::string(kind),
                           q);
      }
  });
  return run_benchmarks(argc, argv);
}
