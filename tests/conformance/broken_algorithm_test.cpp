// The comparator must catch real bugs: two deliberately broken hard-shadow algorithms run through
// the runner and must get Fail, with the right kind of mismatch.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"
#include "shadowcts/verdict.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

enum class Bug {
  open_edges,    // edges and vertices do not count: rays through shared edges leak
  missing_edge,  // the test against edge v2 -> v0 is left out: a half-plane wedge shadows
};

// Double-precision barycentric segment test with one bug in it.
bool occludes(const Triangle& t, const glm::dvec3& p, const glm::dvec3& d, double t_max, Bug bug) {
  const glm::dvec3 a(t.v0), b(t.v1), c(t.v2);
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 q = glm::cross(d, e2);
  const double det = glm::dot(e1, q);
  if (det == 0.0) return false;
  const glm::dvec3 s = p - a;
  const double u = glm::dot(s, q) / det;
  const glm::dvec3 r = glm::cross(s, e1);
  const double v = glm::dot(d, r) / det;
  const double dist = glm::dot(e2, r) / det;
  if (!(dist > 1e-9 * t_max && dist <= t_max)) return false;
  switch (bug) {
    case Bug::open_edges:
      return u > 0 && v > 0 && u + v < 1;
    case Bug::missing_edge:
      return v >= 0 && u + v <= 1;  // u >= 0 (edge v2 -> v0) is missing
  }
  return false;
}

class BrokenHardShadow : public Algorithm {
 public:
  BrokenHardShadow(std::string id, Bug bug) : bug_(bug) {
    info_.id = std::move(id);
    info_.backend = "test";
    info_.variants = {"broken"};
    info_.summary = "deliberately broken for the comparator test";
    info_.capabilities.point_light = info_.capabilities.directional_light = true;
  }
  const AlgorithmInfo& info() const override { return info_; }
  AlgorithmOutput run(const PreparedScene& scene, const std::string&) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    AlgorithmOutput out;
    out.shadowed.assign(samples.samples.size(), 0);
    for (std::size_t i = 0; i < samples.samples.size(); ++i) {
      const ViewSample& s = samples.samples[i];
      if (s.sample_class != SampleClass::regular) continue;
      const glm::dvec3 p(s.position);
      const bool point = c.light->kind == ShadowLightKind::point;
      const glm::dvec3 d =
          point ? glm::dvec3(c.light->position) - p : glm::dvec3(c.light->direction);
      const double t_max = point ? 1.0 : 1e30;
      for (std::size_t k = 0; k < c.triangles.size() && !out.shadowed[i]; ++k)
        if (k != s.receiver && c.meshes[c.triangles[k].mesh].caster)
          out.shadowed[i] = occludes(c.triangles[k], p, d, t_max, bug_);
    }
    return out;
  }

 private:
  AlgorithmInfo info_;
  Bug bug_;
};

nlohmann::json run_broken(const std::string& fixture, const std::string& name) {
  Registry registry;
  registry.add(std::make_unique<BrokenHardShadow>("open_edges", Bug::open_edges));
  registry.add(std::make_unique<BrokenHardShadow>("missing_edge", Bug::missing_edge));
  const fs::path out = fs::temp_directory_path() / ("shadowcts_broken_" + name);
  fs::remove_all(out);
  RunOptions options;
  options.fixtures = {fixture};
  options.out_dir = out.string();
  options.repeats = 1;
  std::ostringstream log, err;
  EXPECT_EQ(run_suite(options, registry, log, err), exit_conformance_failure) << log.str();
  std::ifstream in(out / "results.json");
  return nlohmann::json::parse(in);
}

const nlohmann::json& record(const nlohmann::json& results, const std::string& algorithm) {
  for (const auto& r : results["results"])
    if (r["algorithm"] == algorithm) return r;
  throw std::runtime_error("no record for " + algorithm);
}

TEST(BrokenAlgorithm, OpenEdgesLeakThroughSharedEdges) {
  // The shared_edges fixture aims shadow segments exactly at shared edges and vertices of closed
  // slabs: those samples are robust-shadowed, and an open-edge test lets them through.
  const auto results = run_broken("shared_edges.1k", "shared");
  const auto& r = record(results, "open_edges");
  EXPECT_EQ(r["verdict"], "Fail");
  EXPECT_GT(r["error"]["leaks"].get<int>(), 0);
  EXPECT_EQ(r["error"]["false_shadows"], 0);
  // The curve at the run's eps_rel (2^-16) counts exactly these leaks, and grows as the band
  // shrinks: the leaks are not rounding, they stay at 2^-24.
  for (const auto& point : r["error"]["mismatch_curve"]) {
    if (point["eps_rel_log2"] == -16) {
      EXPECT_EQ(point["robust_mismatches"], r["error"]["leaks"]);
    }
    if (point["eps_rel_log2"] == -24) {
      EXPECT_GE(point["robust_mismatches"].get<int>(), r["error"]["leaks"].get<int>());
    }
  }
}

