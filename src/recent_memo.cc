// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

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

}  // namespace fit3dof
