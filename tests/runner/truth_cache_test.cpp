// The truth cache must never change a verdict: an entry is used only for byte-identical inputs of
// the same build, a damaged one is recomputed, and a run from the cache writes the same records
// (including the mismatch curve, whose exponents the exact oracle computes on demand).
#include "truth_cache.h"

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shadowcts/errors.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("shadowcts_truth_cache_" + name);
  fs::remove_all(dir);
  return dir;
}

// A small case and samples: the cache compares them, the oracles are not run here.
Case small_case() {
  Case c;
  c.meshes = {{"ground", true, true}, {"box", false, false}};
  c.triangles = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0}, {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, 1}};
  c.light = ShadowLight{ShadowLightKind::sun_disk, {0, 0, 0}, {0, 0, 1}, 0.01f};
  c.ranged_lights = {{RangedLightKind::spot, {1, 2, 3}, 4, {0, 0, -1}, 0.5f}};
  return c;
}

ViewSamples small_samples() {
  ViewSamples s;
  s.width = 2;
  s.height = 1;
  s.samples = {{{0.25f, 0.25f, 0}, {0, 0, 1}, 0, 0, 0, SampleClass::regular},
               {{0, 0, 0}, {0, 0, 0}, no_receiver, 1, 0, SampleClass::sky}};
  return s;
}

HardShadowTruth random_hard_truth(std::mt19937& rng) {
  HardShadowTruth t;
  t.method = "test hard";
  t.exact = true;
  t.eps_rel = 0x1p-16;
  t.tau = 0x1p-15;
  for (int i = 0; i < 100; ++i) {
    t.shadowed.push_back(std::uint8_t(rng() % 2));
    t.band.push_back(BandClass(rng() % 4));
    t.robust_exponent.push_back(std::int8_t(int(rng() % 20) - 25));
  }
  return t;
}

SoftShadowTruth random_soft_truth(std::mt19937& rng) {
  SoftShadowTruth t;
  t.method = "test soft";
  t.exact = false;
  t.eps_rel = 0x1p-16;
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 100; ++i) {
    t.visible_fraction.push_back(u(rng));
    t.error_bound.push_back(u(rng) * 1e-3);
    t.band_sensitivity.push_back(u(rng));
    t.robust.push_back(std::uint8_t(rng() % 2));
    t.compared.push_back(std::uint8_t(rng() % 2));
  }
  t.candidate_triangles = rng();
  t.fast_path_samples = rng();
  return t;
}

LightAssignmentTruth random_light_truth(std::mt19937& rng) {
  LightAssignmentTruth t;
  t.method = "test lights";
  t.normal_rule = true;
  for (int i = 0; i < 50; ++i) {
    for (std::uint32_t k = rng() % 4; k > 0; --k) t.lights.push_back(rng() % 1000);
    t.offsets.push_back(t.lights.size());
    if (rng() % 3 == 0) t.ambiguous_lights.push_back(rng() % 1000);
    t.ambiguous_offsets.push_back(t.ambiguous_lights.size());
  }
  t.candidate_pairs = rng();
  t.band_move_pairs = rng();
  return t;
}

void expect_same(const HardShadowTruth& a, const HardShadowTruth& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.exact, b.exact);
  EXPECT_EQ(a.eps_rel, b.eps_rel);
  EXPECT_EQ(a.tau, b.tau);
  EXPECT_EQ(a.shadowed, b.shadowed);
  EXPECT_EQ(a.band, b.band);
  EXPECT_EQ(a.robust_exponent, b.robust_exponent);
}

void expect_same(const SoftShadowTruth& a, const SoftShadowTruth& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.exact, b.exact);
  EXPECT_EQ(a.eps_rel, b.eps_rel);
  EXPECT_EQ(a.visible_fraction, b.visible_fraction);
  EXPECT_EQ(a.error_bound, b.error_bound);
  EXPECT_EQ(a.band_sensitivity, b.band_sensitivity);
  EXPECT_EQ(a.robust, b.robust);
  EXPECT_EQ(a.compared, b.compared);
  EXPECT_EQ(a.candidate_triangles, b.candidate_triangles);
  EXPECT_EQ(a.fast_path_samples, b.fast_path_samples);
}