TEST(BrokenAlgorithm, AMissingEdgeTestCastsFalseShadows) {
  const auto results = run_broken("ground_blockers.2k", "ground");
  const auto& r = record(results, "missing_edge");
  EXPECT_EQ(r["verdict"], "Fail");
  EXPECT_GT(r["error"]["false_shadows"].get<int>(), 0);
}

// --- Approximate algorithms: the ceiling on the robust mismatch rate. ------------------------

const Algorithm& registered_shadowmap() {
  const Algorithm* a = builtin_registry().find("shadowmap", "reference");
  if (!a) throw std::runtime_error("no shadowmap [reference] registered");
  return *a;
}

// The registered shadow map, broken: its answer inverted on every regular sample but every 50th.
// Wrong on about 98 % of the robust samples; it declares the shadow map's own ceilings.
class InvertedShadowMap : public Algorithm {
 public:
  InvertedShadowMap() : info_(registered_shadowmap().info()) {
    info_.id = "inverted_shadowmap";
    info_.backend = "test";
  }
  const AlgorithmInfo& info() const override { return info_; }
  double robust_mismatch_ceiling(const std::string& variant) const override {
    return registered_shadowmap().robust_mismatch_ceiling(variant);
  }
  std::vector<std::string> timed_phases(const std::string& variant) const override {
    return registered_shadowmap().timed_phases(variant);
  }
  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    AlgorithmOutput out = registered_shadowmap().run(scene, variant);
    std::size_t regular = 0;
    for (std::size_t i = 0; i < out.shadowed.size(); ++i)
      if (scene.view_samples.samples[i].sample_class == SampleClass::regular && regular++ % 50 != 0)
        out.shadowed[i] ^= 1;
    return out;
  }

 private:
  AlgorithmInfo info_;
};

// An approximate algorithm wrong on exactly `wrong` robust samples (the first ones, by the exact
// oracle), declaring `ceiling`.
class WrongOnSomeRobustSamples : public Algorithm {
 public:
  WrongOnSomeRobustSamples(std::string id, std::size_t wrong, double ceiling)
      : wrong_(wrong), ceiling_(ceiling) {
    info_.id = std::move(id);
    info_.backend = "test";
    info_.variants = {"approximate"};
    info_.capabilities.point_light = info_.capabilities.directional_light = true;
    info_.capabilities.approximate = true;
  }
  const AlgorithmInfo& info() const override { return info_; }
  double robust_mismatch_ceiling(const std::string&) const override { return ceiling_; }
  AlgorithmOutput run(const PreparedScene& scene, const std::string&) const override {
    const HardShadowTruth truth = exact_hard_shadow_oracle(scene.source, scene.view_samples);
    AlgorithmOutput out;
    out.shadowed = truth.shadowed;
    std::size_t flipped = 0;
    for (std::size_t i = 0; i < out.shadowed.size() && flipped < wrong_; ++i)
      if (truth.band[i] == BandClass::robust_lit || truth.band[i] == BandClass::robust_shadowed) {
        out.shadowed[i] ^= 1;
        ++flipped;
      }
    return out;
  }

 private:
  AlgorithmInfo info_;
  std::size_t wrong_;
  double ceiling_;
};

nlohmann::json run_registry(const Registry& registry, const std::string& fixture,
                            const std::string& name, int expected_exit,
                            std::vector<AlgorithmSelection> algorithms = {}) {
  const fs::path out = fs::temp_directory_path() / ("shadowcts_broken_" + name);
  fs::remove_all(out);
  RunOptions options;
  options.fixtures = {fixture};
  options.algorithms = std::move(algorithms);
  options.out_dir = out.string();
  options.repeats = 1;
  std::ostringstream log, err;
  EXPECT_EQ(run_suite(options, registry, log, err), expected_exit) << log.str() << err.str();
  std::ifstream in(out / "results.json");
  auto results = nlohmann::json::parse(in);
  fs::remove_all(out);
  return results;
}

// The small point-light stiff scene (128 x 128): a cube map's case.
const char* const approximate_fixture = "stiff.walls_on_a_floor";

