// Issue 24: `shadowcts export` then `shadowcts check` of an engine's frame. A naive float ray
// caster (Moller-Trumbore, a 1e-4 offset, as many engines do) renders the exported shared_edges
// case; the check must report exactly the robust mismatches the exact oracle gives, and the
// leaks must lie on shared edges. A mask written from the oracle must pass; bad inputs exit 2
// naming file, channel and pixel, with nothing written.
#include <sys/wait.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "shadowcts/case_manifest.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "tool_run.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::read_file;
using testing::run_tool;

fs::path fresh_dir(const std::string& name) {
  return testing::fresh_dir("frame_check_" + name);
}

const std::string tool = SHADOWCTS_TOOL;

void write_channel(const fs::path& path, std::uint32_t w, std::uint32_t h,
                   const std::vector<float>& values, const char* name = "Y") {
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(int(w), int(h), 1, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {name};
  ASSERT_TRUE(out->open(path.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
  ASSERT_TRUE(out->close());
}

void add_result(const fs::path& manifest, const json& result) {
  json m = json::parse(read_file(manifest));
  m["result"] = result;
  std::ofstream(manifest) << m.dump(2);
}

// Moller-Trumbore in float, as a naive engine casts shadow rays. Inclusive edges (u >= 0), or
// strict ones (u > 0, a common slip) with back faces culled (the textbook culling branch, and
// RAY_FLAG_CULL_BACK_FACING_TRIANGLES): a ray through a shared edge where it enters a closed
// mesh then meets neither face, and its exit face is culled.
bool float_hit(const glm::vec3& o, const glm::vec3& d, const Triangle& t, float t_min,
               bool strict) {
  const glm::vec3 e1 = t.v1 - t.v0, e2 = t.v2 - t.v0;
  const glm::vec3 h = glm::cross(d, e2);
  const float a = glm::dot(e1, h);
  if (strict ? a < 1e-12f : std::fabs(a) < 1e-12f) return false;
  const float f = 1.0f / a;
  const glm::vec3 s = o - t.v0;
  const float u = f * glm::dot(s, h);
  if (strict ? u <= 0.0f || u >= 1.0f : u < 0.0f || u > 1.0f) return false;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = f * glm::dot(d, q);
  if (strict ? v <= 0.0f || u + v >= 1.0f : v < 0.0f || u + v > 1.0f) return false;
  const float tt = f * glm::dot(e2, q);
  return tt > t_min && tt < 1.0f;
}

// Distance between segments [p0, p1] and [q0, q1] (closest points, clamped), in double.
double segment_distance(glm::dvec3 p0, glm::dvec3 p1, glm::dvec3 q0, glm::dvec3 q1) {
  const glm::dvec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  const double c = glm::dot(d1, r), b = glm::dot(d1, d2), denom = a * e - b * b;
  double s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return glm::length((p0 + s * d1) - (q0 + t * d2));
}

const char* const shared_edges_source =
    R"({"scene": {"generator": "shared_edges", "triangles": 20000},
  "camera": {"width": 128, "height": 128}})";

struct Exported {
  fs::path dir, manifest;
  Case c;
  ViewSamples samples;
  HardShadowTruth truth;
};

// `shadowcts export <source> --out export` in a fresh folder (with `manifest` as source.json
// there, where given), and the exported case loaded back.
Exported export_case(const std::string& name, const std::string& source,
                     const char* manifest = nullptr) {
  Exported e;
  e.dir = fresh_dir(name);
  if (manifest) std::ofstream(e.dir / "source.json") << manifest;
  EXPECT_EQ(run_tool("export " + source + " --out export", e.dir), 0)
      << read_file(e.dir / "stderr.txt");
  e.manifest = e.dir / "export" / "case.json";
  e.c = load_case_manifest(e.manifest.string());
  e.samples = read_gbuffer_exr(e.c.gbuffer_path);
  classify_samples(e.c, e.samples, e.c.gbuffer_path);
  e.truth = exact_hard_shadow_oracle(e.c, e.samples);
  return e;
}

// A smaller frame than the fixture's keeps the test's brute-force ray caster quick.
Exported export_shared_edges(const std::string& name) {
  return export_case(name, "--case source.json", shared_edges_source);
}

json only_record(const fs::path& out) {
  const json results = json::parse(read_file(out / "results.json"));
  EXPECT_EQ(results["results"].size(), 1u);
  return results["results"][0];
}

TEST(FrameCheck, ExportedCaseLoadsBackWithClosedMeshesAndTheGbuffer) {
  const Exported e = export_shared_edges("export");
  const Case original = [] {
    const fs::path dir = fresh_dir("export_original");
    std::ofstream(dir / "m.json") << shared_edges_source;
    return load_case_manifest((dir / "m.json").string());
  }();
  ASSERT_EQ(e.c.triangles.size(), original.triangles.size());
  for (std::size_t t = 0; t < original.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = (&e.c.triangles[t].v0)[k], b = (&original.triangles[t].v0)[k];
      using Bits = std::array<std::uint32_t, 3>;
      ASSERT_EQ(std::bit_cast<Bits>(a), std::bit_cast<Bits>(b)) << "triangle " << t;
    }
  ASSERT_EQ(e.c.meshes.size(), original.meshes.size());
  for (std::size_t m = 0; m < original.meshes.size(); ++m)
    EXPECT_EQ(e.c.meshes[m].closed, original.meshes[m].closed) << original.meshes[m].name;
  EXPECT_EQ(e.samples.width, original.camera.width);
  ASSERT_TRUE(e.c.light);
  EXPECT_EQ(e.c.light->position, original.light->position);
}

// Renders the exported case with the naive caster (1e-4 offset along the segment), checks the
// mask and returns the robust leaks the exact oracle finds in it, after checking that `check`
// reports exactly those figures.
// `sharing`: how many triangles share the edge that every leak's segment must pass (2: a shared
// edge; 1: any edge, as at a T-junction's crack).
std::vector<std::size_t> check_naive_render(const Exported& e, bool strict, int sharing = 2) {
  // A directional light as a point far along its direction.
  const auto light_of = [&](const glm::vec3& p) {
    return e.c.light->kind == ShadowLightKind::point
               ? e.c.light->position
               : p + float(4.0 * e.c.scale()) * e.c.light->direction;
  };
  std::vector<float> mask(e.samples.samples.size(), 0.0f);
  for (std::size_t i = 0; i < e.samples.samples.size(); ++i) {
    const ViewSample& s = e.samples.samples[i];
    if (s.sample_class == SampleClass::sky) continue;
    const glm::vec3 d = light_of(s.position) - s.position;
    for (const Triangle& t : e.c.triangles)
      if (float_hit(s.position, d, t, 1e-4f, strict)) {
        mask[i] = 1.0f;
        break;
      }
  }
  write_channel(e.dir / "export" / "mask.exr", e.samples.width, e.samples.height, mask);
  if (::testing::Test::HasFatalFailure()) return {};
  add_result(e.manifest, {{"mask", "mask.exr"}});

  // The robust mismatches, from the exact oracle directly.
  std::vector<std::size_t> leaks;
  std::size_t false_shadows = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (e.truth.band[i] != BandClass::robust_lit && e.truth.band[i] != BandClass::robust_shadowed)
      continue;
    const bool shadowed = mask[i] > 0.5f;
    if (shadowed == bool(e.truth.shadowed[i])) continue;
    if (shadowed)
      ++false_shadows;
    else
      leaks.push_back(i);
  }
  const int rc = run_tool("check --case export/case.json --out out", e.dir);
  EXPECT_EQ(rc, leaks.empty() && false_shadows == 0 ? 0 : 1) << read_file(e.dir / "stderr.txt");
  const json record = only_record(e.dir / "out");
  EXPECT_EQ(record["algorithm"], "frame");
  EXPECT_EQ(record["backend"], "external");
  EXPECT_EQ(record["variant"], "mask");
  EXPECT_EQ(record["verdict"], leaks.empty() && false_shadows == 0 ? "Pass" : "Fail");
  EXPECT_EQ(record["error"]["leaks"], leaks.size()) << record["error"].dump();
  EXPECT_EQ(record["error"]["false_shadows"], false_shadows);
  EXPECT_NE(read_file(e.dir / "out" / "junit.xml").find("mask.external"), std::string::npos);

  // Every leak's shadow segment runs through an edge of `sharing` triangles or more.
  std::map<std::pair<std::array<std::uint32_t, 3>, std::array<std::uint32_t, 3>>, int> edges;
  auto key = [](const glm::vec3& v) { return std::bit_cast<std::array<std::uint32_t, 3>>(v); };
  for (const Triangle& t : e.c.triangles) {
    const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
    for (int k = 0; k < 3; ++k) {
      auto a = key(v[k]), b = key(v[(k + 1) % 3]);
      ++edges[std::minmax(a, b)];
    }
  }
  const double scale = e.c.scale();
  for (std::size_t i : leaks) {
    const ViewSample& s = e.samples.samples[i];
    double nearest = INFINITY;
    for (const auto& [edge, count] : edges) {
      if (count < sharing) continue;
      nearest = std::min(nearest,
                         segment_distance(glm::dvec3(s.position), glm::dvec3(light_of(s.position)),
                                          glm::dvec3(std::bit_cast<glm::vec3>(edge.first)),
                                          glm::dvec3(std::bit_cast<glm::vec3>(edge.second))));
    }
    EXPECT_LT(nearest, 1e-5 * scale) << "leak at pixel " << s.pixel_x << "," << s.pixel_y;
  }
  return leaks;
}

