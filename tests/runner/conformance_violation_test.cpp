// The conformance property of fuzz cases (runner/conformance_violation.h) for soft shadows and
// light lists: the differential generator's sun disks and ranged lights, violations found where a
// list misses a light or a fraction leaves its budget (or errs grossly), ports diffed against
// their reference, and reproducers that keep the lights bit for bit.
#include "conformance_violation.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "case_reproducer.h"
#include "fixtures/fuzz/fuzz_fixtures.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/registry.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

const Algorithm& builtin(const std::string& id, const std::string& backend) {
  for (const auto& a : builtin_registry().algorithms())
    if (a->info().id == id && a->info().backend == backend) return *a;
  throw std::runtime_error("no " + id + " [" + backend + "]");
}

// The first differential fuzz case of seed 1 that `wanted` accepts.
template <class Wanted>
fuzzing::SampleCase first_differential_case(Wanted wanted) {
  for (int i = 0; i < 200; ++i) {
    fuzzing::GeneratedCase g = fuzzing::make_fuzz_case("fuzz.differential.1." + std::to_string(i));
    if (wanted(g.sample_case)) return g.sample_case;
  }
  throw std::runtime_error("no such differential case among the first 200");
}

bool has_sun_disk(const fuzzing::SampleCase& s) {
  return s.c.light && s.c.light->kind == ShadowLightKind::sun_disk;
}

TEST(DifferentialCases, WidenSomeLightsToSunDisksAndAddRangedLights) {
  int suns = 0, ranged = 0, spots = 0, on_a_sample = 0, inner_bvh_nodes = 0;
  for (int i = 0; i < 64; ++i) {
    const fuzzing::SampleCase s =
        fuzzing::make_fuzz_case("fuzz.differential.1." + std::to_string(i)).sample_case;
    if (has_sun_disk(s)) {
      ++suns;
      EXPECT_GT(s.c.light->angular_radius, 0.0f);
      EXPECT_LT(s.c.light->angular_radius, 1.06f);
    }
    ranged += !s.c.ranged_lights.empty();
    inner_bvh_nodes += s.c.ranged_lights.size() > 32;  // the light BVH has 32 leaves per node
    for (const RangedLight& l : s.c.ranged_lights) {
      EXPECT_GT(l.range, 0.0f);
      if (l.kind == RangedLightKind::spot) {
        ++spots;
        EXPECT_NEAR(std::hypot(l.direction.x, l.direction.y, l.direction.z), 1.0, 1e-6);
      }
      for (const ViewSample& v : s.samples.samples)
        on_a_sample += v.sample_class != SampleClass::sky && v.position == l.centre;
    }
  }
  // About a quarter of the cases have a sun disk, half have ranged lights.
  EXPECT_GT(suns, 6);
  EXPECT_GT(ranged, 16);
  EXPECT_GT(spots, 0);
  EXPECT_GT(on_a_sample, 0);
  EXPECT_GT(inner_bvh_nodes, 0);
}

TEST(ConformanceViolation, AListThatMissesALightIsAViolationAtItsSample) {
  const fuzzing::SampleCase s = first_differential_case([](const fuzzing::SampleCase& k) {
    return !k.explicit_samples && k.c.ranged_lights.size() > 2;
  });
  const Algorithm& clustered = builtin("lightassign", "reference");
  const ExactTruths truths = exact_truths(s.c, s.samples);
  ASSERT_TRUE(truths.lights && truths.lights_by_normal_rule);
  EXPECT_EQ(truths.soft.has_value(), has_sun_disk(s));
  EXPECT_EQ(find_violation(clustered, "clustered", s.c, s.samples, truths), std::nullopt);
  AlgorithmOutput output = clustered.run(s.c, s.samples, "clustered");
  // Drop from a sample's list a light its exact set holds robustly.
  const LightLists& lists = output.light_lists;
  const LightAssignmentTruth& t = *truths.lights;
  std::size_t needed_sample = s.samples.samples.size();
  std::uint32_t light = 0;
  for (std::size_t i = 0; i < s.samples.samples.size() && needed_sample == s.samples.samples.size();
       ++i)
    for (std::uint64_t e = t.offsets[i]; e < t.offsets[i + 1]; ++e) {
      const auto ambiguous_begin = t.ambiguous_lights.begin() + t.ambiguous_offsets[i];
      const auto ambiguous_end = t.ambiguous_lights.begin() + t.ambiguous_offsets[i + 1];
      if (std::find(ambiguous_begin, ambiguous_end, t.lights[e]) != ambiguous_end) continue;
      needed_sample = i;
      light = t.lights[e];
      break;
    }
  ASSERT_LT(needed_sample, s.samples.samples.size()) << "no sample is robustly lit";
  const std::uint32_t list = lists.list_of_sample[needed_sample];
  auto& members = output.light_lists.lights;
  const auto begin = members.begin() + lists.offsets[list];
  const auto end = members.begin() + lists.offsets[list + 1];
  const auto at = std::find(begin, end, light);
  ASSERT_NE(at, end);
  members.erase(at);
  for (std::size_t k = list + 1; k < output.light_lists.offsets.size(); ++k)
    --output.light_lists.offsets[k];
  const auto violation = output_violation(clustered, "clustered", s.c, s.samples, output, truths);
  ASSERT_TRUE(violation.has_value());
  EXPECT_NE(violation->what.find("completeness miss"), std::string::npos) << violation->what;
  ASSERT_TRUE(violation->sample.has_value());
  EXPECT_EQ(output.light_lists.list_of_sample[*violation->sample], list);
}