TEST(ApproximateCeiling, ShadowMapsDeclareACeilingBelowNinetySevenPercent) {
  for (const std::string& variant : registered_shadowmap().info().variants) {
    const double ceiling = registered_shadowmap().robust_mismatch_ceiling(variant);
    EXPECT_GT(ceiling, 0.0) << variant;
    EXPECT_LT(ceiling, 0.97) << variant;
  }
}

// The biased maps (the 4k and 8k maps cost seconds to rasterize: 1k and 2k stand for them; the
// unbiased map's acne makes its inversion right on a tenth of the samples, and its ceiling, like
// every other, is checked against 0.97 above).
TEST(ApproximateCeiling, AShadowMapWrongOnNinetySevenPercentFails) {
  Registry registry;
  registry.add(std::make_unique<InvertedShadowMap>());
  const auto results =
      run_registry(registry, approximate_fixture, "inverted_shadowmap", exit_conformance_failure,
                   {{"inverted_shadowmap", "1k"}, {"inverted_shadowmap", "2k"}});
  ASSERT_EQ(results["results"].size(), 2u);
  for (const auto& r : results["results"]) {
    EXPECT_EQ(r["verdict"], "Fail") << r["name"] << ": " << r["reason"];
    EXPECT_GE(r["error"]["robust_mismatch_rate"].get<double>(), 0.97) << r["name"];
    EXPECT_EQ(r["error"]["mismatch_ceiling"].get<double>(),
              registered_shadowmap().robust_mismatch_ceiling(r["variant"].get<std::string>()));
    EXPECT_NE(r["reason"].get<std::string>().find("above the declared ceiling"), std::string::npos)
        << r["reason"];
  }
}

// P(X >= k) for X ~ Binomial(n, p), summed in log space (independent of the runner's bound).
double binomial_upper_tail(std::size_t n, std::size_t k, double p) {
  double tail = 0.0;
  for (std::size_t j = k; j <= n; ++j)
    tail += std::exp(std::lgamma(double(n) + 1) - std::lgamma(double(j) + 1) -
                     std::lgamma(double(n - j) + 1) + double(j) * std::log(p) +
                     double(n - j) * std::log1p(-p));
  return tail;
}

// The ceiling is judged on the rate's lower confidence bound: the most mismatches a map at the
// ceiling shows with probability at least 1e-9 are a QualityWarning although their rate lies above
// the ceiling; one more fails.
TEST(ApproximateCeiling, AtTheCeilingQualityWarningOneMoreMismatchFail) {
  const Case c = make_fixture(approximate_fixture);
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, generate_view_samples(c));
  std::size_t robust = 0;
  for (const BandClass b : truth.band)
    robust += b == BandClass::robust_lit || b == BandClass::robust_shadowed;
  ASSERT_GT(robust, 1000u);
  const double ceiling = registered_shadowmap().robust_mismatch_ceiling("2k");
  std::size_t at = std::size_t(ceiling * double(robust));
  while (binomial_upper_tail(robust, at + 1, ceiling) >= statistical_verdict_failure_probability)
    ++at;
  ASSERT_GT(double(at) / double(robust), ceiling);
  Registry registry;
  registry.add(std::make_unique<WrongOnSomeRobustSamples>("at_ceiling", at, ceiling));
  registry.add(std::make_unique<WrongOnSomeRobustSamples>("above_ceiling", at + 1, ceiling));
  const auto results =
      run_registry(registry, approximate_fixture, "ceiling_line", exit_conformance_failure);
  const auto& within = record(results, "at_ceiling");
  EXPECT_EQ(within["verdict"], "QualityWarning") << within["reason"];
  EXPECT_EQ(within["error"]["leaks"].get<std::size_t>() +
                within["error"]["false_shadows"].get<std::size_t>(),
            at);
  EXPECT_LE(within["error"]["robust_mismatch_rate_lower_bound"].get<double>(), ceiling);
  const auto& beyond = record(results, "above_ceiling");
  EXPECT_EQ(beyond["verdict"], "Fail") << beyond["reason"];
  EXPECT_EQ(beyond["error"]["leaks"].get<std::size_t>() +
                beyond["error"]["false_shadows"].get<std::size_t>(),
            at + 1);
  EXPECT_GT(beyond["error"]["robust_mismatch_rate_lower_bound"].get<double>(), ceiling);
  EXPECT_NE(beyond["reason"].get<std::string>().find("above the declared ceiling"),
            std::string::npos)
      << beyond["reason"];
}

}  // namespace
}  // namespace shadowcts