void expect_same(const LightAssignmentTruth& a, const LightAssignmentTruth& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.normal_rule, b.normal_rule);
  EXPECT_EQ(a.offsets, b.offsets);
  EXPECT_EQ(a.lights, b.lights);
  EXPECT_EQ(a.ambiguous_offsets, b.ambiguous_offsets);
  EXPECT_EQ(a.ambiguous_lights, b.ambiguous_lights);
  EXPECT_EQ(a.candidate_pairs, b.candidate_pairs);
  EXPECT_EQ(a.band_move_pairs, b.band_move_pairs);
}

// Asks the cache twice for `oracle`: the first computes, the second must hit and return the same.
template <class Truth>
void expect_round_trip(const TruthCache& cache, const std::string& oracle, const Truth& truth) {
  const Case c = small_case();
  const ViewSamples s = small_samples();
  int computed = 0;
  const std::function<Truth()> compute = [&] {
    ++computed;
    return truth;
  };
  TruthCacheUse first, second;
  expect_same(cache.get(oracle, c, s, compute, first), truth);
  const Truth again = cache.get(oracle, c, s, compute, second);
  EXPECT_EQ(computed, 1) << oracle;
  EXPECT_FALSE(first.hit);
  EXPECT_TRUE(second.hit) << second.note;
  EXPECT_EQ(first.entry, second.entry);
  EXPECT_EQ(first.computed_ms, second.computed_ms);
  expect_same(again, truth);
}

TEST(TruthCache, EveryTruthKindComesBackBitForBit) {
  ASSERT_FALSE(program_build_id().empty()) << "the test program has no GNU build id";
  const TruthCache cache(fresh_folder("round_trip"));
  std::mt19937 rng(7);
  expect_round_trip(cache, "hard.exact", random_hard_truth(rng));
  expect_round_trip(cache, "soft.exact", random_soft_truth(rng));
  expect_round_trip(cache, "lights.plain", random_light_truth(rng));
}

// Counts how often a get of the same oracle recomputes across a change of the inputs.
class Recomputes {
 public:
  explicit Recomputes(const fs::path& dir) : cache_(dir) {}
  bool after(const Case& c, const ViewSamples& s, TruthCacheUse* use = nullptr) {
    TruthCacheUse local;
    int computed = 0;
    cache_.get("hard.exact", c, s, std::function<HardShadowTruth()>([&] {
                 ++computed;
                 return HardShadowTruth{};
               }),
               use ? *use : local);
    return computed == 1;
  }

 private:
  TruthCache cache_;
};

TEST(TruthCache, AnyChangedInputRecomputes) {
  Recomputes cache(fresh_folder("inputs"));
  const Case c = small_case();
  const ViewSamples s = small_samples();
  EXPECT_TRUE(cache.after(c, s));
  EXPECT_FALSE(cache.after(c, s));

  Case moved = c;  // one float step of one vertex
  moved.triangles[1].v2.z = std::nextafter(moved.triangles[1].v2.z, 2.0f);
  EXPECT_TRUE(cache.after(moved, s));
  Case band = c;
  band.parameters.eps_rel = 0x1p-18;
  EXPECT_TRUE(cache.after(band, s));
  Case light = c;
  light.light->angular_radius = 0.02f;
  EXPECT_TRUE(cache.after(light, s));
  Case caster = c;
  caster.meshes[1].caster = true;
  EXPECT_TRUE(cache.after(caster, s));
  ViewSamples normal = s;
  normal.samples[0].normal.x = 1e-30f;
  EXPECT_TRUE(cache.after(c, normal));
  ViewSamples receiver = s;
  receiver.samples[0].receiver = 1;
  EXPECT_TRUE(cache.after(c, receiver));
  // What the oracles do not read does not matter: names, repeats, threads.
  Case renamed = c;
  renamed.name = "other";
  renamed.parameters.repeats = 9;
  renamed.parameters.threads = 1;
  EXPECT_FALSE(cache.after(renamed, s));
}

