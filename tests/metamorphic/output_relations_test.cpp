// Metamorphic relations for the soft-shadow and light-assignment outputs (issue 25), in the style
// of metamorphic_test.cpp: exact transforms of a case and of its view samples (scaling by 2^k,
// axis permutations, a rotation and a mirror; triangle order, light order) must not change what the
// exact oracles say, and must not change an algorithm's answer beyond what the transform allows.
//
// - Light lists: the exact light sets and their band are invariant (each light renamed by the
//   light order). Every registered light-assignment algorithm x variant x backend must list every
//   robust member after the transform as before, and its lists must hold the same lights for
//   every sample (the transforms are exact in float, and the lists' culling only compares
//   transformed quantities; a list that depends on light order or on the scale is the
//   fixed-capacity, absolute-epsilon class of bugs).
// - Soft shadows: the exact visible fraction is invariant (to its 1e-12 rounding). On samples
//   robust before and after, each registered soft-shadow algorithm's fraction may move by at most
//   twice its declared per-sample budget (both answers lie within the budget of the same truth),
//   its mean move by at most twice its mean budget; under scaling and triangle order, where its
//   arithmetic is exactly equivariant, the fractions must not move at all.
//
// One CTest case per algorithm x variant x backend runs every relation (the inputs and truths
// are computed once per process); the binary needs no image library.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "case_transforms.h"
#include "oracles/light_assignment/light_assignment_comparison.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/light_assignment_oracle.h"
#include "shadowcts/registry.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "tests/test_name.h"