// Measured: inclusive edge tests keep shared_edges watertight at this size (no robust mismatch).
TEST(FrameCheck, NaiveInclusiveRayCasterPasses) {
  EXPECT_TRUE(check_naive_render(export_shared_edges("inclusive"), false).empty());
}

// Strict edge tests leak, and every leak lies on a shared edge.
TEST(FrameCheck, NaiveStrictRayCasterLeaksAtSharedEdges) {
  EXPECT_GT(check_naive_render(export_shared_edges("strict"), true).size(), 0u);
}

// The fuzz cases export with their own samples, aimed through shared edges and vertices of closed
// and open surfaces and T-junctions: an engine shades the G-buffer's positions and check judges
// them like any frame. The strict caster leaks there too, every leak on an edge.
TEST(FrameCheck, FuzzCasesExportWithTheirOwnSamplesForEnginesToShade) {
  std::size_t leaks = 0;
  for (int i = 0; i < 4; ++i) {
    const std::string fixture = "fuzz.watertight.1." + std::to_string(i);
    SCOPED_TRACE(fixture);
    const Exported e = export_case("fuzz_" + std::to_string(i), "--fixture " + fixture);
    EXPECT_NE(read_file(e.dir / "stdout.txt").find("G-buffer of the case's own samples"),
              std::string::npos);
    if (::testing::Test::HasFailure()) return;
    leaks += check_naive_render(e, true, 1).size();
  }
  EXPECT_GE(leaks, 4u);  // measured: 31 in these four cases
}