TEST(TruthCache, DamagedEntriesAreRecomputedNeverTrusted) {
  const fs::path dir = fresh_folder("damaged");
  Recomputes cache(dir);
  const Case c = small_case();
  const ViewSamples s = small_samples();
  TruthCacheUse use;
  ASSERT_TRUE(cache.after(c, s, &use));
  const fs::path entry = dir / use.entry;
  ASSERT_TRUE(fs::exists(entry));
  std::string bytes;
  {
    std::ifstream in(entry, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  auto write = [&](const std::string& contents) {
    std::ofstream out(entry, std::ios::binary | std::ios::trunc);
    out << contents;
  };
  for (std::size_t at : {std::size_t(3), bytes.size() / 2, bytes.size() - 1}) {
    std::string flipped = bytes;
    flipped[at] = char(flipped[at] ^ 0x10);
    write(flipped);
    TruthCacheUse again;
    EXPECT_TRUE(cache.after(c, s, &again)) << "byte " << at;
    EXPECT_EQ(again.note, "damaged entry recomputed");
    EXPECT_FALSE(cache.after(c, s)) << "the recomputed entry replaced the damaged one";
  }
  write(bytes.substr(0, bytes.size() / 3));
  EXPECT_TRUE(cache.after(c, s));
  write("");
  EXPECT_TRUE(cache.after(c, s));
}

TEST(TruthCache, AFileInTheWayIsAUsageError) {
  const fs::path path = fresh_folder("file");
  std::ofstream(path) << "not a folder";
  EXPECT_THROW(TruthCache{path}, UsageError);
  fs::remove(path);
}

// Says every sample is lit: every robust-shadowed sample is a leak, so the mismatch curve needs
// the exact oracle's exponents of all of them (computed on demand, also from a cached truth).
class AllLit : public Algorithm {
 public:
  AllLit() {
    info_.id = "all_lit";
    info_.backend = "test";
    info_.variants = {"lit"};
    info_.summary = "answers lit everywhere";
    info_.capabilities.point_light = info_.capabilities.directional_light = true;
  }
  const AlgorithmInfo& info() const override { return info_; }
  AlgorithmOutput run(const PreparedScene& scene, const std::string&) const override {
    AlgorithmOutput out;
    out.shadowed.assign(scene.view_samples.samples.size(), 0);
    return out;
  }

 private:
  AlgorithmInfo info_;
};

nlohmann::json run_with_cache(const fs::path& cache, const std::string& name) {
  Registry registry;
  registry.add(std::make_unique<AllLit>());
  const fs::path out = fresh_folder(name);
  RunOptions options;
  options.fixtures = {"ground_blockers.2k"};
  options.out_dir = out.string();
  options.repeats = 1;
  options.truth_cache_dir = cache.string();
  std::ostringstream log, err;
  EXPECT_EQ(run_suite(options, registry, log, err), exit_conformance_failure) << log.str();
  std::ifstream in(out / "results.json");
  return nlohmann::json::parse(in);
}

TEST(TruthCache, ARunFromTheCacheWritesTheSameRecords) {
  const fs::path cache = fresh_folder("runs");
  const nlohmann::json first = run_with_cache(cache, "run1");
  const nlohmann::json second = run_with_cache(cache, "run2");
  const auto& oracle1 = first["cases"][0]["oracles"]["hard"];
  const auto& oracle2 = second["cases"][0]["oracles"]["hard"];
  EXPECT_FALSE(oracle1["truth_cache"][0]["hit"].get<bool>());
  EXPECT_TRUE(oracle2["truth_cache"][0]["hit"].get<bool>());
  for (const char* key : {"method", "robust_lit", "robust_shadowed", "ambiguous"})
    EXPECT_EQ(oracle1[key], oracle2[key]) << key;
  const auto& r1 = first["results"][0];
  const auto& r2 = second["results"][0];
  EXPECT_EQ(r1["verdict"], "Fail");
  EXPECT_GT(r1["error"]["leaks"].get<int>(), 0);
  EXPECT_EQ(r1["verdict"], r2["verdict"]);
  EXPECT_EQ(r1["reason"], r2["reason"]);
  EXPECT_EQ(r1["error"], r2["error"]);  // mismatch curve included
}

}  // namespace
}  // namespace shadowcts
