// The simd softtile diffed against the reference: the Highway rasterization gives the reference's
// disk bitmask rows on adversarial edges, per pixel on every tile of the soft fixtures (the first
// differing tile / pixel / row is reported), and the same answers and counters, for every variant,
// thread count and Highway target this CPU runs.
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <tbb/global_control.h>
#include <glm/geometric.hpp>

#include "reference/softtile/disk_bitmask.h"
#include "reference/softtile/fragment_occlusion.h"
#include "reference/softtile/softtile_algorithm.h"
#include "reference/softtile/softtile_gather.h"
#include "reference/softtile/softtile_tile.h"
#include "reference/softtile/softtile_variant.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/geometry/disk_reach.h"
#include "shadowcts/prepared_scene.h"
#include "simd/softtile/fragment_occlusion.h"
#include "simd/softtile/shadow_cone.h"
#include "simd/softtile/softtile_algorithm.h"
#include "simd/softtile/softtile_gather.h"
#include "tests/ports/output_difference.h"

namespace shadowcts {
namespace {

namespace ref = shadowcts::softtile;
namespace port = shadowcts::simd::softtile;

std::string first_row_difference(const ref::DiskBitmask& expected, const port::DiskRows& actual) {
  for (int r = 0; r < port::padded_rows; ++r) {
    const std::uint32_t want = r < expected.rows() ? expected.row(r) : 0u;
    if (actual.bits[r] != want) {
      std::ostringstream out;
      out << "row " << r << ": reference 0x" << std::hex << want << ", simd 0x" << actual.bits[r];
      return out.str();
    }
  }
  return "";
}

// Every Highway target this CPU runs, the best first; f() runs with each forced in turn.
template <class F>
void for_each_target(F&& f) {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  for (std::size_t t = 0; t < targets.size(); ++t) {
    SCOPED_TRACE(hwy::TargetName(targets[t]));
    if (t > 0) hwy::SetSupportedTargetsForTest(targets[t]);
    f();
    hwy::SetSupportedTargetsForTest(0);
  }
}

TEST(SimdSofttile, MasksEqualTheReferenceOnAdversarialEdges) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<float> unit(-1.5f, 1.5f);
  for (const std::string& name : ref::variant_names()) {
    SCOPED_TRACE(name);
    const ref::Variant variant = ref::parse_variant(name);
    const port::DiskRaster raster(variant);
    for_each_target([&] {
      for (int trial = 0; trial < 300; ++trial) {
        ref::DiskBitmask expected(variant);
        port::DiskRows actual = raster.empty_disk();
        std::vector<glm::vec3> edges;
        const int triangles = 1 + trial % 5;
        for (int i = 0; i < 3 * triangles; ++i) {
          glm::vec3 e{unit(random), unit(random), unit(random)};
          switch (random() % 8) {
            case 0:
              e.x = 0.0f;
              break;  // horizontal edge
            case 1:
              e.x = 1e-30f * unit(random);
              break;  // crossings far outside
            case 2:
              e.y = 0.0f;
              e.z = -e.x * float(random() % 5) * 0.25f;
              break;  // at centres
            case 3:
              e.z = std::numeric_limits<float>::quiet_NaN();
              break;
            default:
              break;
          }
          edges.push_back(e);
        }
        for (int t = 0; t < triangles; ++t)
          expected.clear_triangle({edges[3 * t], edges[3 * t + 1], edges[3 * t + 2]});
        raster.clear_triangles(edges.data(), std::size_t(triangles), actual);
        ASSERT_EQ(first_row_difference(expected, actual), "") << "trial " << trial;
        EXPECT_EQ(actual.lit_cells(), expected.lit_cells());
      }
    });
  }
}

// Unrotated fragments skip the rotation's products (fragment_occlusion.cpp), which changes the
// sign of some zeros in the setup: fragments and vertices here share coordinates and signed zeros,
// so that those zeros arise, and every fragment's mask and count must still be the reference's.
TEST(SimdSofttile, UnrotatedFragmentsGiveTheReferenceMasksThroughSignedZeros) {
  const float values[] = {0.0f, -0.0f, 0.25f, -0.25f, 1e-38f, -1e-38f, 0.5f, -1.0f};
  std::mt19937_64 random(5);
  const auto pick = [&] { return values[random() % std::size(values)]; };
  std::vector<ref::FragmentSetup> setups(64);
  for (ref::FragmentSetup& f : setups) {
    f.position = {pick(), pick(), random() % 2 == 0 ? 0.0f : -0.0f};
    f.inverse_scale = 28.636253f;
    f.reach_per_height = disk_reach_per_height(f.inverse_scale);
  }
  port::FragmentArrays fragments;
  fragments.assign(setups, std::vector<std::uint32_t>(setups.size(), 7u));
  ASSERT_FALSE(fragments.rotated);
  for (const char* name : {"grid16", "rows15"}) {
    SCOPED_TRACE(name);
    const ref::Variant variant = ref::parse_variant(name);
    const port::DiskRaster raster(variant);
    std::size_t accepted_total = 0, rejected_total = 0;
    for_each_target([&] {
      for (int trial = 0; trial < 400; ++trial) {
        std::array<glm::vec3, 3> triangle;
        for (glm::vec3& v : triangle) v = {pick(), pick(), random() % 4 == 0 ? -0.0f : 0.5f};
        std::vector<port::DiskRows> masks(setups.size(), raster.empty_disk());
        std::vector<std::uint64_t> rasterized(setups.size(), 0);
        ASSERT_EQ(port::occlude_fragments(fragments, triangle, 1u, raster, masks.data(),
                                          rasterized.data()),
                  setups.size());
        for (std::size_t j = 0; j < setups.size(); ++j) {
          ref::DiskBitmask expected(variant);
          std::array<glm::vec3, 3> edges;
          const bool accepted = ref::triangle_edges(setups[j], triangle, edges);
          if (accepted) expected.clear_triangle(edges);
          (accepted ? accepted_total : rejected_total) += 1;
          ASSERT_EQ(rasterized[j], accepted ? 1u : 0u) << "trial " << trial << ", fragment " << j;
          ASSERT_EQ(first_row_difference(expected, masks[j]), "")
              << "trial " << trial << ", fragment " << j;
        }
      }
    });
    EXPECT_GT(accepted_total, 1000u);
    EXPECT_GT(rejected_total, 1000u);
  }
}

// The default soft fixture at 128 x 128 pixels (64 tiles): enough penumbra, little CI time.
Case small_foliage() {
  Case c = make_fixture("foliage.10k");
  c.camera.width = 128;
  c.camera.height = 128;
  return c;
}

// Where two candidate lists first differ, or "".
std::string first_list_difference(const std::vector<std::uint32_t>& want,
                                  const std::vector<std::uint32_t>& got) {
  for (std::size_t i = 0; i < std::min(want.size(), got.size()); ++i)
    if (want[i] != got[i])
      return "entry " + std::to_string(i) + ": reference triangle " + std::to_string(want[i]) +
             ", simd " + std::to_string(got[i]);
  if (want.size() != got.size())
    return "lengths: reference " + std::to_string(want.size()) + ", simd " +
           std::to_string(got.size());
  return "";
}

// Per tile: the caster list (the reference's cone culling against the port's lanes) and the
// reference's masks (its candidate list rasterized pixel by pixel with
// DiskBitmask) against the port's, for the same grid and rotation.
void expect_tiles_match(const Case& c, const ViewSamples& samples, const std::string& name) {
  SCOPED_TRACE(c.name + " " + name);
  const ref::Variant variant = ref::parse_variant(name);
  const ref::Gathered gathered = ref::gather(c, samples);
  const float inverse_scale = ref::disk_inverse_scale(gathered, variant);
  const port::DiskRaster raster(variant);
  const std::size_t tiles =
      std::size_t(ref::tiles_across(samples.width)) * ref::tiles_across(samples.height);
  ref::Tile tile;
  port::TileScratch scratch;
  port::TileRaster result;
  const port::GatheredCones cones = port::gathered_cones(gathered);
  std::vector<std::uint32_t> list;
  std::vector<std::uint64_t> accepted;
  port::FragmentArrays fragments;
  std::vector<float> lane_edges;
  std::size_t compared = 0, capsules = 0;
  for (std::size_t index = 0; index < tiles; ++index) {
    if (!ref::prepare_tile(c, samples, gathered, variant, inverse_scale, index, tile)) continue;
    for_each_target([&] {
      port::cull_candidates(cones, tile.bound, list);
      ASSERT_EQ(first_list_difference(tile.candidates, list), "")
          << "tile " << index << (tile.bound.capsule ? " (capsule)" : " (sphere)");
    });
    capsules += tile.bound.capsule ? 1 : 0;
    // The fragment setup in lanes: the reference's receiver skip, accept/reject and edge
    // functions, bitwise.
    std::vector<std::uint32_t> receivers;
    for (const std::size_t i : tile.pixels) receivers.push_back(samples.samples[i].receiver);
    fragments.assign(tile.fragments, receivers);
    const std::size_t stride = fragments.x.size();
    accepted.resize(fragments.words());
    lane_edges.resize(9 * stride);
    for (std::size_t k = 0; k < std::min<std::size_t>(tile.candidates.size(), 64); ++k) {
      const ref::GatheredTriangle& t = gathered.triangles[tile.candidates[k]];
      const std::size_t tests = port::triangle_edges(fragments, t.light_space, t.triangle,
                                                     accepted.data(), lane_edges.data(), stride);
      std::size_t want_tests = 0;
      for (std::size_t j = 0; j < tile.pixels.size(); ++j) {
        std::array<glm::vec3, 3> want;
        const bool tested = receivers[j] != t.triangle;
        want_tests += tested ? 1 : 0;
        const bool ok = tested && ref::triangle_edges(tile.fragments[j], t.light_space, want);
        ASSERT_EQ((accepted[j / 64] >> (j % 64)) & 1u, ok ? 1u : 0u)
            << "tile " << index << ", candidate " << k << ", pixel " << tile.pixels[j];
        if (!ok) continue;
        for (int i = 0; i < 3; ++i)
          for (int comp = 0; comp < 3; ++comp)
            ASSERT_EQ(std::bit_cast<std::uint32_t>(lane_edges[(3 * i + comp) * stride + j]),
                      std::bit_cast<std::uint32_t>(want[i][comp]))
                << "tile " << index << ", candidate " << k << ", pixel " << tile.pixels[j]
                << ", edge " << i << ", component " << comp;
      }
      ASSERT_EQ(tests, want_tests) << "tile " << index << ", candidate " << k;
      // Nothing past the tile's pixels.
      for (std::size_t j = tile.pixels.size(); j < 64 * accepted.size(); ++j)
        ASSERT_EQ((accepted[j / 64] >> (j % 64)) & 1u, 0u) << "tile " << index << ", lane " << j;
    }
    port::rasterize_tile(samples, gathered, raster, tile, scratch, result);
    ASSERT_EQ(result.masks.size(), tile.pixels.size());
    std::uint64_t tests = 0, rasterized = 0;
    std::array<glm::vec3, 3> edges;
    for (std::size_t j = 0; j < tile.pixels.size(); ++j) {
      ref::DiskBitmask expected(variant);
      const std::uint32_t receiver = samples.samples[tile.pixels[j]].receiver;
      for (const std::uint32_t k : tile.candidates) {
        const ref::GatheredTriangle& t = gathered.triangles[k];
        if (t.triangle == receiver) continue;
        ++tests;
        if (!ref::triangle_edges(tile.fragments[j], t.light_space, edges)) continue;
        expected.clear_triangle(edges);
        ++rasterized;
      }
      ASSERT_EQ(first_row_difference(expected, result.masks[j]), "")
          << "tile " << index << ", pixel " << tile.pixels[j] << " (" << tile.candidates.size()
          << " candidates)";
      ++compared;
    }
    EXPECT_EQ(result.tests, tests) << "tile " << index;
    EXPECT_EQ(result.rasterized, rasterized) << "tile " << index;
  }
  EXPECT_GT(compared, 500u);
  EXPECT_GT(capsules, 0u);
}

// The cone culling's certificates and tree skips against the reference's may_shadow, cone by
// cone, where they are hardest: random capsule and sphere bounds, and triangle cones placed on
// either side of each bound's boundary at distances from 2^-10 down to 2^-48 of its size (found
// by bisecting the reference's own answer along a random line), plus cones with non-finite tips.
TEST(SimdSofttile, ConeCullingEqualsTheReferenceNearTheBoundary) {
  std::mt19937_64 random(20261203);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto random_vector = [&](double scale) {
    return glm::dvec3(unit(random), unit(random), unit(random)) * scale;
  };
  std::size_t kept = 0, dropped = 0;
  // Trials 24 to 35: capsules of nearly zero radius, and cone tips on lines that leave the
  // capsule's segment, so that the boundary cases touch the bound near their apex: the gap's
  // minimum over the segment is then a sharp bottom (|x(s) - tip| - r(s)), as narrow as the radii.
  // Trials 36 on: both kinds again at scales 2^-100 and 2^200 (squared lengths overflow there).
  for (int trial = 0; trial < 60; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const bool apex_lines = (trial >= 24 && trial < 36) || trial >= 48;
    const int shift = trial < 36 ? 0 : trial < 48 ? -100 : 200;
    ref::Gathered gathered;
    gathered.sun.direction = glm::normalize(glm::dvec3(unit(random), unit(random), 2.0));
    gathered.sun.angular_radius = (trial % 3 == 0 ? 0.2 : 2.0) * 3.14159265358979 / 180.0;
    const double scale = std::ldexp(1.0, int(trial % 5) * 4 - 4 + shift);
    ref::TileBound bound;
    bound.capsule = apex_lines || trial % 4 != 0;
    bound.a = random_vector(scale);
    bound.b = bound.capsule ? bound.a + random_vector(4.0 * scale) : bound.a;
    const double radius_scale = apex_lines ? 1e-7 : 0.01;
    bound.radius_a = radius_scale * scale * (1.0 + unit(random));
    bound.radius_b =
        bound.capsule ? 5.0 * radius_scale * scale * (1.0 + unit(random)) : bound.radius_a;
    // Caster spheres along random lines through the bound's neighbourhood, each line bisected to
    // the reference's boundary between shadowing and not.
    std::vector<ref::ShadowCone> cones;
    const auto cone_at = [&](const glm::dvec3& centre, double radius) {
      return ref::shadow_cone(gathered.sun, centre, radius,
                              glm::dot(centre, gathered.sun.direction) + radius);
    };
    for (int line = 0; line < 60; ++line) {
      // From above a point of the bound (shadowing), to anywhere around it (mostly not); or from a
      // point of the segment, the caster a point, to near it.
      const double radius = apex_lines ? 1e-9 * scale : 0.002 * scale * (1.0 + unit(random));
      const glm::dvec3 on_bound = bound.a + 0.5 * (1.0 + unit(random)) * (bound.b - bound.a);
      const glm::dvec3 from =
          apex_lines ? on_bound
                     : on_bound + gathered.sun.direction * (scale * (1.1 + unit(random)));
      const glm::dvec3 to = from + random_vector((apex_lines ? 0.5 : 6.0) * scale);
      const auto shadows = [&](double t) {
        return ref::may_shadow(gathered.sun, cone_at(from + t * (to - from), radius), bound);
      };
      if (shadows(0.0) == shadows(1.0)) {
        cones.push_back(cone_at(to, radius));
        continue;
      }
      double lo = 0.0, hi = 1.0;
      for (int i = 0; i < 60; ++i)
        ((shadows(0.5 * (lo + hi)) == shadows(0.0)) ? lo : hi) = 0.5 * (lo + hi);
      // One side of the boundary per line, so that whole tree nodes hold near-misses only (or
      // near-hits only); on every other line so close together that their node's cone is barely
      // wider than theirs.
      const bool inside = line % 2 == 0;
      const int coarsest = line % 4 < 2 ? -10 : -34;
      for (int k = 0; k < 16; ++k) {
        const double offset =
            k == 15 ? 0.0 : std::ldexp(1.0, coarsest - (coarsest == -10 ? 2 : 1) * k);
        cones.push_back(cone_at(from + (inside ? lo - offset : hi + offset) * (to - from), radius));
      }
    }
    for (int i = 0; i < 3; ++i) {
      ref::ShadowCone broken = cone_at(bound.a, 0.001 * scale);
      broken.tip[i] = i == 0 ? std::numeric_limits<double>::quiet_NaN()
                             : std::numeric_limits<double>::infinity();
      cones.push_back(broken);
    }
    // Clusters of up to 64 triangles under a cone that holds them all: the list is then decided
    // by the triangles' cones.
    for (std::size_t first = 0; first < cones.size(); first += 64) {
      ref::GatheredCluster cluster;
      cluster.first = std::uint32_t(first);
      cluster.count = std::uint32_t(std::min<std::size_t>(64, cones.size() - first));
      cluster.cone = cone_at(glm::dvec3(0.0), 100.0 * scale);
      cluster.cone.start_height = -std::numeric_limits<double>::infinity();
      gathered.clusters.push_back(cluster);
    }
    for (const ref::ShadowCone& cone : cones) {
      ref::GatheredTriangle t;
      t.triangle = std::uint32_t(gathered.triangles.size());
      t.cone = cone;
      gathered.triangles.push_back(t);
    }
    ref::Tile tile;
    tile.bound = bound;
    ref::cull_candidates(gathered, tile);
    kept += tile.candidates.size();
    dropped += cones.size() - tile.candidates.size();
    const port::GatheredCones ported = port::gathered_cones(gathered);
    for_each_target([&] {
      std::vector<std::uint32_t> list;
      port::cull_candidates(ported, bound, list);
      ASSERT_EQ(first_list_difference(tile.candidates, list), "");
    });
  }
  // Both answers occur in numbers.
  EXPECT_GT(kept, 2000u);
  EXPECT_GT(dropped, 2000u);
}

TEST(SimdSofttile, PerPixelBitmasksEqualTheReferenceOnEveryTile) {
  const Case c = small_foliage();
  const ViewSamples samples = generate_view_samples(c);
  for (const char* name : {"grid16", "grid16+rot", "rows15", "rows31+rot", "post"})
    expect_tiles_match(c, samples, name);
}

// The cone tree's nodes: every triangle tip below a node lies inside the node's cone and within
// its spread of the node's tip (what lets a tile skip the node), and the node's tip stays near
// those tips: its spread is at most (levels + 2) (1 / sin(a) + 1) times the diameter of the tips'
// box. A tip raised over tips that were already raised would grow by 1 / sin(a) (29 at 2 degrees)
// per level, and such nodes never let a tile skip anything.
TEST(SimdSofttile, ConeTreeNodesHoldTheTipsBelowThemAndStayNearThem) {
  const Case c = small_foliage();
  const ViewSamples samples = generate_view_samples(c);
  const ref::Gathered gathered = ref::gather(c, samples);
  const port::GatheredCones cones = port::gathered_cones(gathered);
  const port::ConeTree& tree = cones.tree;
  const std::size_t n = tree.index.size();
  ASSERT_GT(n, 5000u);
  ASSERT_GE(tree.levels.size(), 4u);
  const glm::dvec3 axis = -glm::dvec3(cones.direction[0], cones.direction[1], cones.direction[2]);
  std::size_t span = port::tree_arity;  // triangles below a node of the level
  for (std::size_t level = 0; level < tree.levels.size(); ++level, span *= port::tree_arity) {
    const port::ConeGroups& nodes = tree.levels[level];
    for (std::size_t node = 0; node < nodes.spread.size(); ++node) {
      if (!std::isfinite(nodes.spread[node])) continue;  // never skipped
      const glm::dvec3 tip(nodes.tip[0][node], nodes.tip[1][node], nodes.tip[2][node]);
      glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
      for (std::size_t i = node * span; i < std::min(n, (node + 1) * span); ++i) {
        const glm::dvec3 t(tree.triangles.tip[0][i], tree.triangles.tip[1][i],
                           tree.triangles.tip[2][i]);
        lo = glm::min(lo, t);
        hi = glm::max(hi, t);
        const glm::dvec3 v = t - tip;
        ASSERT_GE(glm::dot(v, axis), glm::length(v) * cones.cos_radius)
            << "level " << level << " node " << node << ": the tip of triangle " << i
            << " lies outside the node's cone";
        ASSERT_LE(glm::length(v), nodes.spread[node])
            << "level " << level << " node " << node << ": triangle " << i;
      }
      const double diameter = glm::length(hi - lo);
      EXPECT_LE(nodes.spread[node], double(level + 2) * (1.0 / cones.sin_radius + 1.0) * diameter +
                                        1e-12 * glm::length(tip))
          << "level " << level << " node " << node << ": the node's tip lies far above its tips";
    }
  }
}

TEST(SimdSofttile, AnswersAndCountersEqualTheReference) {
  const auto reference = make_softtile();
  const auto ported = make_simd_softtile();
  EXPECT_EQ(ported->info().id, "softtile");
  EXPECT_EQ(ported->info().backend, "simd");
  EXPECT_EQ(ported->info().variants,
            (std::vector<std::string>{"grid16", "grid16+rot", "rows15", "rows31", "post"}));
  for (const char* fixture :
       {"foliage.10k", "stiff.sun_radius_45_degrees", "stiff.sun_radius_60_degrees_cone_wall",
        "stiff.sun_radius_60_degrees_cone_tree_wall"}) {
    const Case c = std::string(fixture) == "foliage.10k" ? small_foliage() : make_fixture(fixture);
    const ViewSamples samples = generate_view_samples(c);
    const PreparedScene scene = prepare_scene(c, samples);
    // The registered variants, and rows3 (fewer rows than most targets' lanes).
    std::vector<std::string> variants = ported->info().variants;
    variants.push_back("rows3");
    for (const std::string& variant : variants) {
      SCOPED_TRACE(std::string(fixture) + " " + variant);
      const AlgorithmOutput want = reference->run(scene, variant);
      const AlgorithmOutput got = ported->run(scene, variant);
      EXPECT_EQ(port_test::output_difference(want, got, false), "");
      EXPECT_EQ(ported->soft_error_budget(variant).per_sample,
                reference->soft_error_budget(variant).per_sample);
    }
  }
}

// Where two gathers first differ (cluster, triangle, counter), or "".
std::string first_gather_difference(const ref::Gathered& want, const ref::Gathered& got) {
  const auto same_cone = [](const ref::ShadowCone& a, const ref::ShadowCone& b) {
    return a.tip == b.tip && a.start_height == b.start_height;
  };
  for (std::size_t k = 0; k < std::min(want.clusters.size(), got.clusters.size()); ++k) {
    const ref::GatheredCluster &a = want.clusters[k], &b = got.clusters[k];
    if (a.first != b.first || a.count != b.count || !same_cone(a.cone, b.cone))
      return "cluster " + std::to_string(k);
  }
  if (want.clusters.size() != got.clusters.size()) return "cluster count";
  for (std::size_t k = 0; k < std::min(want.triangles.size(), got.triangles.size()); ++k) {
    const ref::GatheredTriangle &a = want.triangles[k], &b = got.triangles[k];
    if (a.triangle != b.triangle || a.light_space != b.light_space || !same_cone(a.cone, b.cone))
      return "triangle " + std::to_string(k) + " (reference triangle " +
             std::to_string(a.triangle) + ", simd " + std::to_string(b.triangle) + ")";
  }
  if (want.triangles.size() != got.triangles.size()) return "triangle count";
  if (want.clusters_in != got.clusters_in || want.clusters_culled != got.clusters_culled ||
      want.triangles_culled != got.triangles_culled ||
      want.light_facing_dropped != got.light_facing_dropped)
    return "counters";
  return "";
}

// The clusters gathered in parallel blocks and joined: the reference's gather, for any thread
// count, on a frame of many clusters and on closed meshes under a wide sun (light-facing drops).
TEST(SimdSofttile, GatherEqualsTheReferenceClusterForClusterOnAnyThreadCount) {
  for (const Case& c : {small_foliage(), make_fixture("stiff.sun_radius_45_degrees")}) {
    SCOPED_TRACE(c.name);
    const ViewSamples samples = generate_view_samples(c);
    const ref::Gathered want = ref::gather(c, samples);
    ASSERT_GT(want.clusters.size(), 1u);
    for (const int threads : {1, 2}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                      std::size_t(threads));
      EXPECT_EQ(first_gather_difference(want, port::gather(c, samples)), "") << threads;
    }
  }
  // Several parallel blocks (2^14 triangles each, softtile_gather.cpp).
  const Case c = make_fixture("foliage.100k");
  ASSERT_GT(c.triangles.size(), std::size_t(4) << 14);
  const ViewSamples samples = generate_view_samples(c);
  const ref::Gathered want = ref::gather(c, samples);
  EXPECT_EQ(first_gather_difference(want, port::gather(c, samples)), "");
}

TEST(SimdSofttile, ResultsDoNotDependOnTheThreadCountOrTheHighwayTarget) {
  const Case c = small_foliage();
  const ViewSamples samples = generate_view_samples(c);
  const PreparedScene scene = prepare_scene(c, samples);
  const auto ported = make_simd_softtile();
  for (const char* variant : {"grid16+rot", "rows31"}) {
    SCOPED_TRACE(variant);
    AlgorithmOutput one, two;
    {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = ported->run(scene, variant);
    }
    {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = ported->run(scene, variant);
    }
    EXPECT_EQ(port_test::output_difference(one, two, false), "");
    for_each_target([&] {
      EXPECT_EQ(port_test::output_difference(one, ported->run(scene, variant), false), "");
    });
  }
}

}  // namespace
}  // namespace shadowcts