TEST(ConformanceViolation, ASoftFractionOutsideItsBudgetIsAViolation) {
  const fuzzing::SampleCase s = first_differential_case(
      [](const fuzzing::SampleCase& k) { return has_sun_disk(k) && !k.explicit_samples; });
  const Algorithm& softtile = builtin("softtile", "reference");
  const ExactTruths truths = exact_truths(s.c, s.samples, {.hard = false, .lights = false});
  ASSERT_TRUE(truths.soft.has_value());
  AlgorithmOutput output = softtile.run(s.c, s.samples, "rows31");
  ASSERT_EQ(output_violation(softtile, "rows31", s.c, s.samples, output, truths), std::nullopt);
  // Without the soft truth only the range is checked.
  const ExactTruths no_soft = exact_truths(s.c, s.samples, {.soft = false});
  std::size_t robust = 0;
  while (robust < truths.soft->robust.size() && !truths.soft->robust[robust]) ++robust;
  ASSERT_LT(robust, truths.soft->robust.size()) << "no robust sample";
  output.visible_fraction[robust] = 1.0f - float(truths.soft->visible_fraction[robust]);
  if (std::fabs(output.visible_fraction[robust] - truths.soft->visible_fraction[robust]) < 0.5)
    output.visible_fraction[robust] = truths.soft->visible_fraction[robust] < 0.5 ? 1.0f : 0.0f;
  const auto violation = output_violation(softtile, "rows31", s.c, s.samples, output, truths);
  ASSERT_TRUE(violation.has_value());
  EXPECT_EQ(violation->sample, robust);
  EXPECT_EQ(output_violation(softtile, "rows31", s.c, s.samples, output, no_soft), std::nullopt);
  output.visible_fraction[robust] = std::nanf("");
  const auto nan = output_violation(softtile, "rows31", s.c, s.samples, output, no_soft);
  ASSERT_TRUE(nan.has_value());
  EXPECT_NE(nan->what.find("not in [0, 1]"), std::string::npos) << nan->what;
}

// What the fuzz targets judge soft fractions by: a robust sample in full light (or umbra) answered
// more than half shadowed (or lit); smaller errors, over budget or not, are left to the suite.
TEST(ConformanceViolation, GrossSoftErrorsAreJudgedWithoutTheBudget) {
  const fuzzing::SampleCase s = first_differential_case(
      [](const fuzzing::SampleCase& k) { return has_sun_disk(k) && !k.explicit_samples; });
  const Algorithm& softtile = builtin("softtile", "reference");
  ExactTruths gross = exact_truths(s.c, s.samples, {.hard = false, .lights = false});
  gross.soft_gross_errors_only = true;
  const SoftShadowTruth& truth = *gross.soft;
  std::size_t lit = 0;
  while (lit < truth.robust.size() && !(truth.robust[lit] && truth.visible_fraction[lit] == 1.0))
    ++lit;
  ASSERT_LT(lit, truth.robust.size()) << "no robust sample in full light";
  AlgorithmOutput output = softtile.run(s.c, s.samples, "post");
  ASSERT_EQ(output_violation(softtile, "post", s.c, s.samples, output, gross), std::nullopt);
  output.visible_fraction[lit] = 0.625f;  // over post's per-sample budget, not gross
  EXPECT_EQ(output_violation(softtile, "post", s.c, s.samples, output, gross), std::nullopt);
  ExactTruths budget = gross;
  budget.soft_gross_errors_only = false;
  EXPECT_TRUE(output_violation(softtile, "post", s.c, s.samples, output, budget).has_value());
  output.visible_fraction[lit] = 0.375f;
  const auto violation = output_violation(softtile, "post", s.c, s.samples, output, gross);
  ASSERT_TRUE(violation.has_value());
  EXPECT_EQ(violation->sample, lit);
  EXPECT_NE(violation->what.find("fully lit"), std::string::npos) << violation->what;
}

