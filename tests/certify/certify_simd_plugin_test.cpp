// Issue 23, deliverable 4: one of the suite's own optimized ports behind the C ABI. The SIMD ptsv
// port (Highway + oneTBB), linked into examples/libexample_simd_ptsv.so from the suite's static
// libraries, is certified on a point-light and a directional-light case with all its variants,
// and the certificate verifies.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli/tool_run.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;
using testing::fresh_dir;
using testing::read_file;
using testing::run_tool;

TEST(Certify, SuitesSimdPtsvPortAsAPluginPasses) {
  const fs::path dir = fresh_dir("certify_simd_ptsv");
  const int code = run_tool(std::string("certify --backend '") + EXAMPLE_SIMD_PTSV +
                                "' --fixture ground_blockers.100 --fixture closed_shapes.100 "
                                "--timeout 120 --threads 1 --out out",
                            dir);
  const std::string log = read_file(dir / "stdout.txt") + read_file(dir / "stderr.txt");
  ASSERT_EQ(code, 0) << log;
  const ordered_json c = ordered_json::parse(read_file(dir / "out" / "certificate.json"));
  EXPECT_EQ(c["library"]["name"], "example_simd_ptsv");
  ASSERT_EQ(c["library"]["variants"].size(), 3u) << c["library"].dump();
  ASSERT_EQ(c["results"].size(), 6u) << log;
  for (const ordered_json& r : c["results"]) {
    EXPECT_EQ(r["verdict"], "Pass") << r.dump();
    EXPECT_EQ(r["record"]["algorithm"], "ptsv") << r.dump();
  }
  EXPECT_EQ(run_tool("certify verify out", dir), 0) << read_file(dir / "stdout.txt");
}

// The implicit variant's bounds are spans of pixel coordinates, and it declares so
// (SHADOWCTS_VARIANT_NEEDS_SAMPLES_IN_THEIR_PIXELS): samples a fuzzer placed off their pixels'
// frusta are declared NotSupported, saying why, instead of reaching the port (an error there is a
// Crash); the other variants still run those cases.
TEST(Certify, SimdPtsvImplicitDeclaresItNeedsSamplesInTheirPixels) {
  const fs::path dir = fresh_dir("certify_simd_ptsv_fuzz");
  const int code = run_tool(std::string("certify --backend '") + EXAMPLE_SIMD_PTSV +
                                "' --fixture fuzz.watertight.1.0 --fixture fuzz.watertight.1.1 "
                                "--fixture fuzz.watertight.1.2 --timeout 120 --threads 1 --out out",
                            dir);
  const std::string log = read_file(dir / "stdout.txt") + read_file(dir / "stderr.txt");
  ASSERT_EQ(code, 0) << log;
  const ordered_json c = ordered_json::parse(read_file(dir / "out" / "certificate.json"));
  int implicit_not_supported = 0, others_judged = 0;
  for (const ordered_json& r : c["results"]) {
    EXPECT_NE(r["verdict"], "Crash") << r.dump();
    EXPECT_NE(r["verdict"], "Fail") << r.dump();
    const std::string variant = r["variant"].get<std::string>();
    if (variant == "implicit" && r["verdict"] == "NotSupported") {
      ++implicit_not_supported;
      EXPECT_NE(r["reason"].get<std::string>().find("inside its own pixel's view frustum"),
                std::string::npos)
          << r.dump();
    }
    others_judged += variant != "implicit" && r["verdict"] == "Pass";
  }
  EXPECT_GE(implicit_not_supported, 1) << log;
  EXPECT_GE(others_judged, 1) << log;
}

}  // namespace
}  // namespace shadowcts