TEST(FrameCheck, OracleMaskPassesInBothConventions) {
  const Exported e = export_shared_edges("oracle");
  std::vector<float> shadow(e.truth.shadowed.begin(), e.truth.shadowed.end());
  std::vector<float> visible(shadow.size());
  for (std::size_t i = 0; i < shadow.size(); ++i) visible[i] = 1.0f - shadow[i];
  write_channel(e.dir / "export" / "shadow.exr", e.samples.width, e.samples.height, shadow);
  write_channel(e.dir / "export" / "visible.exr", e.samples.width, e.samples.height, visible, "V");
  add_result(e.manifest, {{"mask", "shadow.exr"}});
  EXPECT_EQ(run_tool("check --case export/case.json --out out", e.dir), 0)
      << read_file(e.dir / "stdout.txt") << read_file(e.dir / "stderr.txt");
  EXPECT_EQ(only_record(e.dir / "out")["verdict"], "Pass");
  EXPECT_NE(read_file(e.dir / "stdout.txt").find("frame:mask [external]"), std::string::npos);
  add_result(e.manifest, {{"mask", "visible.exr"}, {"mask_values", "visible"}});
  EXPECT_EQ(run_tool("check --case export/case.json --out out", e.dir), 0);
  EXPECT_EQ(only_record(e.dir / "out")["verdict"], "Pass");
  // The same file read as a shadow amount is everywhere wrong.
  add_result(e.manifest, {{"mask", "visible.exr"}});
  EXPECT_EQ(run_tool("check --case export/case.json --out out", e.dir), 1);
}

