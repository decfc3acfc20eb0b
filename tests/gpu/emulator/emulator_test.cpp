// The CUDA-subset emulator: correct kernels give the right answers under every schedule with
// race checking on, and each kernel with a bug is reported with its kernel, block, thread and
// line.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <fstream>
#include <functional>
#include <numeric>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "tests/gpu/emulator/bug_kernels.cuh"
#include "tests/gpu/emulator/correct_kernels.cuh"

namespace shadowcts {
namespace {

namespace k = emulated::test_kernels;
namespace bug = emulated::bug_kernels;
using emu::ErrorKind;
using emu::Options;
using emu::Schedule;

// Run-until-block and four random seeds, race checking on.
std::vector<Options> schedules() {
  std::vector<Options> all{{Schedule::run_until_block, 0, true}};
  for (std::uint64_t seed : {1, 2, 3, 17}) all.push_back({Schedule::random, seed, true});
  return all;
}

std::string schedule_name(const ::testing::TestParamInfo<Options>& info) {
  return info.param.schedule == Schedule::run_until_block
             ? std::string("RunUntilBlock")
             : "Random" + std::to_string(info.param.seed);
}

class EmulatorKernels : public ::testing::TestWithParam<Options> {
 protected:
  emu::ScopedOptions options_{GetParam()};
};

std::vector<int> random_ints(std::size_t n, int lo, int hi, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> value(lo, hi);
  std::vector<int> v(n);
  for (int& x : v) x = value(random);
  return v;
}

TEST_P(EmulatorKernels, BlockReductionInSharedMemory) {
  const std::vector<int> values = random_ints(1000, -1000, 1000, 1);
  unsigned long long total = 0;
  SHADOWCTS_LAUNCH(k::block_reduce_sum, 4, 256, 0)(values.data(), 1000u, &total);
  EXPECT_EQ(static_cast<long long>(total), std::accumulate(values.begin(), values.end(), 0ll));
}

TEST_P(EmulatorKernels, WarpShuffleReduction) {
  const std::vector<int> values = random_ints(700, -50, 50, 2);
  std::vector<int> sums(3, 0);
  SHADOWCTS_LAUNCH(k::warp_shuffle_reduce, 3, 256, 0)(values.data(), 700u, sums.data());
  for (unsigned b = 0; b < 3; ++b) {
    const auto first = values.begin() + b * 256;
    const auto last = values.begin() + std::min<std::size_t>(700, (b + 1) * 256);
    EXPECT_EQ(sums[b], std::accumulate(first, last, 0)) << "block " << b;
  }
}

TEST_P(EmulatorKernels, InclusiveScan) {
  const unsigned n = 1000, block = 128, blocks = (n + block - 1) / block;
  const std::vector<int> values = random_ints(n, -9, 9, 3);
  std::vector<int> out(n, 0), totals(blocks, 0);
  SHADOWCTS_LAUNCH(k::block_inclusive_scan, blocks, block, 0)
  (values.data(), n, out.data(), totals.data());
  SHADOWCTS_LAUNCH(k::add_block_offsets, blocks, block, 0)(out.data(), n, totals.data());
  std::vector<int> expected(n);
  std::inclusive_scan(values.begin(), values.end(), expected.begin());
  EXPECT_EQ(out, expected);
}

TEST_P(EmulatorKernels, TiledTranspose) {
  const unsigned width = 70, height = 45;
  std::vector<float> in(width * height), out(width * height, -1.0f);
  std::iota(in.begin(), in.end(), 0.0f);
  const dim3 grid((width + k::tile_dim - 1) / k::tile_dim,
                  (height + k::tile_dim - 1) / k::tile_dim);
  SHADOWCTS_LAUNCH(k::transpose, grid, dim3(k::tile_dim, k::tile_rows), 0)
  (in.data(), out.data(), width, height);
  for (unsigned y = 0; y < height; ++y) {
    for (unsigned x = 0; x < width; ++x) {
      ASSERT_EQ(out[x * height + y], in[y * width + x]) << x << "," << y;
    }
  }
}

TEST_P(EmulatorKernels, AtomicsOnGlobalAndSharedMemory) {
  const unsigned n = 900;
  std::vector<unsigned> values(n);
  std::mt19937 random(4);
  for (unsigned& v : values) v = random() % 5000;
  std::vector<unsigned> histogram(k::bins, 0);
  k::AtomicResults r{};
  r.min = INT_MAX;
  r.max = INT_MIN;
  r.and_bits = ~0u;
  SHADOWCTS_LAUNCH(k::histogram_and_atomics, 4, 256, 0)(values.data(), n, histogram.data(), &r);

  std::vector<unsigned> expected_histogram(k::bins, 0);
  unsigned and_bits = ~0u, or_bits = 0, xor_bits = 0;
  for (unsigned v : values) {
    ++expected_histogram[v % k::bins];
    and_bits &= ~(1u << (v % 32));
    or_bits |= 1u << (v % 32);
    xor_bits ^= v;
  }
  EXPECT_EQ(histogram, expected_histogram);
  EXPECT_EQ(r.add, static_cast<int>(n));
  EXPECT_EQ(r.min, static_cast<int>(*std::min_element(values.begin(), values.end())));
  EXPECT_EQ(r.max, static_cast<int>(*std::max_element(values.begin(), values.end())));
  EXPECT_EQ(r.max_shared, *std::max_element(values.begin(), values.end()));
  EXPECT_EQ(r.and_bits, and_bits);
  EXPECT_EQ(r.or_bits, or_bits);
  EXPECT_EQ(r.xor_bits, xor_bits);
  EXPECT_EQ(r.add64, static_cast<unsigned long long>(n) << 33);
  EXPECT_EQ(r.add_float, 0.5f * n);  // exact: halves up to 450
  EXPECT_EQ(r.exch_winners, 1);
  EXPECT_EQ(r.cas_count, static_cast<int>(n));
}

TEST_P(EmulatorKernels, VotesActiveMaskAndBarrierPredicates) {
  const unsigned block = 64;
  std::vector<k::VoteResults> out(2 * block);
  SHADOWCTS_LAUNCH(k::votes, 2, block, 0)(out.data());
  unsigned ballot = 0;
  for (unsigned lane = 0; lane < 32; lane += 3) ballot |= 1u << lane;
  for (unsigned i = 0; i < out.size(); ++i) {
    const k::VoteResults& r = out[i];
    const unsigned lane = i % 32;
    EXPECT_EQ(r.ballot, ballot) << i;
    EXPECT_EQ(r.any, 1) << i;
    EXPECT_EQ(r.all, 1) << i;
    EXPECT_EQ(r.none_all, 0) << i;
    EXPECT_EQ(r.active, lane < 10 ? 0x3ffu : ~0x3ffu) << i;
    EXPECT_EQ(r.count, static_cast<int>(block / 4)) << i;
    EXPECT_EQ(r.and_all, 1) << i;
    EXPECT_EQ(r.and_some, 0) << i;
    EXPECT_EQ(r.or_some, 1) << i;
  }
}

TEST_P(EmulatorKernels, ShuffleWidthAndOutOfRangeRules) {
  std::vector<k::ShuffleResults> out(32);
  SHADOWCTS_LAUNCH(k::shuffle_rules, 1, 32, 0)(out.data());
  for (int lane = 0; lane < 32; ++lane) {
    const k::ShuffleResults& r = out[lane];
    const int segment = lane & ~7, offset = lane - segment;
    EXPECT_EQ(r.idx, segment + 3) << lane;
    EXPECT_EQ(r.idx_wide, segment + 3) << lane;  // srcLane 11 wraps to 3 within width 8
    EXPECT_EQ(r.up, offset >= 2 ? lane - 2 : lane) << lane;
    EXPECT_EQ(r.down, offset + 3 < 8 ? lane + 3 : lane) << lane;
    EXPECT_EQ(r.xor_in, lane ^ 1) << lane;
    // xor 8 leaves the segment: earlier segments are readable, later ones give the own value.
    EXPECT_EQ(r.xor_out, (lane & 8) ? lane - 8 : lane) << lane;
  }
}

TEST_P(EmulatorKernels, DynamicSharedMemory) {
  const unsigned block = 96, n = 3 * block;
  std::vector<int> in(n), out(n, 0);
  std::iota(in.begin(), in.end(), 0);
  SHADOWCTS_LAUNCH(k::reverse_dynamic, 3, block, block * sizeof(int))(in.data(), out.data(), n);
  for (unsigned i = 0; i < n; ++i) {
    EXPECT_EQ(out[i], static_cast<int>(i / block * block + (block - 1 - i % block))) << i;
  }
}

TEST_P(EmulatorKernels, WarpSynchronousCodeWithSyncwarp) {
  const std::vector<int> values = random_ints(4 * 64, -100, 100, 5);
  std::vector<int> sums(4, 0);
  SHADOWCTS_LAUNCH(k::warp_synchronous_reduce, 4, 64, 0)(values.data(), sums.data());
  for (unsigned b = 0; b < 4; ++b) {
    EXPECT_EQ(sums[b], std::accumulate(values.begin() + b * 64, values.begin() + (b + 1) * 64, 0));
  }
}

INSTANTIATE_TEST_SUITE_P(Schedules, EmulatorKernels, ::testing::ValuesIn(schedules()),
                         schedule_name);

// ---------------------------------------------------------------------------------------------
// Bugs

unsigned bug_line(const std::string& name) {
  std::ifstream in(bug::source_file);
  const std::string marker = "// BUG:" + name;
  std::string line;
  for (unsigned number = 1; std::getline(in, line); ++number) {
    const auto at = line.find(marker);
    if (at != std::string::npos && at + marker.size() == line.size()) return number;
  }
  ADD_FAILURE() << "no " << marker << " in " << bug::source_file;
  return 0;
}

struct Expected {
  ErrorKind kind;
  std::string kernel;
  std::string bug;             // the BUG: marker of the reported line
  emu::Uint3 thread;           // under run-until-block
  std::set<ErrorKind> random;  // kinds a random schedule may report first (default: kind)
  bool random_line = true;     // whether a random schedule reports the same line
};

class EmulatorBugs : public ::testing::TestWithParam<Options> {
 protected:
  void expect_error(const Expected& e, const std::function<void()>& launch) {
    try {
      launch();
      ADD_FAILURE() << e.kernel << ": no error reported";
    } catch (const emu::EmulatorError& error) {
      SCOPED_TRACE(error.what());
      EXPECT_EQ(error.kernel, e.kernel);
      EXPECT_EQ(error.block.x, 0u);
      EXPECT_EQ(error.file, bug::source_file);
      if (GetParam().schedule == Schedule::run_until_block) {
        EXPECT_EQ(error.kind, e.kind) << emu::to_string(error.kind);
        EXPECT_EQ(error.line, bug_line(e.bug));
        EXPECT_EQ(error.thread.x, e.thread.x);
        EXPECT_EQ(error.thread.y, e.thread.y);
        EXPECT_EQ(error.thread.z, e.thread.z);
      } else {
        std::set<ErrorKind> kinds = e.random;
        kinds.insert(e.kind);
        EXPECT_TRUE(kinds.count(error.kind)) << emu::to_string(error.kind);
        if (e.random_line) {
          EXPECT_EQ(error.line, bug_line(e.bug));
        }
      }
    }
  }
  emu::ScopedOptions options_{GetParam()};
  std::vector<int> out_ = std::vector<int>(1024, 0);
  std::vector<int> in_ = std::vector<int>(1024, 1);
};

TEST_P(EmulatorBugs, ThreadExitsBeforeBarrier) {
  expect_error(
      {ErrorKind::barrier_divergence, "exit_before_barrier", "exit_before_barrier", {5, 0, 0}, {}},
      [&] {
        SHADOWCTS_LAUNCH(bug::exit_before_barrier, 3, 64, 0)
        (out_.data());
      });
}

TEST_P(EmulatorBugs, ThreadsWaitAtDifferentBarriers) {
  expect_error({ErrorKind::barrier_divergence,
                "different_barriers",
                "different_barriers",
                {32, 0, 0},
                {},
                false},
               [&] {
                 SHADOWCTS_LAUNCH(bug::different_barriers, 1, 64, 0)
                 (out_.data());
               });
}

TEST_P(EmulatorBugs, WarpLaneDoesNotArrive) {
  expect_error(
      {ErrorKind::warp_lane_missing, "lane_misses_shuffle", "lane_misses_shuffle", {0, 0, 0}, {}},
      [&] {
        SHADOWCTS_LAUNCH(bug::lane_misses_shuffle, 1, 32, 0)
        (out_.data());
      });
}

TEST_P(EmulatorBugs, WarpLaneHasExited) {
  expect_error({ErrorKind::warp_lane_exited,
                "lane_exited_before_shuffle",
                "lane_exited_before_shuffle",
                {0, 0, 0},
                {}},
               [&] {
                 SHADOWCTS_LAUNCH(bug::lane_exited_before_shuffle, 1, 32, 0)
                 (out_.data());
               });
}

TEST_P(EmulatorBugs, FullMaskInPartialWarp) {
  expect_error(
      {ErrorKind::warp_lane_exited, "partial_warp_shuffle", "partial_warp_shuffle", {32, 0, 0}, {}},
      [&] {
        SHADOWCTS_LAUNCH(bug::partial_warp_shuffle, 1, 48, 0)
        (out_.data());
      });
}

TEST_P(EmulatorBugs, ShuffleFromInactiveLane) {
  expect_error({ErrorKind::shuffle_inactive_lane,
                "shuffle_from_inactive_lane",
                "shuffle_from_inactive_lane",
                {8, 0, 0},
                {}},
               [&] {
                 SHADOWCTS_LAUNCH(bug::shuffle_from_inactive_lane, 1, 32, 0)
                 (out_.data());
               });
}

TEST_P(EmulatorBugs, SharedReadRacesWriteWithoutBarrier) {
  expect_error({ErrorKind::shared_race,
                "missing_barrier",
                "missing_barrier",
                {1, 0, 0},
                {ErrorKind::shared_uninitialized}},
               [&] {
                 SHADOWCTS_LAUNCH(bug::missing_barrier, 1, 128, 0)
                 (in_.data(), out_.data());
               });
}

TEST_P(EmulatorBugs, SharedWriteRacesReadOfPreviousTile) {
  expect_error({ErrorKind::shared_race,
                "tile_overwritten_while_read",
                "tile_overwritten_while_read",
                {1, 0, 0},
                {},
                false},
               [&] {
                 SHADOWCTS_LAUNCH(bug::tile_overwritten_while_read, 1, 64, 0)
                 (in_.data(), out_.data(), 4u);
               });
}

TEST_P(EmulatorBugs, WarpSynchronousCodeWithoutSyncwarp) {
  expect_error({ErrorKind::shared_race,
                "warp_synchronous_without_syncwarp",
                "warp_synchronous_without_syncwarp",
                {1, 0, 0},
                {},
                false},
               [&] {
                 SHADOWCTS_LAUNCH(bug::warp_synchronous_without_syncwarp, 1, 64, 0)
                 (in_.data(), out_.data());
               });
}

TEST_P(EmulatorBugs, SyncwarpOfAnotherHalfDoesNotOrder) {
  expect_error({ErrorKind::shared_race, "half_warp_syncwarp", "half_warp_syncwarp", {16, 0, 0}, {}},
               [&] {
                 SHADOWCTS_LAUNCH(bug::half_warp_syncwarp, 1, 32, 0)
                 (out_.data());
               });
}

TEST_P(EmulatorBugs, Deadlock) {
  expect_error({ErrorKind::deadlock,
                "mismatched_collectives",
                "mismatched_collectives",
                {0, 0, 0},
                {},
                false},
               [&] {
                 SHADOWCTS_LAUNCH(bug::mismatched_collectives, 1, 2, 0)
                 (out_.data());
               });
}

TEST_P(EmulatorBugs, UninitializedSharedRead) {
  expect_error({ErrorKind::shared_uninitialized,
                "uninitialized_shared_read",
                "uninitialized_shared_read",
                {9, 0, 0},
                {}},
               [&] {
                 SHADOWCTS_LAUNCH(bug::uninitialized_shared_read, 1, 32, 0)
                 (out_.data());
               });
}

TEST_P(EmulatorBugs, SharedIndexOutOfBounds) {
  expect_error({ErrorKind::shared_out_of_bounds,
                "shared_out_of_bounds",
                "shared_out_of_bounds",
                {31, 0, 0},
                {}},
               [&] {
                 SHADOWCTS_LAUNCH(bug::shared_out_of_bounds, 1, 32, 0)
                 (out_.data());
               });
}

INSTANTIATE_TEST_SUITE_P(Schedules, EmulatorBugs, ::testing::ValuesIn(schedules()), schedule_name);

// ---------------------------------------------------------------------------------------------

// Run-until-block without race checks hides a missing barrier (each thread's neighbour ran
// first); the random schedule gives wrong answers.
TEST(EmulatorSchedules, RandomScheduleExposesMissingBarrier) {
  std::vector<int> in(128), out(128, 0);
  std::iota(in.begin(), in.end(), 1);
  auto wrong = [&] {
    SHADOWCTS_LAUNCH(bug::missing_barrier, 1, 128, 0)(in.data(), out.data());
    int bad = 0;
    for (int i = 1; i < 128; ++i) bad += out[i] != in[i - 1];
    return bad;
  };
  {
    const emu::ScopedOptions options({Schedule::run_until_block, 0, false});
    EXPECT_EQ(wrong(), 0);
  }
  for (std::uint64_t seed : {1, 2, 3}) {
    const emu::ScopedOptions options({Schedule::random, seed, false});
    EXPECT_GT(wrong(), 0) << "seed " << seed;
  }
}

// The warp-synchronous reduction tail without __syncwarp relies on lanes moving in lockstep,
// which neither schedule provides: its answer is wrong under both, even with race checks off.
TEST(EmulatorSchedules, SchedulesExposeWarpSynchronousCodeWithoutSyncwarp) {
  std::vector<int> in(64), out(1, 0);
  std::iota(in.begin(), in.end(), 1);
  const int sum = std::accumulate(in.begin(), in.end(), 0);
  std::vector<Options> all{{Schedule::run_until_block, 0, false}};
  for (std::uint64_t seed : {1, 2, 3}) all.push_back({Schedule::random, seed, false});
  for (const Options& options : all) {
    const emu::ScopedOptions scoped(options);
    SHADOWCTS_LAUNCH(bug::warp_synchronous_without_syncwarp, 1, 64, 0)(in.data(), out.data());
    EXPECT_NE(out[0], sum) << "seed " << options.seed;
  }
  // With __syncwarp between the steps the same reduction is right under every schedule.
  for (const Options& options : all) {
    const emu::ScopedOptions scoped(options);
    std::vector<int> sums(1, 0);
    SHADOWCTS_LAUNCH(k::warp_synchronous_reduce, 1, 64, 0)(in.data(), sums.data());
    EXPECT_EQ(sums[0], sum) << "seed " << options.seed;
  }
}

TEST(EmulatorSchedules, RandomScheduleIsReproducible) {
  std::vector<int> in(128), first(128, 0), second(128, 0);
  std::iota(in.begin(), in.end(), 1);
  const emu::ScopedOptions options({Schedule::random, 42, false});
  SHADOWCTS_LAUNCH(bug::missing_barrier, 1, 128, 0)(in.data(), first.data());
  SHADOWCTS_LAUNCH(bug::missing_barrier, 1, 128, 0)(in.data(), second.data());
  EXPECT_EQ(first, second);
}

TEST(EmulatorLaunch, RefusesWhatAGpuRefuses) {
  std::vector<int> out(4096, 0);
  auto kind_of = [](const std::function<void()>& launch) -> std::optional<ErrorKind> {
    try {
      launch();
    } catch (const emu::EmulatorError& e) {
      return e.kind;
    }
    return std::nullopt;
  };
  EXPECT_EQ(kind_of([&] {
              SHADOWCTS_LAUNCH(k::votes, 1, 2048, 0)
              (nullptr);
            }),
            ErrorKind::invalid_launch);
  EXPECT_EQ(kind_of([&] {
              SHADOWCTS_LAUNCH(k::votes, 0, 32, 0)
              (nullptr);
            }),
            ErrorKind::invalid_launch);
  EXPECT_EQ(kind_of([&] {
              SHADOWCTS_LAUNCH(k::reverse_dynamic, 1, 32, 64 * 1024)(nullptr, out.data(), 0u);
            }),
            ErrorKind::invalid_launch);
  EXPECT_EQ(kind_of([] { (void)threadIdx.x; }), ErrorKind::outside_kernel);
}

// The lowest failing block is the one reported, whatever order the blocks ran in.
TEST(EmulatorLaunch, ReportsTheLowestFailingBlock) {
  std::vector<int> out(64, 0);
  for (int repeat = 0; repeat < 5; ++repeat) {
    try {
      SHADOWCTS_LAUNCH(bug::exit_before_barrier, 64, 64, 0)(out.data());
      ADD_FAILURE() << "no error";
    } catch (const emu::EmulatorError& e) {
      EXPECT_EQ(e.block.x, 0u);
    }
  }
}

TEST(EmulatorRuntime, DeviceMemoryIsHostMemory) {
  int* device = nullptr;
  ASSERT_EQ(cudaMalloc(&device, 16 * sizeof(int)), cudaSuccess);
  ASSERT_EQ(cudaMemset(device, 0, 16 * sizeof(int)), cudaSuccess);
  std::vector<int> host(16, 7), back(16, -1);
  ASSERT_EQ(cudaMemcpy(device, host.data(), 8 * sizeof(int), cudaMemcpyHostToDevice), cudaSuccess);
  ASSERT_EQ(cudaMemcpy(back.data(), device, 16 * sizeof(int), cudaMemcpyDeviceToHost), cudaSuccess);
  EXPECT_EQ(back[7], 7);
  EXPECT_EQ(back[8], 0);
  EXPECT_EQ(cudaFree(device), cudaSuccess);
  EXPECT_EQ(cudaDeviceSynchronize(), cudaSuccess);
  EXPECT_EQ(cudaGetLastError(), cudaSuccess);
}

}  // namespace
}  // namespace shadowcts
