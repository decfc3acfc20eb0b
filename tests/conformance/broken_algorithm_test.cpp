// The comparator must catch real bugs: two deliberately broken hard-shadow algorithms run through
// the runner and must get Fail, with the right kind of mismatch.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

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

}  // namespace
}  // namespace shadowcts
