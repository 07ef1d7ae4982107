// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The most recent results of a pure function of a case and its data
// (FitSamples in fit_memo.h, the diagnosis' scores in diagnose_round.cc),
// kept so that a search repeating a call gets the same result without the
// work. A key is the case (operator==, case.h, and its `source`, which a
// fit's warnings name), the samples, and whatever else the function reads.

#ifndef FIT3DOF_SRC_RECENT_MEMO_H_
#define FIT3DOF_SRC_RECENT_MEMO_H_

#include <deque>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "fit3dof/case.h"
#include "fit3dof/time_history.h"

namespace fit3dof {

// Whether two lists of records hold the same samples.
bool SameSamples(const std::vector<TimeHistory>& a,
                 const std::vector<TimeHistory>& b);

// Whether two cases are equal and name the same source.
inline bool SameCase(const Case& a, const Case& b) {
  return a == b && a.source == b.source;
}

// Calls and hits since the memo was made (for tests and benchmarks).
struct MemoCounts {
  long calls = 0;
  long hits = 0;
};

// A thread-safe memo of the last `capacity` (Key, Value) pairs added (the
// oldest goes first); Key needs operator==. Two threads asking for the same
// key at once both compute it: holding the lock through the work would
// serialize the search.
template <typename Key, typename Value>
class RecentMemo {
 public:
  explicit RecentMemo(int capacity) : capacity_(capacity) {}

  std::optional<Value> Find(const Key& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.calls;
    for (const auto& [k, v] : entries_) {
      if (k == key) {
        ++counts_.hits;
        return v;
      }
    }
    return std::nullopt;
  }

  void Add(Key key, Value value) {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.emplace_back(std::move(key), std::move(value));
    if (static_cast<int>(entries_.size()) > capacity_) entries_.pop_front();
  }

  MemoCounts Counts() {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }

 private:
  const int capacity_;
  std::mutex mutex_;
  std::deque<std::pair<Key, Value>> entries_;
  MemoCounts counts_;
};

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_RECENT_MEMO_H_
