// Issue 16, item 4: every algorithm x variant x backend shows how far its long phase is. Each one
// runs on a small fixture its capabilities accept; afterwards the phase it began last
// (phase_progress.h) must have a total, name its unit, and be done to the last unit (an
// algorithm that reports nothing, or counts past or short of its total, fails). The device
// backend (cuda) is left out: its kernels report nothing per block, and without a device it does
// not run at all.
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shadowcts/fixtures.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/registry.h"
#include "shadowcts/view_samples.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

struct ProgressCase {
  std::string algorithm, variant, backend;
};

void PrintTo(const ProgressCase& c, std::ostream* os) {
  *os << c.algorithm << ":" << c.variant << " [" << c.backend << "]";
}

std::vector<ProgressCase> all_cases() {
  std::vector<ProgressCase> cases;
  for (const auto& a : builtin_registry().algorithms())
    for (const std::string& variant : a->info().variants)
      cases.push_back({a->info().id, variant, a->info().backend});
  return cases;
}

std::string case_name(const testing::TestParamInfo<ProgressCase>& info) {
  return test_support::test_name(info.param.algorithm + "_" + info.param.variant + "_" +
                                 info.param.backend);
}

// One small fixture per light kind: a point light over closed fans (hard shadows, stencil's
// closed meshes), a sun disk (soft shadows), ranged lights (light lists). 128 x 128 samples.
struct Input {
  Case c;
  ViewSamples samples;
};

const std::vector<Input>& inputs() {
  static const std::vector<Input> all = [] {
    std::vector<Input> out;
    for (const char* fixture : {"shared_edge_fans.2k", "foliage.2k", "many_lights.2k"}) {
      Input in;
      in.c = make_fixture(fixture);
      in.c.camera.width = 128;
      in.c.camera.height = 128;
      in.samples = generate_view_samples(in.c);
      out.push_back(std::move(in));
    }
    return out;
  }();
  return all;
}

class AlgorithmProgress : public testing::TestWithParam<ProgressCase> {};

TEST_P(AlgorithmProgress, FinishesThePhaseItBeganLast) {
  const ProgressCase& p = GetParam();
  if (p.backend == "cuda") GTEST_SKIP() << "the device backend reports no per-block progress";
  const Algorithm* algorithm = builtin_registry().find(p.algorithm, p.backend);
  ASSERT_NE(algorithm, nullptr);
  std::string reasons;
  for (const Input& in : inputs()) {
    if (const auto why = algorithm->unsupported_reason(in.c, in.samples, p.variant)) {
      reasons += in.c.name + ": " + *why + "\n";
      continue;
    }
    const PreparedScene scene = prepare_scene(in.c, in.samples);
    phase_progress::begin(0);  // as the runner does before every step
    const std::uint64_t before = phase_progress::snapshot().generation;
    algorithm->run(scene, p.variant);
    const phase_progress::Snapshot s = phase_progress::snapshot();
    EXPECT_GT(s.generation, before) << "no phase began on " << in.c.name;
    EXPECT_GT(s.total, 0u) << in.c.name;
    EXPECT_EQ(s.done, s.total) << in.c.name << ": " << s.unit << " of " << s.of;
    EXPECT_STRNE(s.unit, "") << "a phase names what it counts";
    return;
  }
  FAIL() << "no fixture of this test runs it:\n" << reasons;
}

INSTANTIATE_TEST_SUITE_P(AlgorithmProgress, AlgorithmProgress, testing::ValuesIn(all_cases()),
                         case_name);

}  // namespace
}  // namespace shadowcts
