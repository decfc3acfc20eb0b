#include "simd/simd_target.h"

#include <cstdint>
#include <vector>

#include <hwy/targets.h>

namespace shadowcts::simd {

std::string dispatched_target_name() {
  // SupportedAndGeneratedTargets() is what HWY_DYNAMIC_DISPATCH chooses from, best first.
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  return targets.empty() ? std::string("none") : std::string(hwy::TargetName(targets.front()));
}

}  // namespace shadowcts::simd
