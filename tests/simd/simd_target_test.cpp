#include "simd/simd_target.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

namespace shadowcts::simd {
namespace {

TEST(SimdTarget, NamesATargetThisCpuSupports) {
  const std::string name = dispatched_target_name();
  bool supported = false;
  for (std::int64_t t : hwy::SupportedAndGeneratedTargets())
    supported = supported || name == hwy::TargetName(t);
  EXPECT_TRUE(supported) << name;
}

}  // namespace
}  // namespace shadowcts::simd
