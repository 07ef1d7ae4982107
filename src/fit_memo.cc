// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit_memo.h"

#include "recent_memo.h"

namespace fit3dof {

namespace {

struct FitKey {
  Case c;
  std::vector<TimeHistory> data;
  bool operator==(const FitKey& o) const {
    return SameCase(c, o.c) && SameSamples(data, o.data);
  }
};

RecentMemo<FitKey, FitResult>& TheMemo() {
  // Never destroyed: used until exit.
  static auto* memo = new RecentMemo<FitKey, FitResult>(kFitMemoCapacity);
  return *memo;
}

}  // namespace

FitResult MemoizedFitSamples(const Case& c,
                             const std::vector<TimeHistory>& data) {
  FitKey key{c, data};
  if (std::optional<FitResult> fit = TheMemo().Find(key)) return *fit;
  // A fit that throws is not remembered (the next call throws again).
  FitResult fit = FitSamples(c, data);
  TheMemo().Add(std::move(key), fit);
  return fit;
}

FitMemoCounts GetFitMemoCounts() { return TheMemo().Counts(); }

}  // namespace fit3dof