TEST(ConformanceViolation, PortsAreDiffedAgainstTheirReferenceAtTheFirstDifferingSample) {
  const fuzzing::SampleCase s = first_differential_case([](const fuzzing::SampleCase& k) {
    return has_sun_disk(k) && !k.explicit_samples && k.c.ranged_lights.size() > 2;
  });
  const AlgorithmOutput soft = builtin("softtile", "reference").run(s.c, s.samples, "grid16");
  const AlgorithmOutput lists =
      builtin("lightassign", "reference").run(s.c, s.samples, "clustered");
  EXPECT_EQ(difference_from_reference(OutputKind::soft_shadow, s.samples, soft, soft),
            std::nullopt);
  EXPECT_EQ(difference_from_reference(OutputKind::light_lists, s.samples, lists, lists),
            std::nullopt);
  std::size_t last = s.samples.samples.size() - 1;
  while (s.samples.samples[last].sample_class != SampleClass::regular) --last;
  AlgorithmOutput nudged = soft;
  nudged.visible_fraction[last] = std::nextafter(soft.visible_fraction[last], 2.0f);
  const auto fraction = difference_from_reference(OutputKind::soft_shadow, s.samples, nudged, soft);
  ASSERT_TRUE(fraction.has_value());
  EXPECT_EQ(fraction->sample, last);
  // The same lists in another order are the same sets; one light fewer is a difference.
  std::size_t sample = s.samples.samples.size() - 1;
  const LightLists& l = lists.light_lists;
  while (l.list_of_sample[sample] == LightLists::no_list ||
         l.offsets[l.list_of_sample[sample] + 1] == l.offsets[l.list_of_sample[sample]])
    ASSERT_GT(sample--, 0u) << "every list is empty";
  const std::uint32_t list = l.list_of_sample[sample];
  AlgorithmOutput reordered = lists;
  std::reverse(reordered.light_lists.lights.begin() + l.offsets[list],
               reordered.light_lists.lights.begin() + l.offsets[list + 1]);
  EXPECT_EQ(difference_from_reference(OutputKind::light_lists, s.samples, reordered, lists),
            std::nullopt);
  AlgorithmOutput fewer = lists;
  const std::uint32_t dropped = l.lights[l.offsets[list]];
  fewer.light_lists.lights.erase(fewer.light_lists.lights.begin() + l.offsets[list]);
  for (std::size_t k = list + 1; k < l.offsets.size(); ++k) --fewer.light_lists.offsets[k];
  const auto difference =
      difference_from_reference(OutputKind::light_lists, s.samples, fewer, lists);
  ASSERT_TRUE(difference.has_value());
  EXPECT_NE(difference->what.find("light " + std::to_string(dropped) + " only in the reference's"),
            std::string::npos)
      << difference->what;
  EXPECT_EQ(l.list_of_sample[*difference->sample], list);
}

TEST(ConformanceViolation, ReproducersKeepSunDisksAndRangedLightsBitForBit) {
  const fuzzing::SampleCase s = first_differential_case([](const fuzzing::SampleCase& k) {
    bool spot = false;
    for (const RangedLight& l : k.c.ranged_lights) spot |= l.kind == RangedLightKind::spot;
    return has_sun_disk(k) && spot;
  });
  const fs::path dir = fs::temp_directory_path() / "shadowcts_reproducer_lights";
  fs::remove_all(dir);
  const Case back = load_case_manifest(write_reproducer(dir.string(), s.c, s.samples));
  ASSERT_TRUE(back.light.has_value());
  EXPECT_EQ(back.light->kind, ShadowLightKind::sun_disk);
  EXPECT_EQ(back.light->direction, s.c.light->direction);
  EXPECT_EQ(back.light->angular_radius, s.c.light->angular_radius);
  ASSERT_EQ(back.ranged_lights.size(), s.c.ranged_lights.size());
  for (std::size_t k = 0; k < back.ranged_lights.size(); ++k) {
    const RangedLight &a = back.ranged_lights[k], &b = s.c.ranged_lights[k];
    EXPECT_EQ(a.kind, b.kind) << k;
    EXPECT_EQ(a.centre, b.centre) << k;
    EXPECT_EQ(a.range, b.range) << k;
    if (b.kind != RangedLightKind::spot) continue;
    EXPECT_EQ(a.direction, b.direction) << k;
    EXPECT_EQ(a.cone_half_angle, b.cone_half_angle) << k;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shadowcts
