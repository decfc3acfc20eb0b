// The softtile kernel of the `cuda` backend run by the emulator (`cuda-emu`), diffed against the
// reference: per tile the candidate list (the reference's cone culling), per pixel the disk
// bitmask, the visible fraction and the work counts, for the same grid and rotation, reporting the
// first differing tile / pixel / row; the same lists and masks for any shared batch size (the
// overflow path), schedule (race checking on) and thread count; the Algorithm's answers and
// counters equal the reference's.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "gpu/emulator/emulator.h"
#include "gpu/emulator/kernel.h"
#include "gpu/softtile/disk_bitmask.cuh"
#include "gpu/softtile/fragment_occlusion.cuh"
#include "gpu/softtile/softtile_algorithm.h"
#include "gpu/softtile/softtile_kernel.h"
#include "reference/softtile/disk_bitmask.h"
#include "reference/softtile/fragment_occlusion.h"
#include "reference/softtile/softtile_algorithm.h"
#include "reference/softtile/softtile_gather.h"
#include "reference/softtile/softtile_tile.h"
#include "reference/softtile/softtile_variant.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/view_samples.h"
#include "tests/ports/output_difference.h"

// The kernel's device functions one call per thread, for the unit tests below.
namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::softtile_test {

__global__ void edges_kernel(const softtile::FragmentSetup* fragments,
                             const SofttileTriangle* triangles, float inverse_scale,
                             float reach_per_height, std::uint32_t count, std::uint32_t* accepted,
                             float* edges) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= count) return;
  const softtile::FragmentSetup fragment = fragments[i];
  const SofttileTriangle triangle = triangles[i];
  accepted[i] =
      softtile::triangle_edges(fragment, inverse_scale, reach_per_height, triangle, edges + 9 * i)
          ? 1
          : 0;
}

// Thread i clears triangles[i * per_thread ..] (9 edge components each) from the empty disk.
__global__ void clear_kernel(const float* edges, std::uint32_t per_thread, SofttileRaster raster,
                             std::uint32_t count, std::uint32_t* masks) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= count) return;
  std::uint32_t rows[softtile_kernel_max_rows] = {};
  for (int r = 0; r < raster.rows; ++r) rows[r] = raster.empty[r];
  for (std::uint32_t t = 0; t < per_thread; ++t)
    softtile::clear_triangle(raster, edges + 9 * (i * per_thread + t), rows);
  for (int r = 0; r < softtile_kernel_max_rows; ++r)
    masks[i * softtile_kernel_max_rows + r] = rows[r];
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::softtile_test

