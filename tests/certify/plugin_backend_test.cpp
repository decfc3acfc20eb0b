// The adapter (runner/plugin_backend.h) in-process: a plugin's light lists (through the
// OUTPUT_TOO_SMALL protocol), soft shadows and hard shadows are judged by the runner like a
// registered algorithm's, and outputs that break the ABI's rules are a Crash naming the value.
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "runner/plugin_backend.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"
#include "tests/cli/tool_run.h"

namespace shadowcts {
namespace {

TEST(PluginBackend, OtherOutputKindsAreJudgedByTheRunner) {
  const PluginBackend backend(OTHER_OUTPUTS_PLUGIN);
  ASSERT_EQ(backend.variants().size(), 3u);
  Registry registry;
  for (std::size_t k = 0; k < backend.variants().size(); ++k) registry.add(backend.algorithm(k));
  RunOptions options;
  options.fixtures = {"foliage.100", "many_lights.100"};
  options.out_dir = (testing::fresh_dir("plugin_backend") / "out").string();
  options.repeats = 1;
  options.threads = 1;
  std::ostringstream out, err;
  EXPECT_EQ(run_suite(options, registry, out, err), exit_conformance_failure) << out.str();
  const auto results =
      nlohmann::json::parse(testing::read_file(std::string(options.out_dir) + "/results.json"));
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& r : results["results"]) by_name[r["name"].get<std::string>()] = r;
  const auto& lists = by_name.at("lights.other_lightassign.one_list.other_outputs.many_lights.100");
  EXPECT_EQ(lists["verdict"], "Pass") << lists.dump(2);
  const auto& soft = by_name.at("soft.other_soft.fully_lit.other_outputs.foliage.100");
  EXPECT_EQ(soft["verdict"], "Fail") << soft.dump(2);
  const auto& hard = by_name.at("hard.other_hard.bad_bit.other_outputs.foliage.100");
  EXPECT_EQ(hard["verdict"], "Crash");
  EXPECT_NE(hard["reason"].get<std::string>().find("shadowed[0] is 2"), std::string::npos)
      << hard["reason"];
  // Declared capabilities decide NotSupported: no sun disk on many_lights, no ranged lights on
  // foliage.
  EXPECT_EQ(by_name.at("soft.other_soft.fully_lit.other_outputs.many_lights.100")["verdict"],
            "NotSupported");
  EXPECT_EQ(by_name.at("lights.other_lightassign.one_list.other_outputs.foliage.100")["verdict"],
            "NotSupported");
}

}  // namespace
}  // namespace shadowcts