namespace shadowcts::metamorphic {
namespace {

// Small fixtures: ranged lights (spheres and spots, the city and the depth gaps with its
// fence-and-wall tiles) at 64 x 64, and the foliage's sun disk at 40 x 40 (the soft oracle is
// the expensive part).
const std::vector<std::string> light_fixtures = {"many_lights.1000", "depth_gaps.1000"};
const std::vector<std::string> soft_fixtures = {"foliage.1000"};
constexpr std::uint32_t light_side = 64, soft_side = 40;

struct Transformed {
  CaseWithSamples after;
  // Per light of `after`, its index in the original (the identity unless lights are reordered).
  std::vector<std::uint32_t> old_light;
  // Per sample of the original, its index in `after`; empty: the same index (the image turns
  // over only under a mirror, and only where the samples are moved to their new pixels).
  std::vector<std::size_t> new_sample;
  std::size_t sample_after(std::size_t s) const { return new_sample.empty() ? s : new_sample[s]; }
};

struct OutputRelation {
  std::string name;
  // The algorithm's arithmetic is exactly equivariant under it (powers of two, reordering of
  // independent items): soft fractions must be identical.
  bool exact_in_float;
  std::function<Transformed(const CaseWithSamples&)> apply;
};

std::vector<std::uint32_t> identity(std::size_t n) {
  std::vector<std::uint32_t> v(n);
  std::iota(v.begin(), v.end(), 0u);
  return v;
}

std::vector<OutputRelation> relations(bool with_lights) {
  std::vector<OutputRelation> list;
  for (const int k : {-20, 7})
    list.push_back({"scale_2pow" + std::string(k < 0 ? "m" : "") + std::to_string(std::abs(k)),
                    true, [k](const CaseWithSamples& in) {
                      return Transformed{
                          scale_by_power_of_two(in, k), identity(in.c.ranged_lights.size()), {}};
                    }});
  list.push_back(
      {"permute_axes_zxy", false, [](const CaseWithSamples& in) {
         const int axis[3] = {2, 0, 1};
         const float sign[3] = {1.0f, 1.0f, 1.0f};
         return Transformed{permute_axes(in, axis, sign), identity(in.c.ranged_lights.size()), {}};
       }});
  if (with_lights) {
    // The proper rotation (x, y, z) -> (y, x, -z), a half turn about (1, 1, 0), which swaps two
    // axes and flips one.
    list.push_back({"swap_xy_flip_z", false, [](const CaseWithSamples& in) {
                      const int axis[3] = {1, 0, 2};
                      const float sign[3] = {1.0f, 1.0f, -1.0f};
                      return Transformed{
                          permute_axes(in, axis, sign), identity(in.c.ranged_lights.size()), {}};
                    }});
  }
  // A mirror turns the camera's image over (its right vector is a cross product). Tiles and
  // clusters are made of pixels, so for light lists each sample moves to the pixel the camera
  // now sees it at (the tile grid maps onto itself: the widths here are multiples of the tile);
  // soft shadows keep the samples where they were, which their budget absorbs.
  list.push_back(
      {"mirror_x_swap_yz", false, [with_lights](const CaseWithSamples& in) {
         const int axis[3] = {0, 2, 1};
         const float sign[3] = {-1.0f, 1.0f, -1.0f};
         Transformed t{permute_axes(in, axis, sign), identity(in.c.ranged_lights.size()), {}};
         if (with_lights) t.after = turn_image_over(t.after, t.new_sample);
         return t;
       }});
  list.push_back(
      {"shuffle_triangles", true, [](const CaseWithSamples& in) {
         return Transformed{shuffle_triangles(in, 0x5eed), identity(in.c.ranged_lights.size()), {}};
       }});
  if (with_lights)
    list.push_back({"shuffle_lights", true, [](const CaseWithSamples& in) {
                      Transformed t;
                      t.after = shuffle_lights(in, 0x1165, t.old_light);
                      return t;
                    }});
  return list;
}

const CaseWithSamples& original(const std::string& fixture, std::uint32_t side) {
  static std::map<std::string, CaseWithSamples> cache;
  auto it = cache.find(fixture);
  if (it == cache.end()) {
    CaseWithSamples in;
    in.c = make_fixture(fixture);
    in.c.camera.width = in.c.camera.height = side;
    in.samples = generate_view_samples(in.c);
    it = cache.emplace(fixture, std::move(in)).first;
  }
  return it->second;
}

using test_support::test_name;

// --- Light assignment --------------------------------------------------------------------------

struct LightTruths {
  LightAssignmentTruth plain, normals;
  const LightAssignmentTruth& for_variant(bool normal_rule) const {
    return normal_rule ? normals : plain;
  }
};

LightTruths light_truths(const CaseWithSamples& in) {
  return {exact_light_assignment_oracle(in.c, in.samples, false),
          exact_light_assignment_oracle(in.c, in.samples, true)};
}

struct PreparedLights {
  Transformed t;
  LightTruths after;
};

const LightTruths& original_light_truths(const std::string& fixture) {
  static std::map<std::string, LightTruths> cache;
  auto it = cache.find(fixture);
  if (it == cache.end())
    it = cache.emplace(fixture, light_truths(original(fixture, light_side))).first;
  return it->second;
}

const PreparedLights& prepared_lights(const std::string& fixture, const OutputRelation& r) {
  static std::map<std::string, std::unique_ptr<PreparedLights>> cache;
  const std::string key = fixture + "/" + r.name;
  auto it = cache.find(key);
  if (it == cache.end()) {
    auto p = std::make_unique<PreparedLights>();
    p->t = r.apply(original(fixture, light_side));
    p->after = light_truths(p->t.after);
    it = cache.emplace(key, std::move(p)).first;
  }
  return *it->second;
}

// The robust members of sample s (exact set minus ambiguous lights), as original light indices,
// ascending.
std::vector<std::uint32_t> robust_members(const LightAssignmentTruth& truth, std::size_t s,
                                          const std::vector<std::uint32_t>& old_light) {
  std::vector<std::uint32_t> out;
  const auto amb_begin =
      truth.ambiguous_lights.begin() + std::ptrdiff_t(truth.ambiguous_offsets[s]);
  const auto amb_end =
      truth.ambiguous_lights.begin() + std::ptrdiff_t(truth.ambiguous_offsets[s + 1]);
  for (std::uint64_t e = truth.offsets[s]; e < truth.offsets[s + 1]; ++e)
    if (!std::binary_search(amb_begin, amb_end, truth.lights[e]))
      out.push_back(old_light[truth.lights[e]]);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::uint32_t> ambiguous(const LightAssignmentTruth& truth, std::size_t s,
                                     const std::vector<std::uint32_t>& old_light) {
  std::vector<std::uint32_t> out;
  for (std::uint64_t e = truth.ambiguous_offsets[s]; e < truth.ambiguous_offsets[s + 1]; ++e)
    out.push_back(old_light[truth.ambiguous_lights[e]]);
  std::sort(out.begin(), out.end());
  return out;
}

// The lights of sample s's list, as original light indices, ascending.
std::vector<std::uint32_t> listed(const LightLists& lists, std::size_t s,
                                  const std::vector<std::uint32_t>& old_light) {
  std::vector<std::uint32_t> out;
  const std::uint32_t list = lists.list_of_sample[s];
  if (list == LightLists::no_list) return out;
  for (std::uint32_t e = lists.offsets[list]; e < lists.offsets[list + 1]; ++e)
    out.push_back(old_light[lists.lights[e]]);
  std::sort(out.begin(), out.end());
  return out;
}

struct LightsParam {
  std::string fixture, relation;
};

class ExactLightOracleInvariance : public testing::TestWithParam<LightsParam> {};

TEST_P(ExactLightOracleInvariance, SameSetsAndBandOnEverySample) {
  const OutputRelation* relation = nullptr;
  static const std::vector<OutputRelation> all = relations(true);
  for (const OutputRelation& r : all)
    if (r.name == GetParam().relation) relation = &r;
  ASSERT_NE(relation, nullptr);
  const CaseWithSamples& in = original(GetParam().fixture, light_side);
  const LightTruths& before = original_light_truths(GetParam().fixture);
  const PreparedLights& p = prepared_lights(GetParam().fixture, *relation);
  const std::vector<std::uint32_t> same = identity(in.c.ranged_lights.size());
  std::size_t members = 0, differences = 0;
  for (const bool normal_rule : {false, true}) {
    const LightAssignmentTruth &a = before.for_variant(normal_rule),
                               &b = p.after.for_variant(normal_rule);
    for (std::size_t s = 0; s < in.samples.samples.size(); ++s) {
      const std::size_t t = p.t.sample_after(s);
      const auto ra = robust_members(a, s, same), rb = robust_members(b, t, p.t.old_light);
      members += ra.size();
      if (ra == rb && ambiguous(a, s, same) == ambiguous(b, t, p.t.old_light)) continue;
      if (++differences <= 5)
        ADD_FAILURE() << "sample " << s << (normal_rule ? " (normal rule)" : "") << ": "
                      << ra.size() << " -> " << rb.size() << " robust members";
    }
  }
  EXPECT_EQ(differences, 0u);
  EXPECT_GT(members, 0u) << "no robust member: the relation decides nothing";
}

std::vector<LightsParam> light_oracle_params() {
  std::vector<LightsParam> params;
  for (const std::string& f : light_fixtures)
    for (const OutputRelation& r : relations(true)) params.push_back({f, r.name});
  return params;
}

std::string light_oracle_test_name(const testing::TestParamInfo<LightsParam>& param) {
  return test_name(param.param.relation + "_" + param.param.fixture);
}

INSTANTIATE_TEST_SUITE_P(Exact, ExactLightOracleInvariance,
                         testing::ValuesIn(light_oracle_params()), light_oracle_test_name);

struct AlgorithmParam {
  std::string id, backend, variant;
};

// Readable parameter values in test logs.
void PrintTo(const AlgorithmParam& p, std::ostream* os) {
  *os << p.id << ":" << p.variant << " [" << p.backend << "]";
}
void PrintTo(const LightsParam& p, std::ostream* os) {
  *os << p.relation << " on " << p.fixture;
}

std::string algorithm_test_name(const testing::TestParamInfo<AlgorithmParam>& param) {
  return test_name(param.param.id + "_" + param.param.variant + "_" + param.param.backend);
}

std::vector<AlgorithmParam> algorithms_of(OutputKind kind) {
  std::vector<AlgorithmParam> params;
  for (const auto& a : builtin_registry().algorithms())
    if (a->info().capabilities.output == kind)
      for (const std::string& variant : a->info().variants)
        params.push_back({a->info().id, a->info().backend, variant});
  return params;
}

class LightListInvariance : public testing::TestWithParam<AlgorithmParam> {};

TEST_P(LightListInvariance, SameListsAndEveryRobustMemberListed) {
  const AlgorithmParam& param = GetParam();
  const Algorithm* algorithm = builtin_registry().find(param.id, param.backend);
  ASSERT_NE(algorithm, nullptr);
  const bool normal_rule = light_lists_use_normal_rule(param.variant);
  std::size_t relations_run = 0;
  for (const std::string& fixture : light_fixtures) {
    const CaseWithSamples& in = original(fixture, light_side);
    if (auto reason = algorithm->unsupported_reason(in.c, in.samples, param.variant))
      GTEST_SKIP() << "NotSupported: " << *reason;
    const std::vector<std::uint32_t> same = identity(in.c.ranged_lights.size());
    const LightAssignmentTruth& truth_before =
        original_light_truths(fixture).for_variant(normal_rule);
    const AlgorithmOutput before = algorithm->run(in.c, in.samples, param.variant);
    for (const OutputRelation& relation : relations(true)) {
      SCOPED_TRACE(relation.name + " on " + fixture);
      const PreparedLights& p = prepared_lights(fixture, relation);
      if (auto reason =
              algorithm->unsupported_reason(p.t.after.c, p.t.after.samples, param.variant)) {
        ADD_FAILURE() << "supported before, NotSupported after: " << *reason;
        continue;
      }
      const AlgorithmOutput after = algorithm->run(p.t.after.c, p.t.after.samples, param.variant);
      ASSERT_EQ(after.light_lists.list_of_sample.size(), in.samples.samples.size());
      const LightAssignmentTruth& truth_after = p.after.for_variant(normal_rule);
      std::size_t compared = 0, missing = 0, changed = 0, listed_pairs = 0;
      for (std::size_t s = 0; s < in.samples.samples.size(); ++s) {
        if (in.samples.samples[s].sample_class != SampleClass::regular) continue;
        ++compared;
        const std::size_t t = p.t.sample_after(s);
        const auto a = listed(before.light_lists, s, same);
        const auto b = listed(after.light_lists, t, p.t.old_light);
        listed_pairs += a.size();
        for (const std::uint32_t l : robust_members(truth_after, t, p.t.old_light))
          if (!std::binary_search(b.begin(), b.end(), l) && ++missing <= 3)
            ADD_FAILURE() << "sample " << s << ": robust member " << l << " not listed after";
        for (const std::uint32_t l : robust_members(truth_before, s, same))
          if (!std::binary_search(a.begin(), a.end(), l) && ++missing <= 3)
            ADD_FAILURE() << "sample " << s << ": robust member " << l << " not listed before";
        if (a != b && ++changed <= 3)
          ADD_FAILURE() << "sample " << s << " (pixel " << in.samples.samples[s].pixel_x << ", "
                        << in.samples.samples[s].pixel_y << "): " << a.size() << " -> " << b.size()
                        << " listed lights";
      }
      EXPECT_EQ(missing, 0u);
      EXPECT_EQ(changed, 0u) << "of " << compared << " samples";
      EXPECT_GT(listed_pairs, 0u) << "nothing listed: the relation decides nothing";
      ++relations_run;
    }
  }
  EXPECT_GT(relations_run, 0u);
}

INSTANTIATE_TEST_SUITE_P(Registered, LightListInvariance,
                         testing::ValuesIn(algorithms_of(OutputKind::light_lists)),
                         algorithm_test_name);

// --- Soft shadows ------------------------------------------------------------------------------

struct PreparedSoft {
  Transformed t;
  SoftShadowTruth after;
};

const SoftShadowTruth& original_soft_truth(const std::string& fixture) {
  static std::map<std::string, SoftShadowTruth> cache;
  auto it = cache.find(fixture);
  if (it == cache.end()) {
    const CaseWithSamples& in = original(fixture, soft_side);
    it = cache.emplace(fixture, exact_soft_shadow_oracle(in.c, in.samples)).first;
  }
  return it->second;
}

const PreparedSoft& prepared_soft(const std::string& fixture, const OutputRelation& r) {
  static std::map<std::string, std::unique_ptr<PreparedSoft>> cache;
  const std::string key = fixture + "/" + r.name;
  auto it = cache.find(key);
  if (it == cache.end()) {
    auto p = std::make_unique<PreparedSoft>();
    p->t = r.apply(original(fixture, soft_side));
    p->after = exact_soft_shadow_oracle(p->t.after.c, p->t.after.samples);
    it = cache.emplace(key, std::move(p)).first;
  }
  return *it->second;
}

TEST(ExactSoftOracleInvariance, SameFractionOnEverySample) {
  for (const std::string& fixture : soft_fixtures) {
    const CaseWithSamples& in = original(fixture, soft_side);
    const SoftShadowTruth& before = original_soft_truth(fixture);
    for (const OutputRelation& relation : relations(false)) {
      SCOPED_TRACE(relation.name + " on " + fixture);
      const SoftShadowTruth& after = prepared_soft(fixture, relation).after;
      std::size_t compared = 0, partial = 0, differences = 0;
      for (std::size_t s = 0; s < in.samples.samples.size(); ++s) {
        if (!before.compared[s]) continue;
        ++compared;
        const double a = before.visible_fraction[s], b = after.visible_fraction[s];
        partial += a > 0.0 && a < 1.0;
        // The oracle's only rounding (projected coordinates to double, the area's sum) is below
        // 1e-12 (docs/soft-shadow-oracle.md).
        if (std::fabs(a - b) > 1e-9 && ++differences <= 5)
          ADD_FAILURE() << "sample " << s << ": " << a << " -> " << b;
      }
      EXPECT_EQ(differences, 0u) << "of " << compared;
      EXPECT_GT(partial, 0u) << "no penumbra sample: the relation decides little";
    }
  }
}

class SoftShadowInvariance : public testing::TestWithParam<AlgorithmParam> {};

TEST_P(SoftShadowInvariance, FractionsMoveWithinTheBudget) {
  const AlgorithmParam& param = GetParam();
  const Algorithm* algorithm = builtin_registry().find(param.id, param.backend);
  ASSERT_NE(algorithm, nullptr);
  const SoftErrorBudget budget = algorithm->soft_error_budget(param.variant);
  for (const std::string& fixture : soft_fixtures) {
    const CaseWithSamples& in = original(fixture, soft_side);
    if (auto reason = algorithm->unsupported_reason(in.c, in.samples, param.variant))
      GTEST_SKIP() << "NotSupported: " << *reason;
    const SoftShadowTruth& truth_before = original_soft_truth(fixture);
    const AlgorithmOutput before = algorithm->run(in.c, in.samples, param.variant);
    for (const OutputRelation& relation : relations(false)) {
      SCOPED_TRACE(relation.name + " on " + fixture);
      const PreparedSoft& p = prepared_soft(fixture, relation);
      if (auto reason =
              algorithm->unsupported_reason(p.t.after.c, p.t.after.samples, param.variant)) {
        ADD_FAILURE() << "supported before, NotSupported after: " << *reason;
        continue;
      }
      const AlgorithmOutput after = algorithm->run(p.t.after.c, p.t.after.samples, param.variant);
      ASSERT_EQ(after.visible_fraction.size(), in.samples.samples.size());
      std::size_t compared = 0, moved = 0, beyond = 0;
      double largest = 0.0, sum = 0.0;
      for (std::size_t s = 0; s < in.samples.samples.size(); ++s) {
        if (!truth_before.robust[s] || !p.after.robust[s]) continue;
        ++compared;
        const double d =
            std::fabs(double(before.visible_fraction[s]) - double(after.visible_fraction[s]));
        largest = std::max(largest, d);
        sum += d;
        moved += d > 0.0;
        if (d > 2.0 * budget.per_sample && ++beyond <= 3)
          ADD_FAILURE() << "sample " << s << ": " << before.visible_fraction[s] << " -> "
                        << after.visible_fraction[s] << " (exact "
                        << truth_before.visible_fraction[s] << ")";
      }
      ASSERT_GT(compared, 0u);
      std::cout << "[ MOVED    ] " << relation.name << ": " << moved << " of " << compared
                << " robust samples, largest " << largest << ", mean " << sum / compared
                << " (budget " << budget.per_sample << " per sample, " << budget.mean << " mean)\n";
      EXPECT_EQ(beyond, 0u);
      EXPECT_LE(sum / double(compared), 2.0 * budget.mean);
      if (relation.exact_in_float) {
        EXPECT_EQ(moved, 0u) << "an exact transform in float moved " << moved << " of " << compared
                             << " samples, by up to " << largest;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Registered, SoftShadowInvariance,
                         testing::ValuesIn(algorithms_of(OutputKind::soft_shadow)),
                         algorithm_test_name);

}  // namespace
}  // namespace shadowcts::metamorphic