TEST(FrameCheck, BadMasksExitTwoNamingFileChannelAndPixelAndWriteNothing) {
  const Exported e = export_shared_edges("bad");
  const std::uint32_t w = e.samples.width, h = e.samples.height;
  std::vector<float> mask(std::size_t(w) * h, 0.0f);
  mask[5 * w + 3] = std::nanf("");
  write_channel(e.dir / "export" / "nan.exr", w, h, mask);
  mask[5 * w + 3] = 1.5f;
  write_channel(e.dir / "export" / "range.exr", w, h, mask);
  write_channel(e.dir / "export" / "small.exr", w - 1, h,
                std::vector<float>(std::size_t(w - 1) * h));
  struct Bad {
    json result;
    std::string message;
  };
  for (const Bad& bad :
       {Bad{{{"mask", "nan.exr"}}, "nan.exr: channel Y, pixel (3, 5): is NaN"},
        Bad{{{"visibility", "range.exr"}}, "range.exr: channel Y, pixel (3, 5): value 1.5"},
        Bad{{{"mask", "small.exr"}},
            "small.exr: dataWindow: 127x128 differs from the case camera's 128x128"},
        Bad{{{"mask", "missing.exr"}}, "result.mask: file"},
        Bad{{{"mask", "nan.exr"}, {"visibility", "nan.exr"}}, "give exactly one of"}}) {
    add_result(e.manifest, bad.result);
    EXPECT_EQ(run_tool("check --case export/case.json --out out", e.dir), 2) << bad.message;
    EXPECT_NE(read_file(e.dir / "stderr.txt").find(bad.message), std::string::npos)
        << read_file(e.dir / "stderr.txt");
    EXPECT_FALSE(fs::exists(e.dir / "out")) << bad.message;
  }
}

// Soft visibility: the exact disk oracle's fractions pass; a frame without penumbrae (every
// sample fully lit) fails beyond the declared budget; the budget key is read.
TEST(FrameCheck, SoftVisibilityIsJudgedAgainstTheDiskOracle) {
  const fs::path dir = fresh_dir("soft");
  std::ofstream(dir / "source.json") << R"({"scene": {"generator": "foliage", "triangles": 100},
    "camera": {"width": 48, "height": 48}})";
  ASSERT_EQ(run_tool("export --case source.json --out export", dir), 0)
      << read_file(dir / "stderr.txt");
  const fs::path manifest = dir / "export" / "case.json";
  const Case c = load_case_manifest(manifest.string());
  ASSERT_TRUE(c.light && c.light->kind == ShadowLightKind::sun_disk);
  ViewSamples samples = read_gbuffer_exr(c.gbuffer_path);
  classify_samples(c, samples, c.gbuffer_path);
  const SoftShadowTruth truth = exact_soft_shadow_oracle(c, samples);
  std::vector<float> exact(samples.samples.size()), lit(samples.samples.size(), 1.0f);
  bool penumbra = false;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    exact[i] = float(truth.visible_fraction[i]);
    penumbra |= truth.compared[i] && truth.robust[i] && exact[i] < 0.9f;
  }
  ASSERT_TRUE(penumbra)
      << "the all-lit frame must be wrong by more than its 0.05 budget on a robust sample";
  write_channel(dir / "export" / "exact.exr", c.camera.width, c.camera.height, exact);
  write_channel(dir / "export" / "lit.exr", c.camera.width, c.camera.height, lit);
  add_result(manifest, {{"visibility", "exact.exr"}});
  EXPECT_EQ(run_tool("check --case export/case.json --out out", dir), 0)
      << read_file(dir / "stdout.txt");
  json record = only_record(dir / "out");
  EXPECT_EQ(record["output"], "soft");
  EXPECT_EQ(record["variant"], "visibility");
  EXPECT_EQ(record["verdict"], "Pass");
  add_result(manifest,
             {{"visibility", "lit.exr"}, {"budget", {{"per_sample", 0.05}, {"mean", 0.1}}}});
  EXPECT_EQ(run_tool("check --case export/case.json --out out", dir), 1);
  record = only_record(dir / "out");
  EXPECT_EQ(record["verdict"], "Fail");
  EXPECT_EQ(record["error"]["budget"]["per_sample"], 0.05);
  add_result(manifest, {{"mask", "lit.exr"}, {"budget", {{"mean", 0.1}}}});
  EXPECT_EQ(run_tool("check --case export/case.json --out out", dir), 2);
  EXPECT_NE(
      read_file(dir / "stderr.txt").find("result.budget: belongs to a visibility result only"),
      std::string::npos);
}

