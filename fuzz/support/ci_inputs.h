#pragma once
// The fuzz targets' reproducible CI mode: a fixed sequence of inputs decided by a seed and the
// seed files alone. libFuzzer's own loop is not reproducible here (the same binary, seed and
// -runs gave ok, ok, FAILED in three runs): its mutations follow coverage feedback, which moves
// with thread interleavings (racy 8-bit counters under oneTBB and Embree's threads) and with
// address-dependent comparisons fed to its value tables. This generator uses no feedback: the
// seed files in path order, then `runs` inputs, each a seeded mutation of a seed file (or random
// bytes), so the same commit, seed and count always execute the same inputs in the same order.
// Coverage-guided exploration stays libFuzzer's job (run_ci.sh's time-budget mode).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace shadowcts::fuzzing {

using Bytes = std::vector<std::uint8_t>;

// A seed file and the name it is reported under.
struct SeedInput {
  std::string path;
  Bytes bytes;
};

// Every regular file under each path (a file or a folder, recursively), sorted by path within
// each argument so the order does not depend on the file system; each truncated to `max_len`
// bytes (as libFuzzer truncates seeds to -max_len).
std::vector<SeedInput> read_seed_inputs(const std::vector<std::filesystem::path>& paths,
                                        std::size_t max_len);

// splitmix64: a small, fast generator whose sequence is fixed by its seed on every platform.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  // Uniform in [0, n) for n > 0 (the small modulo bias does not matter for fuzzing).
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }

 private:
  std::uint64_t state_;
};

class CiInputGenerator {
 public:
  CiInputGenerator(std::vector<SeedInput> seeds, std::uint64_t seed, std::size_t max_len);
  // The next generated input: with seeds, mostly a stack of 1-4 mutations of one seed (bit and
  // byte changes, inserted and erased ranges, copied chunks, interesting integers, number tokens
  // of text formats replaced by extreme ones, splices of two seeds, a short chunk repeated up to
  // thousands of times for deep nesting and long lists); otherwise, and sometimes anyway, random
  // bytes. Seeds above large_seed_bytes (the deep-nesting files of several hundred KB) cost a
  // hundred ordinary inputs each: one generated input in large_seed_share starts from one of them.
  Bytes next();
  static constexpr std::size_t large_seed_bytes = 65536;
  static constexpr std::size_t large_seed_share = 32;
  const std::vector<SeedInput>& seeds() const { return seeds_; }

 private:
  Bytes random_bytes();
  const SeedInput& pick_seed();
  void mutate(Bytes& data);

  std::vector<SeedInput> seeds_;
  std::vector<std::size_t> ordinary_, large_;  // indices into seeds_
  SplitMix64 random_;
  std::size_t max_len_;
};

// FNV-1a over the length and bytes of each input in turn: two runs that print the same digest
// executed the same inputs in the same order.
class InputDigest {
 public:
  void add(const std::uint8_t* data, std::size_t size);
  std::string hex() const;

 private:
  std::uint64_t hash_ = 1469598103934665603ull;
};

}  // namespace shadowcts::fuzzing
