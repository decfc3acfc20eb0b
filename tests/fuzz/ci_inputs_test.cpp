#include "ci_inputs.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace shadowcts::fuzzing {
namespace {

std::vector<SeedInput> text_seeds() {
  const auto bytes = [](const std::string& s) { return Bytes(s.begin(), s.end()); };
  return {{"a.json", bytes(R"({"name": "a", "camera": {"width": 8, "height": 8}})")},
          {"b.obj", bytes("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")},
          {"c.bin", Bytes{0, 1, 2, 3, 4, 5, 6, 7, 255}}};
}

std::vector<Bytes> generate(std::vector<SeedInput> seeds, std::uint64_t seed, std::size_t count,
                            std::size_t max_len = 65536) {
  CiInputGenerator generator(std::move(seeds), seed, max_len);
  std::vector<Bytes> inputs;
  for (std::size_t k = 0; k < count; ++k) inputs.push_back(generator.next());
  return inputs;
}

std::string digest_of(const std::vector<Bytes>& inputs) {
  InputDigest digest;
  for (const Bytes& b : inputs) digest.add(b.data(), b.size());
  return digest.hex();
}

TEST(FuzzCiInputs, TheSameSeedGivesTheSameInputsInTheSameOrder) {
  const auto first = generate(text_seeds(), 1, 2000);
  const auto second = generate(text_seeds(), 1, 2000);
  EXPECT_EQ(first, second);
  EXPECT_EQ(digest_of(first), digest_of(second));
}

TEST(FuzzCiInputs, AnotherSeedGivesOtherInputs) {
  const auto first = generate(text_seeds(), 1, 200);
  const auto second = generate(text_seeds(), 2, 200);
  EXPECT_NE(first, second);
  EXPECT_NE(digest_of(first), digest_of(second));
}

TEST(FuzzCiInputs, DigestSeesOrderAndBoundariesOfInputs) {
  InputDigest ab, ba, joined;
  const Bytes a{1, 2}, b{3};
  ab.add(a.data(), a.size());
  ab.add(b.data(), b.size());
  ba.add(b.data(), b.size());
  ba.add(a.data(), a.size());
  const Bytes all{1, 2, 3};
  joined.add(all.data(), all.size());
  EXPECT_NE(ab.hex(), ba.hex());
  EXPECT_NE(ab.hex(), joined.hex());
}

TEST(FuzzCiInputs, InputsStayWithinTheLimitAndVary) {
  const std::size_t max_len = 4096;
  const auto inputs = generate(text_seeds(), 7, 3000, max_len);
  std::size_t longest = 0, changed = 0;
  for (const Bytes& input : inputs) {
    EXPECT_LE(input.size(), max_len);
    longest = std::max(longest, input.size());
    bool is_seed = false;
    for (const SeedInput& s : text_seeds()) is_seed |= s.bytes == input;
    changed += !is_seed;
  }
  EXPECT_GT(changed, inputs.size() * 9 / 10);
  EXPECT_EQ(longest, max_len);  // the repeat mutation fills the room it has
}

// Deep nesting and long lists come from repeating a short chunk thousands of times.
TEST(FuzzCiInputs, ReachesDeepNestingFromASmallSeed) {
  const std::vector<SeedInput> seeds = {{"n.json", Bytes{'[', '1', ']'}}};
  std::size_t deepest = 0;
  for (const Bytes& input : generate(seeds, 3, 3000)) {
    std::size_t run = 0;
    for (const std::uint8_t c : input) {
      run = c == '[' ? run + 1 : 0;
      deepest = std::max(deepest, run);
    }
  }
  EXPECT_GE(deepest, 10000u);
}

// Deep-nesting seeds are hundreds of KB: they seed one generated input in 32, not one in two.
TEST(FuzzCiInputs, LargeSeedsAreMutatedRarely) {
  const Bytes large(CiInputGenerator::large_seed_bytes + 1, 'L');
  const std::vector<SeedInput> seeds = {{"deep.json", large}, {"small.json", Bytes{'[', ']'}}};
  std::size_t from_large = 0;
  const std::size_t count = 6400;
  for (const Bytes& input : generate(seeds, 9, count, 1 << 20))
    from_large += std::count(input.begin(), input.end(), 'L') > 1000;
  EXPECT_GT(from_large, count / CiInputGenerator::large_seed_share / 2);
  EXPECT_LT(from_large, count / CiInputGenerator::large_seed_share * 2);
}

TEST(FuzzCiInputs, WithoutSeedsEveryInputIsRandomBytes) {
  const auto inputs = generate({}, 5, 500);
  std::size_t distinct_lengths = 0;
  std::vector<bool> seen(8193);
  for (const Bytes& input : inputs) {
    ASSERT_LE(input.size(), 8192u);
    if (!seen[input.size()]) ++distinct_lengths;
    seen[input.size()] = true;
  }
  EXPECT_GT(distinct_lengths, 50u);
}

TEST(FuzzCiInputs, SeedFilesAreReadInPathOrderWhateverTheFolderListsFirst) {
  const auto root = std::filesystem::temp_directory_path() /
                    ("shadowcts-ci-inputs-" + std::to_string(::getpid()));
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root / "sub");
  for (const std::string name : {"zz", "b", "a", "sub/c"}) std::ofstream(root / name) << name;
  std::ofstream(root / "long") << std::string(100, 'x');
  const auto seeds = read_seed_inputs({root}, 10);
  std::vector<std::string> names;
  for (const SeedInput& s : seeds)
    names.push_back(std::filesystem::path(s.path).lexically_relative(root).string());
  EXPECT_EQ(names, (std::vector<std::string>{"a", "b", "long", "sub/c", "zz"}));
  EXPECT_EQ(seeds[2].bytes.size(), 10u);  // truncated to max_len
  EXPECT_THROW(read_seed_inputs({root / "missing"}, 10), std::runtime_error);
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace shadowcts::fuzzing
