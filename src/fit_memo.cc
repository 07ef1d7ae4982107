// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit_memo.h"

#include <deque>
#include <mutex>
#include <optional>

namespace fit3dof {
namespace {

bool SameData(const std::vector<TimeHistory>& a,
              const std::vector<TimeHistory>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].t != b[i].t || a[i].phi != b[i].phi || a[i].theta != b[i].theta ||
        a[i].psi != b[i].psi) {
      return false;
    }
  }
  return true;
}

struct Entry {
  Case c;
  std::vector<TimeHistory> data;
  FitResult fit;
};

class Memo {
 public:
  std::optional<FitResult> Find(const Case& c,
                                const std::vector<TimeHistory>& data) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.calls;
    for (const Entry& e : entries_) {
      if (e.c == c && e.c.source == c.source && SameData(e.data, data)) {
        ++counts_.hits;
        return e.fit;
      }
    }
    return std::nullopt;
  }

  void Add(const Case& c,
           const std::vector<TimeHistory>& data,
           const FitResult& fit) {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_back({c, data, fit});
    if (entries_.size() > kFitMemoCapacity) entries_.pop_front();
  }

  FitMemoCounts Counts() {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }

 private:
  std::mutex mutex_;
  std::deque<Entry> entries_;
  FitMemoCounts counts_;
};

Memo& TheMemo() {
  static Memo* memo = new Memo;  // never destroyed: used until exit
  return *memo;
}

}  // namespace

FitResult MemoizedFitSamples(const Case& c,
                             const std::vector<TimeHistory>& data) {
  if (std::optional<FitResult> fit = TheMemo().Find(c, data)) return *fit;
  // Two threads asking for the same fit at once both fit it (the same
  // doubles); holding the lock through a fit would serialize the search.
  FitResult fit = FitSamples(c, data);
  TheMemo().Add(c, data, fit);
  return fit;
}

FitMemoCounts GetFitMemoCounts() { return TheMemo().Counts(); }

}  // namespace fit3dof
