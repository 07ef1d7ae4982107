// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

#include "fit_memo.h"

#include "recent_memo.h"

namespace fit3dof {

bool SameSamples(const std::vector<TimeHistory>& a,
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

FitMemoCounts GetFitMemoCounts() {
  const MemoCounts counts = TheMemo().Counts();
  return FitMemoCounts{counts.calls, counts.hits};
}

}  // namespace fit3dof
