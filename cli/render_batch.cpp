#include "render_batch.h"

#include "course_args.h"
#include "messages.h"
#include "output_names.h"
#include "rayform/distributed/ranks.h"
#include "rayform/distributed/work_counter.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

namespace rayform::cli {
namespace fs = std::filesystem;

BatchJobs::BatchJobs(const RenderJob& job, const std::vector<std::string>& inputs, const Turntable& turntable)
    : job_(job), turntable_(turntable), frames_(std::max(1, turntable.frames)) {
  if (inputs.size() > 1 && !has_placeholder(job.output, "stem"))
    throw UsageError("-o " + job.output + ": several inputs need {stem} in the output name, e.g. 'out/{stem}.png'");
  if (turntable.frames > 1 && !has_placeholder(job.output, "frame"))
    throw UsageError("-o " + job.output + ": --frames needs {frame} in the output name, e.g. 'spin_{frame}.png'");
  // Largest first: the longest renders start early and the short ones fill
  // the gaps at the end (a missing file counts as empty; it fails at once).
  std::vector<std::pair<uintmax_t, std::string>> sized;
  for (const std::string& in : inputs) {
    std::error_code ec;
    const uintmax_t size = fs::file_size(in, ec);
    sized.emplace_back(ec ? 0 : size, in);
  }
  std::stable_sort(sized.begin(), sized.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (const auto& sized_input : sized) inputs_.push_back(sized_input.second);
  // Every output of the first and the last frame of every input, once.
  for (const long long frame : frames_ > 1 ? std::vector<long long>{0, frames_ - 1} : std::vector<long long>{0}) {
    std::map<std::string, std::string> written;  // output -> the input writing it
    for (size_t k = 0; k < inputs_.size(); ++k) {
      const RenderJob j = (*this)[(long long)k * frames_ + frame];
      auto check = [&](const std::string& path, const char* option) {
        if (path.empty()) return;
        auto [at, fresh] = written.emplace(path, j.input);
        if (!fresh)
          throw UsageError(std::string(option) + ": " + at->second + " and " + j.input + " would both write " + path);
      };
      check(j.output, "-o");
      if (j.depth) check(j.depth->file, "--depth");
      check(j.normals, "--normals");
      check(j.albedo, "--albedo");
    }
  }
}

RenderJob BatchJobs::operator[](long long i) const {
  const std::string& input = inputs_[size_t(i / frames_)];
  const int frame = int(i % frames_);
  RenderJob j = job_;
  j.input = input;
  auto expand = [&](std::string& path, const char* option) {
    if (!path.empty()) path = expand_output_name(path, input, frame, option);
  };
  expand(j.output, "-o");
  if (j.depth) expand(j.depth->file, "--depth");
  expand(j.normals, "--normals");
  expand(j.albedo, "--albedo");
  if (turntable_.frames > 0) {
    Orbit o = job_.orbit.value_or(Orbit{});
    o.azimuth_deg += float(frame) * turntable_.sweep_deg / float(turntable_.frames);
    j.orbit = o;
  }
  return j;
}

int run_render_batch(const BatchJobs& jobs, bool turntable, const Reporting& reporting) {
  using clock = std::chrono::steady_clock;
  const distributed::Ranks& r = distributed::ranks();
  const auto start = clock::now();
  long long done = 0, failed = 0;
  double busy_s = 0.0;
  {
    distributed::WorkCounter counter;
    // The scene of this rank's last turntable frame: the next frame of the
    // same file starts from it instead of reading the file again.
    std::shared_ptr<const LoadedScene> last;
    std::shared_ptr<MeshAccelCache> last_accels;  // its meshes' BVHs, kept from frame to frame
    std::string last_input;
    for (long long i; (i = counter.next()) < jobs.size();) {
      RenderJob job = jobs[i];
      const auto t = clock::now();
      try {
        if (job.orbit && turntable) {
          if (!last || last_input != job.input) {
            last_accels.reset();
            last.reset();  // one scene in memory at a time
            last = std::make_shared<const LoadedScene>(load_job_scene(job));
            last_accels = std::make_shared<MeshAccelCache>();
            last_accels->source = &last->scene;
            last_input = job.input;
          }
          job.preloaded = last;
          job.mesh_cache = last_accels;
        }
        run_job(job, reporting, false);
        ++done;
      } catch (const std::exception& e) {
        // One line naming the input (the readers' messages start with it),
        // written at once so that mpirun does not mix it with another rank's.
        const std::string what = e.what();
        std::cerr << "rayform: error: " +
                         terminal_text((what.rfind(job.input, 0) == 0 ? "" : job.input + ": ") + what) + "\n"
                  << std::flush;
        ++failed;
      }
      busy_s += std::chrono::duration<double>(clock::now() - t).count();
    }
  }  // the counter's window is freed together, once every rank has taken its last number
  const long long failed_total = distributed::sum_over_ranks(failed);
  const double wall_s = std::chrono::duration<double>(clock::now() - start).count();
  if (reporting.stats) {
    std::ostringstream line;
    line << "stats: rank " << r.rank << " of " << r.size << ": " << done + failed << " renders (" << failed
         << " failed), busy " << busy_s << " s of " << wall_s << " s\n";
    for (const std::string& text : distributed::gather_text(line.str())) std::cerr << text;
  }
  if (failed_total > 0 && r.root())
    std::cerr << "rayform: " << failed_total << " of " << jobs.size() << " renders failed\n";
  return failed_total > 0 ? 1 : 0;
}

}  // namespace rayform::cli