namespace shadowcts {
namespace {

namespace ref = shadowcts::softtile;
namespace kernels = shadowcts::emulated::softtile_test;

// Host vectors as emulated device memory.
template <typename T>
struct Device {
  T* data = nullptr;
  std::size_t size;
  explicit Device(const std::vector<T>& host) : size(host.size()) {
    EXPECT_EQ(cudaMalloc(&data, size * sizeof(T)), cudaSuccess);
    EXPECT_EQ(cudaMemcpy(data, host.data(), size * sizeof(T), cudaMemcpyHostToDevice), cudaSuccess);
  }
  ~Device() { cudaFree(data); }
  std::vector<T> get() const {
    std::vector<T> host(size);
    EXPECT_EQ(cudaMemcpy(host.data(), data, size * sizeof(T), cudaMemcpyDeviceToHost), cudaSuccess);
    return host;
  }
};

// Random light-space triangles against random fragments, rotated and not, some behind the
// fragment, some degenerate: the reference's accept / reject and edge functions, bitwise.
TEST(SofttileEmu, EdgeFunctionsEqualTheReferenceBitwise) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const std::uint32_t count = 4096;
  std::vector<emulated::softtile::FragmentSetup> fragments(count);
  std::vector<SofttileTriangle> triangles(count);
  std::vector<ref::FragmentSetup> setups(count);
  std::vector<std::array<glm::vec3, 3>> light_space(count);
  const float inverse_scale = 1.0f / std::tan(0.035f);
  for (std::uint32_t i = 0; i < count; ++i) {
    ref::FragmentSetup& f = setups[i];
    f.position = {unit(random), unit(random), unit(random)};
    f.inverse_scale = inverse_scale;
    f.reach_per_height = disk_reach_per_height(inverse_scale);
    if (i % 2 == 1) {
      const float angle = 3.2f * unit(random);
      f.cos_rotation = std::cos(angle);
      f.sin_rotation = std::sin(angle);
    }
    // Near the fragment's axis towards the light, mostly above it, the disk's size apart.
    for (int v = 0; v < 3; ++v) {
      const float height = i % 7 == 0 ? unit(random) : 0.5f + unit(random) * 0.45f;
      light_space[i][v] =
          f.position + glm::vec3(0.05f * unit(random), 0.05f * unit(random), height);
    }
    if (i % 11 == 0) light_space[i][2] = light_space[i][0];  // degenerate
    for (int k = 0; k < 3; ++k) fragments[i].position[k] = f.position[k];
    fragments[i].cos_rotation = f.cos_rotation;
    fragments[i].sin_rotation = f.sin_rotation;
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k) triangles[i].vertices[3 * v + k] = light_space[i][v][k];
  }
  const Device<emulated::softtile::FragmentSetup> d_fragments(fragments);
  const Device<SofttileTriangle> d_triangles(triangles);
  Device<std::uint32_t> accepted{std::vector<std::uint32_t>(count)};
  Device<float> edges{std::vector<float>(9 * count)};
  SHADOWCTS_LAUNCH(kernels::edges_kernel, (count + 255) / 256, 256, 0)
  (d_fragments.data, d_triangles.data, inverse_scale, disk_reach_per_height(inverse_scale), count,
   accepted.data, edges.data);
  const std::vector<std::uint32_t> got_accepted = accepted.get();
  const std::vector<float> got_edges = edges.get();
  std::size_t accepted_count = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    std::array<glm::vec3, 3> want;
    const bool ok = ref::triangle_edges(setups[i], light_space[i], want);
    ASSERT_EQ(got_accepted[i], ok ? 1u : 0u) << "triangle " << i;
    if (!ok) continue;
    ++accepted_count;
    for (int e = 0; e < 3; ++e)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(std::bit_cast<std::uint32_t>(got_edges[9 * i + 3 * e + k]),
                  std::bit_cast<std::uint32_t>(want[e][k]))
            << "triangle " << i << ", edge " << e << ", component " << k;
  }
  EXPECT_GT(accepted_count, count / 4);
  EXPECT_LT(accepted_count, count);
}

