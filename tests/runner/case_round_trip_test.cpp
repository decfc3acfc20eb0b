// Cases written to files load back as the cases they were written from (runner/case_round_trip.h):
// fuzz cases through their reproducers (what certify and the fuzz targets leave behind) and
// through `shadowcts export` with their own samples, a fixture through export with its camera's;
// and the comparison sees every kind of change.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "case_reproducer.h"
#include "case_round_trip.h"
#include "fixtures/fuzz/fuzz_fixtures.h"
#include "scene_export.h"
#include "shadowcts/fixtures.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("shadowcts_round_trip_" + name);
  fs::remove_all(dir);
  return dir;
}

TEST(CaseRoundTrip, FuzzCasesReplayBitForBitFromTheirReproducers) {
  for (std::uint64_t seed : {1u, 2u})
    for (const std::string& name : fuzzing::fuzz_case_names(seed, 200)) {
      const fuzzing::SampleCase s = fuzzing::make_fuzz_case(name).sample_case;
      const fs::path dir = fresh_dir("reproducer");
      const std::string manifest = write_reproducer(dir.string(), s.c, s.samples);
      EXPECT_EQ(first_difference(s.c, s.samples, load_case_with_gbuffer(manifest)), "") << name;
    }
}

TEST(CaseRoundTrip, FuzzCasesExportWithTheirOwnSamples) {
  for (const std::string& name : fuzzing::fuzz_case_names(1, 100)) {
    SCOPED_TRACE(name);
    const fuzzing::SampleCase s = fuzzing::make_fuzz_case(name).sample_case;
    const fs::path dir = fresh_dir("export");
    std::ostringstream out;
    // export_case checks the round trip itself (it throws on a difference); this checks what it
    // checks against: each sample on the triangle it was on, at the same place.
    ASSERT_NO_THROW(export_case(s.c, s.samples, dir.string(), out));
    EXPECT_NE(out.str().find("of the case's own samples"), std::string::npos) << out.str();
    const LoadedCase loaded = load_case_with_gbuffer((dir / "case.json").string());
    ASSERT_EQ(loaded.samples.samples.size(), s.samples.samples.size());
    for (std::size_t i = 0; i < s.samples.samples.size(); ++i) {
      const ViewSample &a = s.samples.samples[i], &b = loaded.samples.samples[i];
      EXPECT_EQ(a.sample_class, b.sample_class) << i;
      if (a.sample_class == SampleClass::sky) continue;
      EXPECT_EQ(a.position, b.position) << i;
      const Triangle &t = s.c.triangles[a.receiver], &u = loaded.c.triangles[b.receiver];
      EXPECT_TRUE(t.v0 == u.v0 && t.v1 == u.v1 && t.v2 == u.v2) << i;
    }
  }
}

TEST(CaseRoundTrip, AFixtureExportsWithItsCameraSamples) {
  const Case c = make_fixture("shared_edge_fans.600");
  const fs::path dir = fresh_dir("fixture");
  std::ostringstream out;
  ASSERT_NO_THROW(export_case(c, std::nullopt, dir.string(), out));
  const LoadedCase loaded = load_case_with_gbuffer((dir / "case.json").string());
  EXPECT_EQ(loaded.samples.count(SampleClass::regular),
            generate_view_samples(c).count(SampleClass::regular));
}

TEST(CaseRoundTrip, EveryChangeIsADifference) {
  const fuzzing::SampleCase s = fuzzing::make_fuzz_case("fuzz.watertight.1.0").sample_case;
  const fs::path dir = fresh_dir("changes");
  const LoadedCase loaded = load_case_with_gbuffer(write_reproducer(dir.string(), s.c, s.samples));
  ASSERT_EQ(first_difference(s.c, s.samples, loaded), "");
  ASSERT_TRUE(s.c.light.has_value());
  const auto differs = [&](auto&& change) {
    fuzzing::SampleCase t = s;
    change(t);
    return first_difference(t.c, t.samples, loaded);
  };
  // The written vertex, then the loaded one, in hexadecimal.
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) {
              t.c.triangles[1].v2.x = std::nextafter(t.c.triangles[1].v2.x, 1e9f);
            }).rfind("triangle 1: vertex 2 (", 0),
            0u);
  const bool point = s.c.light->kind == ShadowLightKind::point;
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) {
              t.c.light->position.x = std::nextafter(t.c.light->position.x, 1e9f);
              t.c.light->direction.x = std::nextafter(t.c.light->direction.x, 1e9f);
            }),
            point ? "the point light's position" : "the light's direction");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) {
              t.c.meshes[t.c.triangles[0].mesh].closed = !t.c.meshes[t.c.triangles[0].mesh].closed;
            }),
            s.c.meshes[s.c.triangles[0].mesh].closed
                ? "triangle 0: its mesh is open, loads as closed"
                : "triangle 0: its mesh is closed, loads as open");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) {
              t.c.meshes[t.c.triangles[0].mesh].caster = !t.c.meshes[t.c.triangles[0].mesh].caster;
            }),
            "triangle 0: its mesh casts shadows, loads as casting none");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) { t.c.light->kind = ShadowLightKind::point; }),
            "the shadow light's kind");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) { t.c.light.reset(); }), "a shadow light");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) { t.c.ranged_lights.push_back(RangedLight{}); }),
            "loads 0 ranged lights, not 1");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) { t.c.camera.far_plane *= 2.0f; }), "the camera");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) { t.c.parameters.seed += 1; }), "the parameters");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) {
              t.samples.samples.back().normal = -t.samples.samples.back().normal;
            }),
            "sample " + std::to_string(s.samples.samples.size() - 1) + ": normal");
  EXPECT_EQ(differs([](fuzzing::SampleCase& t) { t.samples.samples[0].receiver += 1; }),
            "sample 0: receiver");
}

}  // namespace
}  // namespace shadowcts