// Light lists: Olsson-style 2D tiles and Filament-style froxels over many_lights.
TEST(FrameCheck, LightListsAreJudgedLikeLightAssignment) {
  const fs::path dir = fresh_dir("lights");
  std::ofstream(dir / "m.json") << R"({"scene": {"generator": "many_lights", "triangles": 100},
    "camera": {"width": 64, "height": 64}, "result": {"light_lists": "lists.json"}})";
  std::ofstream(dir / "lists.json") << "{}";  // the manifest names an existing file
  const Case c = load_case_manifest((dir / "m.json").string());
  const std::size_t n = c.ranged_lights.size();
  ASSERT_GT(n, 3u);
  std::vector<std::uint32_t> all(n);
  for (std::size_t k = 0; k < n; ++k) all[k] = std::uint32_t(k);
  // Every light in every 32x32 tile: complete, but lights listed where they cannot reach.
  std::ofstream(dir / "lists.json")
      << json{{"tile_width", 32}, {"tile_height", 32}, {"lists", std::vector<json>(4, all)}}.dump();
  EXPECT_EQ(run_tool("check --case m.json --out out", dir), 1);
  json record = only_record(dir / "out");
  EXPECT_EQ(record["output"], "lights");
  EXPECT_EQ(record["error"]["completeness_misses"], 0);
  EXPECT_GT(record["error"]["unsound_listings"], 0);
  // No light anywhere: every sample inside a light's volume is a miss.
  std::ofstream(dir / "lists.json") << json{{"tile_width", 16},
                                            {"tile_height", 16},
                                            {"depth_slices",
                                             {{"function", "exponential_with_near_slice"},
                                              {"count", 8},
                                              {"near", 0.1},
                                              {"split", 2},
                                              {"far", 100}}},
                                            {"lists", std::vector<json>(4 * 4 * 8, json::array())}}
                                           .dump();
  EXPECT_EQ(run_tool("check --case m.json --out out", dir), 1);
  record = only_record(dir / "out");
  EXPECT_GT(record["error"]["completeness_misses"], 0);
  EXPECT_EQ(record["error"]["unsound_listings"], 0);
  EXPECT_EQ(record["error"]["lists"], 128);
  // Layout errors: a list count that is not the grid's, a light index out of range.
  std::ofstream(dir / "lists.json")
      << json{{"tile_width", 32}, {"tile_height", 32}, {"lists", std::vector<json>(3, all)}}.dump();
  fs::remove_all(dir / "out");
  EXPECT_EQ(run_tool("check --case m.json --out out", dir), 2);
  EXPECT_NE(read_file(dir / "stderr.txt").find("lists.json: lists: has 3 lists, the grid has 4"),
            std::string::npos)
      << read_file(dir / "stderr.txt");
  std::vector<json> lists(4, all);
  lists[2] = json::array({0, n});
  std::ofstream(dir / "lists.json")
      << json{{"tile_width", 32}, {"tile_height", 32}, {"lists", lists}}.dump();
  EXPECT_EQ(run_tool("check --case m.json --out out", dir), 2);
  EXPECT_NE(read_file(dir / "stderr.txt").find("lists[2][1]: light index " + std::to_string(n)),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace shadowcts