// Horizontal edges, crossings far outside, crossings exactly at cell centres, NaN: the
// reference's rows for every variant's grid.
TEST(SofttileEmu, MasksEqualTheReferenceOnAdversarialEdges) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<float> unit(-1.5f, 1.5f);
  const std::uint32_t trials = 512, per_thread = 3;
  std::vector<float> edges;
  for (std::uint32_t i = 0; i < 3 * trials * per_thread; ++i) {
    glm::vec3 e{unit(random), unit(random), unit(random)};
    switch (random() % 8) {
      case 0:
        e.x = 0.0f;
        break;
      case 1:
        e.x = 1e-30f * unit(random);
        break;
      case 2:
        e.y = 0.0f;
        e.z = -e.x * float(random() % 5) * 0.25f;
        break;
      case 3:
        e.z = std::numeric_limits<float>::quiet_NaN();
        break;
      default:
        break;
    }
    edges.insert(edges.end(), {e.x, e.y, e.z});
  }
  const Device<float> d_edges(edges);
  for (const char* name : {"grid16", "rows15", "rows31", "rows3"}) {
    SCOPED_TRACE(name);
    const ref::Variant variant = ref::parse_variant(name);
    // The variant's raster as the kernel input carries it.
    Case c = make_fixture("foliage.10k");
    c.camera.width = c.camera.height = 16;
    const ViewSamples samples = generate_view_samples(c);
    const SofttileKernelInput input =
        softtile_kernel_input(c, samples, variant, ref::gather(c, samples));
    Device<std::uint32_t> masks{std::vector<std::uint32_t>(trials * softtile_kernel_max_rows)};
    SHADOWCTS_LAUNCH(kernels::clear_kernel, trials / 256, 256, 0)
    (d_edges.data, per_thread, input.raster, trials, masks.data);
    const std::vector<std::uint32_t> got = masks.get();
    for (std::uint32_t i = 0; i < trials; ++i) {
      ref::DiskBitmask expected(variant);
      for (std::uint32_t t = 0; t < per_thread; ++t) {
        const float* e = edges.data() + 9 * (i * per_thread + t);
        expected.clear_triangle({glm::vec3(e[0], e[1], e[2]), glm::vec3(e[3], e[4], e[5]),
                                 glm::vec3(e[6], e[7], e[8])});
      }
      for (int r = 0; r < softtile_kernel_max_rows; ++r)
        ASSERT_EQ(got[i * softtile_kernel_max_rows + r], r < expected.rows() ? expected.row(r) : 0u)
            << "trial " << i << ", row " << r;
    }
  }
}

// The default soft fixture at 128 x 128 pixels (64 tiles): enough penumbra, little CI time.
Case small_foliage(std::uint32_t size = 128) {
  Case c = make_fixture("foliage.10k");
  c.camera.width = size;
  c.camera.height = size;
  return c;
}

struct Scene {
  Case c;
  ViewSamples samples;
  ref::Gathered gathered;
  explicit Scene(Case source)
      : c(std::move(source)),
        samples(generate_view_samples(c)),
        gathered(ref::gather(c, samples)) {}
};

std::string hex(std::uint32_t v) {
  std::ostringstream out;
  out << "0x" << std::hex << v;
  return out.str();
}

