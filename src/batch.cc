// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The batch scheduler (batch.h): the manifest's runs of this shard, run by
// a pool of workers from the thread budget in start_from order, with the
// output directory's lock, a progress line and the summary at the end. One
// run is batch_run.cc, the summary batch_summary.cc.

#include "fit3dof/batch.h"

#include <fcntl.h>
#include <glog/logging.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "batch_run.h"
#include "fit3dof/atomic_file.h"
#include "fit3dof/input_error.h"
#include "fit3dof/interrupt.h"
#include "fit3dof/thread_budget.h"
#include "manifest.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

std::string Clock(double seconds) {
  const int s = static_cast<int>(seconds + 0.5);
  char out[32];
  std::snprintf(
      out, sizeof(out), "%02d:%02d:%02d", s / 3600, (s / 60) % 60, s % 60);
  return out;
}

// The output directory's lock (DIR/.fit3dof.lock, holding the pid): a
// second batch into the same directory would mix two campaigns. A lock
// whose process is gone is taken over.
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::string& dir)
      : path_(dir + "/" + kBatchLockName) {
    for (int attempt = 0; attempt < 2; ++attempt) {
      const int fd =
          ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
      if (fd >= 0) {
        const std::string pid = std::to_string(::getpid()) + "\n";
        const bool written = ::write(fd, pid.data(), pid.size()) ==
                             static_cast<ssize_t>(pid.size());
        ::close(fd);
        if (!written) break;
        return;
      }
      if (errno != EEXIST) break;
      long holder = 0;
      std::ifstream(path_) >> holder;
      if (holder > 0 &&
          (::kill(static_cast<pid_t>(holder), 0) == 0 || errno == EPERM)) {
        throw InputError(dir + ": another fit3dof batch (pid " +
                         std::to_string(holder) +
                         ") is writing into this directory (lock " + path_ +
                         "); wait for it or choose another --out_dir");
      }
      LOG(WARNING) << path_ << ": taking over the lock of pid " << holder
                   << ", which is gone";
      ::unlink(path_.c_str());
    }
    throw InputError(path_ +
                     ": cannot create the lock file: " + std::strerror(errno));
  }
  ~DirectoryLock() { ::unlink(path_.c_str()); }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  std::string path_;
};

// Temporaries left by a run that was killed mid-write.
void RemoveTemporaries(const std::string& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_regular_file(ec) &&
        IsTemporaryFileName(it->path().filename().string())) {
      LOG(INFO) << "removing " << it->path().string()
                << " (left by an interrupted run)";
      fs::remove(it->path(), ec);
    }
  }
}

}  // namespace

void ParseShard(const std::string& text, int* shard, int* shards) {
  int k = 0, n = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &k, &n, &tail) != 2 || n < 1 ||
      k < 1 || k > n) {
    throw InputError("--shard=" + text + ": expected K/N with 1 <= K <= N");
  }
  *shard = k;
  *shards = n;
}

