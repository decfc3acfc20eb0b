#include "shadowcts/variant_table_algorithm.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace shadowcts {
namespace {

bool device_present = true;

std::optional<std::string> no_device() {
  if (device_present) return std::nullopt;
  return "no device";
}

// Answers with its configuration as the one counter; refuses cases with more than one ranged
// light as its own input problem.
class Table final : public VariantTableAlgorithm<int> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  std::optional<std::string> input_problem(const Case& c, const ViewSamples&,
                                           const Variant& variant) const override {
    if (c.ranged_lights.size() > 1) return "too many lights for " + variant.name;
    return std::nullopt;
  }

  AlgorithmOutput run_variant(const PreparedScene&, const Variant& variant) const override {
    AlgorithmOutput output;
    output.counters = {{"config", std::uint64_t(variant.config)}};
    return output;
  }
};

Table make_table(std::vector<std::string> registered = {}) {
  return Table({.id = "table",
                .backend = "test",
                .summary = "a table",
                .capabilities = {.output = OutputKind::light_lists, .ranged_lights = true},
                .registered = std::move(registered),
                .unavailable_reason = no_device},
               {{.name = "a", .config = 1},
                {.name = "b", .config = 2, .phases = {}, .soft_error_budget = {0.5, 0.25}},
                {.name = "c", .config = 3, .robust_mismatch_ceiling = 0.125}});
}

TEST(VariantTableAlgorithm, AnswersTheInterfaceFromTheTableInItsOrder) {
  const Table table = make_table();
  EXPECT_EQ(table.info().id, "table");
  EXPECT_EQ(table.info().backend, "test");
  EXPECT_EQ(table.info().variants, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(table.timed_phases("a"), build_and_query_phases());
  EXPECT_TRUE(table.timed_phases("b").empty());
  EXPECT_EQ(table.soft_error_budget("b").per_sample, 0.5);
  EXPECT_EQ(table.soft_error_budget("a").mean, 0.0);
  EXPECT_EQ(table.robust_mismatch_ceiling("c"), 0.125);
  EXPECT_EQ(table.variant("c").config, 3);
  try {
    table.variant("d");
    FAIL() << "no error for an unknown variant";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "table/test: unknown variant 'd'");
  }
  EXPECT_THROW(table.timed_phases("d"), std::invalid_argument);
}

TEST(VariantTableAlgorithm, RegistersSomeRowsAndRunsEveryRow) {
  const Table table = make_table({"c", "a"});
  EXPECT_EQ(table.info().variants, (std::vector<std::string>{"c", "a"}));
  Case c;
  c.ranged_lights.resize(1);
  const ViewSamples samples;
  EXPECT_EQ(table.unsupported_reason(c, samples, "b"), "unknown variant 'b'");
  EXPECT_EQ(table.unsupported_reason(c, samples, "a"), std::nullopt);
  const PreparedScene scene = prepare_scene(c, samples);
  EXPECT_EQ(table.run(scene, "b").counters.front().second, 2u);
  EXPECT_THROW(table.run(scene, "d"), std::invalid_argument);
  EXPECT_THROW(make_table({"d"}), std::invalid_argument);
}

TEST(VariantTableAlgorithm, CapabilitiesThenInputProblemThenDevice) {
  const Table table = make_table();
  Case c;
  const ViewSamples samples;
  device_present = false;
  EXPECT_EQ(table.unsupported_reason(c, samples, "a"), "the case has no ranged lights");
  c.ranged_lights.resize(2);
  EXPECT_EQ(table.unsupported_reason(c, samples, "a"), "too many lights for a");
  c.ranged_lights.resize(1);
  EXPECT_EQ(table.unsupported_reason(c, samples, "a"), "no device");
  EXPECT_THROW(table.run(prepare_scene(c, samples), "a"), std::runtime_error);
  device_present = true;
  EXPECT_EQ(table.unsupported_reason(c, samples, "a"), std::nullopt);
}

}  // namespace
}  // namespace shadowcts