// The first difference between the kernel's per-tile lists and per-pixel results and the
// reference's (prepare_tile, then each candidate through triangle_edges and clear_triangle), or "".
std::string first_difference(const Scene& s, const ref::Variant& variant,
                             const SofttileKernelResult& got, std::size_t& compared_pixels,
                             std::size_t& capsules) {
  const float inverse_scale = ref::disk_inverse_scale(s.gathered, variant);
  const std::size_t tiles =
      std::size_t(ref::tiles_across(s.samples.width)) * ref::tiles_across(s.samples.height);
  if (got.candidate_offsets.size() != tiles + 1) return "no recorded candidate lists";
  ref::Tile tile;
  std::array<glm::vec3, 3> edges;
  for (std::size_t index = 0; index < tiles; ++index) {
    const std::string at = "tile " + std::to_string(index);
    if (!ref::prepare_tile(s.c, s.samples, s.gathered, variant, inverse_scale, index, tile)) {
      if (got.candidates[index] != 0 || got.tile_kinds[index] != softtile_tile_empty)
        return at + ": a bound or candidates in a tile without pixels";
      continue;
    }
    capsules += tile.bound.capsule ? 1 : 0;
    if (got.tile_kinds[index] !=
        (tile.bound.capsule ? softtile_tile_capsule : softtile_tile_sphere))
      return at + ": reference bound " + (tile.bound.capsule ? "capsule" : "sphere") +
             ", kernel kind " + std::to_string(got.tile_kinds[index]);
    const std::uint32_t* list = got.candidate_list.data() + got.candidate_offsets[index];
    const std::size_t length = got.candidate_offsets[index + 1] - got.candidate_offsets[index];
    if (got.candidates[index] != length) return at + ": counted and recorded lists differ";
    for (std::size_t k = 0; k < std::min(length, tile.candidates.size()); ++k)
      if (list[k] != tile.candidates[k])
        return at + (tile.bound.capsule ? " (capsule)" : " (sphere)") + ", candidate " +
               std::to_string(k) + ": reference triangle " + std::to_string(tile.candidates[k]) +
               ", kernel " + std::to_string(list[k]);
    if (length != tile.candidates.size())
      return at + ": list lengths: reference " + std::to_string(tile.candidates.size()) +
             ", kernel " + std::to_string(length);
    for (std::size_t j = 0; j < tile.pixels.size(); ++j) {
      const std::size_t pixel = tile.pixels[j];
      ref::DiskBitmask expected(variant);
      const std::uint32_t receiver = s.samples.samples[pixel].receiver;
      std::uint32_t tests = 0, rasterized = 0;
      for (const std::uint32_t k : tile.candidates) {
        const ref::GatheredTriangle& t = s.gathered.triangles[k];
        if (t.triangle == receiver) continue;
        ++tests;
        if (!ref::triangle_edges(tile.fragments[j], t.light_space, edges)) continue;
        expected.clear_triangle(edges);
        ++rasterized;
      }
      const std::string where = at + ", pixel " + std::to_string(pixel);
      for (int r = 0; r < softtile_kernel_max_rows; ++r) {
        const std::uint32_t want = r < expected.rows() ? expected.row(r) : 0u;
        const std::uint32_t have = got.masks[pixel * softtile_kernel_max_rows + r];
        if (want != have)
          return where + ", row " + std::to_string(r) + ": reference " + hex(want) + ", kernel " +
                 hex(have);
      }
      const float fraction = float(expected.lit_cells()) / float(expected.disk_cells());
      if (got.visible_fraction[pixel] != fraction)
        return where + ": visible fraction " + std::to_string(fraction) + " vs " +
               std::to_string(got.visible_fraction[pixel]);
      if (got.tests[pixel] != tests || got.rasterized[pixel] != rasterized)
        return where + ": tests / rasterized " + std::to_string(tests) + " / " +
               std::to_string(rasterized) + " vs " + std::to_string(got.tests[pixel]) + " / " +
               std::to_string(got.rasterized[pixel]);
      ++compared_pixels;
    }
  }
  return "";
}

SofttileKernelResult run_recorded(const Scene& s, const ref::Variant& variant,
                                  std::uint32_t batch_capacity = 0) {
  SofttileKernelInput input = softtile_kernel_input(s.c, s.samples, variant, s.gathered);
  if (batch_capacity != 0) input.batch_capacity = batch_capacity;
  input.record_candidates = true;
  input.record_masks = true;
  return run_softtile_kernel_emulated(input);
}

TEST(SofttileEmu, ListsAndBitmasksEqualTheReferenceOnEveryTile) {
  const Scene s(small_foliage());
  for (const char* name : {"grid16", "grid16+rot", "rows15", "rows31", "post"}) {
    SCOPED_TRACE(name);
    const ref::Variant variant = ref::parse_variant(name);
    const SofttileKernelResult got = run_recorded(s, variant);
    std::size_t compared = 0, capsules = 0;
    EXPECT_EQ(first_difference(s, variant, got, compared, capsules), "");
    EXPECT_GT(compared, 500u);
    EXPECT_GT(capsules, 0u);
  }
}

// The shared list holds batch_capacity triangles; longer lists are rasterized in batches. Tiny
// buffers split every tile's list, and a chunk of clusters over several fills of the buffer.
TEST(SofttileEmu, SmallSharedBuffersGiveTheSameListsAndBitmasks) {
  const Scene s(small_foliage(64));
  const ref::Variant variant = ref::parse_variant("grid16+rot");
  const SofttileKernelResult full = run_recorded(s, variant);
  std::size_t compared = 0, capsules = 0;
  EXPECT_EQ(first_difference(s, variant, full, compared, capsules), "");
  const std::uint32_t longest = *std::max_element(full.candidates.begin(), full.candidates.end());
  ASSERT_GT(longest, 3u * 61u);
  for (std::uint32_t capacity : {1u, 61u}) {
    SCOPED_TRACE(capacity);
    const SofttileKernelResult small = run_recorded(s, variant, capacity);
    EXPECT_EQ(small.masks, full.masks);
    EXPECT_EQ(small.visible_fraction, full.visible_fraction);
    EXPECT_EQ(small.tests, full.tests);
    EXPECT_EQ(small.candidate_list, full.candidate_list);
  }
}