BatchSummary RunBatch(const std::string& manifest,
                      const BatchOptions& options) {
  if (options.out_dir.empty())
    throw InputError("batch: --out_dir=DIR is required");
  std::vector<RunSpec> all = LoadManifest(manifest, options.deck_data);
  std::vector<RunSpec> specs;
  for (const RunSpec& s : all) {
    const std::uint64_t h = std::stoull(StableHash(s.chain_root), nullptr, 16);
    if (static_cast<int>(h % options.shards) == options.shard - 1)
      specs.push_back(s);
  }
  std::map<std::string, int> index;
  for (size_t i = 0; i < specs.size(); ++i)
    index[specs[i].name] = static_cast<int>(i);
  const int n = static_cast<int>(specs.size());
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) {
    throw InputError(options.out_dir +
                     ": cannot create the output directory: " + ec.message());
  }
  const DirectoryLock lock(options.out_dir);
  if (options.resume) RemoveTemporaries(options.out_dir);

  enum State { kPending, kRunning, kDone };
  std::vector<State> state(n, kPending);
  std::vector<RunResult> results(n);
  std::mutex mutex;
  std::condition_variable changed;
  int running = 0, done = 0, failed = 0;
  const auto start = std::chrono::steady_clock::now();
  const bool tty = options.progress && ::isatty(STDERR_FILENO);

  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
        .count();
  };
  // Caller holds the mutex.
  auto show = [&] {
    if (!tty) return;
    const double t = elapsed();
    std::string eta = "--:--:--";
    if (done > 0) eta = Clock(t / done * (n - done));
    std::fprintf(
        stderr,
        "\r\033[K%d/%d done, %d running, %d failed, %s elapsed, ~%s left",
        done,
        n,
        running,
        failed,
        Clock(t).c_str(),
        eta.c_str());
    std::fflush(stderr);
  };
  auto ready = [&](int i) {
    if (state[i] != kPending) return false;
    const std::string& before = specs[i].start_from;
    return before.empty() || state[index.at(before)] == kDone;
  };

  auto worker = [&] {
    while (true) {
      int pick = -1;
      {
        std::unique_lock<std::mutex> guard(mutex);
        changed.wait(guard, [&] {
          pick = -1;
          if (StopRequested()) return true;
          bool pending = false;
          for (int i = 0; i < n && pick < 0; ++i) {
            pending |= state[i] == kPending;
            if (ready(i)) pick = i;
          }
          return pick >= 0 || !pending;
        });
        if (pick < 0) return;
        state[pick] = kRunning;
        ++running;
        show();
      }
      const RunSpec& spec = specs[pick];
      const RunResult* predecessor = spec.start_from.empty()
                                         ? nullptr
                                         : &results[index.at(spec.start_from)];
      RunResult result = ExecuteRun(spec, predecessor, options);
      {
        std::lock_guard<std::mutex> lock(mutex);
        results[pick] = std::move(result);
        state[pick] = kDone;
        --running;
        ++done;
        const RunResult& r = results[pick];
        if (r.status != RunStatus::kConverged) ++failed;
        if (!tty) {
          LOG(INFO) << "[" << done << "/" << n << "] " << r.name << ": "
                    << RunStatusToString(r.status)
                    << (r.resumed ? " (resumed)" : "")
                    << (r.reason.empty() ? "" : " (" + r.reason + ")");
        }
        show();
      }
      changed.notify_all();
    }
  };

  // At most the budget's threads compute at once, whatever jobs says.
  int jobs = options.jobs > 0 ? std::min(options.jobs, ThreadBudget())
                              : ThreadBudget();
  jobs = std::max(1, std::min(jobs, std::max(n, 1)));
  std::atomic<bool> ticking{tty};
  std::thread ticker([&] {
    while (ticking) {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      std::lock_guard<std::mutex> lock(mutex);
      if (ticking) show();
    }
  });
  // Workers borrow their threads from the process's budget
  // (thread_budget.h), which the fits' multi-starts share.
  ParallelFor(jobs, [&](int) { worker(); });
  ticking = false;
  ticker.join();
  if (tty) std::fprintf(stderr, "\n");

  BatchSummary summary;
  summary.planned = n;
  summary.interrupted = StopRequested();
  for (int i = 0; i < n; ++i) {
    // What finished; runs not started or abandoned are left for --resume.
    if (state[i] == kDone && results[i].status != RunStatus::kInterrupted) {
      summary.runs.push_back(results[i]);
    }
  }
  std::sort(
      summary.runs.begin(),
      summary.runs.end(),
      [](const RunResult& a, const RunResult& b) { return a.name < b.name; });
  LOG(INFO) << "batch: " << n << " runs, " << n - failed << " converged, "
            << failed << " failed or not converged, " << Clock(elapsed())
            << " (" << jobs << " jobs)";
  WriteSummary(options.out_dir, summary);
  return summary;
}

}  // namespace fit3dof
