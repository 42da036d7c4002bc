#include "rayform/distributed/frame_spread_ranks.h"

#include "rayform/base/error.h"
#include "rayform/distributed/distributed_frame.h"
#include "rayform/distributed/rank_work_share.h"
#include "rayform/distributed/ranks.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rayform::distributed {
namespace {

// The ranks of a spread frame read one file before any shared work: a large
// OBJ's parse is exchanged among them, and a rank that could not open the
// file (a path missing on its node) or read another copy would leave the
// others waiting in that exchange. Each rank gives the file's size (or
// -errno when it cannot open it) and whether it has loaded the scene so far
// (one gather, the gate); unless all sizes agree, every rank fails, rank 0
// naming the first rank that differs.
//
// The gate comes as late as it can, so that the work before it overlaps
// MPI's start (ranks.h; a course scene loads in a millisecond, MPI takes
// tens of milliseconds to start, more when the machine is busy): before the
// first exchange of the load or of prepare (a large OBJ's parse, a shared BVH
// build, the textures' decoding), at once after a load that failed, or else
// when the ranks agree that the scene is ready. A rank that failed its load
// passes the gate with its flag down and prepares nothing; the others learn
// it there (their exchange throws LoadFailedElsewhere) or at the readiness
// agreement. Every rank makes one gate, then the same collectives.
class InputGate {
 public:
  explicit InputGate(std::string input) : input_(std::move(input)) {
    if (const int fd = ::open(input_.c_str(), O_RDONLY | O_CLOEXEC); fd < 0) {
      seen_ = -errno;
    } else {
      struct stat st {};
      seen_ = ::fstat(fd, &st) == 0 ? (long long)st.st_size : -errno;
      ::close(fd);
    }
  }

  bool passed() const { return passed_; }
  // Whether every rank had loaded the scene (or was still loading) at the gate.
  bool all_loaded() const { return all_loaded_; }

  // Collective, the first time: throws when the ranks read different files.
  void pass(bool loaded) {
    if (std::exchange(passed_, true)) return;
    // The size and the flag in one number: 2 * size + flag.
    const std::vector<long long> all = gather_numbers(seen_ * 2 + (loaded ? 1 : 0));
    auto size = [](long long v) { return (v - (v & 1)) / 2; };
    all_loaded_ = std::all_of(all.begin(), all.end(), [](long long v) { return (v & 1) != 0; });
    const auto other = std::find_if(all.begin(), all.end(), [&](long long v) { return size(v) != size(all[0]); });
    if (other == all.end()) return;
    auto what = [](long long s) {
      return s < 0 ? std::string("cannot open it (") + std::strerror(int(-s)) + ")"
                   : "reads " + std::to_string(s) + " bytes";
    };
    if (!ranks().root()) throw ReportedElsewhere("rank 0 reports the error");
    throw Error(input_ + ": rank " + std::to_string(other - all.begin()) + " of the MPI job " + what(size(*other)) +
                ", rank 0 " + what(size(all[0])) + ": every rank must read the same file; nothing written");
  }

 private:
  std::string input_;
  long long seen_ = 0;
  bool passed_ = false;
  bool all_loaded_ = true;
};

// Thrown by an exchange of a rank that loaded the scene when another did not.
struct LoadFailedElsewhere : std::runtime_error {
  LoadFailedElsewhere() : std::runtime_error("another rank could not load the scene") {}
};

class RankFrameSpread final : public FrameSpread {
 public:
  RankFrameSpread(const std::string& input, bool stats) : gate_(input), stats_(stats) {
    share_ = rank_work_share();
    share_.exchange = [exchange = share_.exchange, this](std::vector<std::byte> mine) {
      gate_.pass(/*loaded*/ true);  // so far
      if (!gate_.all_loaded()) throw LoadFailedElsewhere();
      return exchange(std::move(mine));
    };
  }

  bool writer() const override { return ranks().root(); }

  const WorkShare& work_share() override { return share_; }

  std::exception_ptr after_load(std::exception_ptr failure) override {
    if (!failure || gate_.passed()) return failure;  // a rank that loaded passes the gate later
    try {
      gate_.pass(/*loaded*/ false);  // a different file is the cause, when it is one
    } catch (...) {
      return std::current_exception();
    }
    return failure;
  }

  // Without a collective unless the gate was passed during the load: a rank
  // that loaded the scene goes on to prepare, and learns at the gate whether
  // every other did.
  bool all_loaded(bool ok) override {
    if (!gate_.passed()) return ok;
    if (!gate_.all_loaded()) return false;
    const std::vector<bool> loaded = gather_flags(ok);
    return std::find(loaded.begin(), loaded.end(), false) == loaded.end();
  }

  // Every rank has loaded and prepared the scene, or none goes on: a rank
  // that failed reports its error when rank 0 did not fail (rank 0 reports
  // its own; the others would say the same), rank 0 says that another
  // failed, and every rank stops with status 1.
  void agree_ready(std::exception_ptr failure) override {
    if (!gate_.passed()) {
      try {
        gate_.pass(/*loaded*/ true);
      } catch (...) {
        failure = std::current_exception();
      }
    }
    if (failure) {
      try {
        std::rethrow_exception(failure);
      } catch (const LoadFailedElsewhere&) {
        failure = nullptr;  // this rank is ready; the one that failed says why
      } catch (...) {
      }
    }
    const std::vector<bool> ok = gather_flags(!failure);
    const Ranks& r = ranks();
    if (failure && r.root()) std::rethrow_exception(failure);
    if (failure && ok[0]) {
      try {
        std::rethrow_exception(failure);
      } catch (const std::exception& e) {
        throw Error("rank " + std::to_string(r.rank) + ": " + e.what());  // printed by main on any rank
      }
    }
    if (failure) throw ReportedElsewhere("rank 0 reports the error");
    if (std::find(ok.begin(), ok.end(), false) == ok.end()) return;
    const int other = int(std::find(ok.begin(), ok.end(), false) - ok.begin());
    if (r.root())
      throw Error("rank " + std::to_string(other) +
                  " of the MPI job could not load or prepare the scene (its message "
                  "above): nothing written");
    throw ReportedElsewhere("another rank failed");
  }

  RenderResult render(const PreparedScene& scene, const RenderOptions& options) override {
    tiles_ = tile_grid(options).count();
    return render_frame_over_ranks(scene, options, &share_of_frame_);
  }

  // Each rank's share, so that imbalance shows (before rank 0 writes: the
  // others wait for nothing after this).
  void after_render(double load_s, double prepare_s) override {
    if (!stats_) return;
    const Ranks& r = ranks();
    const FrameShare& s = share_of_frame_;
    std::ostringstream line;
    line << "stats: rank " << r.rank << " of " << r.size << ": " << s.tiles << " of " << tiles_ << " tiles, load "
         << load_s << " s, prepare " << prepare_s << " s, render " << s.render_s << " s (CPU " << s.render_cpu_s
         << " s), gather " << s.gather_s << " s\n";
    for (const std::string& text : gather_text(line.str())) std::cerr << text;
  }

 private:
  InputGate gate_;
  bool stats_;
  WorkShare share_;
  FrameShare share_of_frame_;
  int tiles_ = 0;
};

}  // namespace

std::unique_ptr<FrameSpread> spread_frame_over_ranks(const std::string& input, bool stats) {
  return std::make_unique<RankFrameSpread>(input, stats);
}

}  // namespace rayform::distributed