// A GPU runs warps in any order: under a seeded random interleaving with shared-memory race
// checking on, the kernel has no race and gives the same lists and masks.
TEST(SofttileEmu, NoRaceAndTheSameResultsUnderRandomSchedules) {
  const Scene s(small_foliage(32));
  const ref::Variant variant = ref::parse_variant("rows15");
  const SofttileKernelResult plain = run_recorded(s, variant, 100);
  ASSERT_GT(plain.candidate_list.size(), 100u);  // several batches in some tile
  for (std::uint64_t seed : {1u, 2u}) {
    emu::Options options;
    options.schedule = emu::Schedule::random;
    options.seed = seed;
    options.check_races = true;
    const emu::ScopedOptions scoped(options);
    const SofttileKernelResult checked = run_recorded(s, variant, 100);
    EXPECT_EQ(checked.masks, plain.masks);
    EXPECT_EQ(checked.candidate_list, plain.candidate_list);
    EXPECT_EQ(checked.tests, plain.tests);
  }
}

// The reference's counters, then emulated_threads.
TEST(SofttileEmu, AnswersAndCountersEqualTheReference) {
  const auto reference = make_softtile();
  const auto ported = make_softtile_cuda_emu();
  EXPECT_EQ(ported->info().id, "softtile");
  EXPECT_EQ(ported->info().backend, "cuda-emu");
  EXPECT_EQ(ported->info().variants,
            (std::vector<std::string>{"grid16", "grid16+rot", "rows15", "rows31", "post"}));
  // The default soft fixture at its full size, and a wide sun.
  for (const char* fixture :
       {"foliage.10k", "stiff.sun_radius_45_degrees", "stiff.sun_radius_60_degrees_cone_wall",
        "stiff.sun_radius_60_degrees_cone_tree_wall"}) {
    const Case c = make_fixture(fixture);
    const ViewSamples samples = generate_view_samples(c);
    const PreparedScene scene = prepare_scene(c, samples);
    const bool full = std::string(fixture) != "foliage.10k";
    for (const std::string& variant :
         full ? ported->info().variants : std::vector<std::string>{"grid16+rot"}) {
      SCOPED_TRACE(std::string(fixture) + " " + variant);
      const AlgorithmOutput want = reference->run(scene, variant);
      EXPECT_EQ(port_test::output_difference(want, ported->run(scene, variant), true), "");
      EXPECT_EQ(ported->soft_error_budget(variant).per_sample,
                reference->soft_error_budget(variant).per_sample);
    }
  }
}

TEST(SofttileEmu, ResultsDoNotDependOnTheThreadCount) {
  const Case c = small_foliage();
  const ViewSamples samples = generate_view_samples(c);
  const PreparedScene scene = prepare_scene(c, samples);
  const auto ported = make_softtile_cuda_emu();
  AlgorithmOutput one, two;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = ported->run(scene, "post");
  }
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = ported->run(scene, "post");
  }
  EXPECT_EQ(port_test::output_difference(one, two, false), "");
}

TEST(SofttileEmu, RejectsVariantsItDoesNotRegister) {
  const Case c = small_foliage(16);
  const ViewSamples samples = generate_view_samples(c);
  const PreparedScene scene = prepare_scene(c, samples);
  EXPECT_THROW(make_softtile_cuda_emu()->run(scene, "rows3"), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcts
