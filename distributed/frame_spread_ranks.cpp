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
#include <utility>
#include <vector>

namespace rayform::distributed {
namespace {

// The ranks of a spread frame read one file before any shared work: a large
// OBJ's parse is exchanged among them, and a rank that could not open the
// file (a path missing on its node) or read another copy would leave the
// others waiting in that exchange. Each rank gives the file's size (or
// -errno when it cannot open it); unless all agree, every rank fails its
// load, rank 0 naming the first rank that differs. Ranks that all fail alike
// go on to the load, which fails on each before any exchange and says why.
//
// The agreement comes as late as it can: before the load's first exchange,
// or after the load when it makes none (agree() is called at both places and
// acts once), so that what comes before (mapping the file, scanning a large
// OBJ's chunks) overlaps MPI's start (ranks.h). A rank whose load fails
// before its first exchange agrees after it, as every rank then does.
class InputAgreement {
 public:
  explicit InputAgreement(std::string input) : input_(std::move(input)) {
    if (const int fd = ::open(input_.c_str(), O_RDONLY | O_CLOEXEC); fd < 0) {
      seen_ = -errno;
    } else {
      struct stat st {};
      seen_ = ::fstat(fd, &st) == 0 ? (long long)st.st_size : -errno;
      ::close(fd);
    }
  }

  // Collective, the first time.
  void agree() {
    if (std::exchange(agreed_, true)) return;
    const std::vector<long long> all = gather_numbers(seen_);
    const auto other = std::find_if(all.begin(), all.end(), [&](long long s) { return s != all[0]; });
    if (other == all.end()) return;
    auto what = [](long long s) {
      return s < 0 ? std::string("cannot open it (") + std::strerror(int(-s)) + ")"
                   : "reads " + std::to_string(s) + " bytes";
    };
    if (!ranks().root()) throw ReportedElsewhere("rank 0 reports the error");
    throw Error(input_ + ": rank " + std::to_string(other - all.begin()) + " of the MPI job " + what(*other) +
                ", rank 0 " + what(all[0]) + ": every rank must read the same file; nothing written");
  }

 private:
  std::string input_;
  long long seen_ = 0;
  bool agreed_ = false;
};

class RankFrameSpread final : public FrameSpread {
 public:
  RankFrameSpread(const std::string& input, bool stats) : input_(input), stats_(stats) {
    share_ = rank_work_share();
    share_.exchange = [exchange = share_.exchange, this](std::vector<std::byte> mine) {
      input_.agree();
      return exchange(std::move(mine));
    };
  }

  bool writer() const override { return ranks().root(); }

  const WorkShare& work_share() override { return share_; }

  std::exception_ptr after_load(std::exception_ptr failure) override {
    try {
      input_.agree();  // a different file is the cause, when it is one
    } catch (...) {
      return std::current_exception();
    }
    return failure;
  }

  bool all_loaded(bool ok) override {
    const std::vector<bool> loaded = gather_flags(ok);
    return std::find(loaded.begin(), loaded.end(), false) == loaded.end();
  }

  // Every rank has loaded and prepared the scene, or none goes on: a rank
  // that failed reports its error when rank 0 did not fail (rank 0 reports
  // its own; the others would say the same), rank 0 says that another
  // failed, and every rank stops with status 1.
  void agree_ready(std::exception_ptr failure) override {
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
  InputAgreement input_;
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
