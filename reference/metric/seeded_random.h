#pragma once
// Portable seeded randomness for the clustering and the tree builds. std:: distributions differ
// between standard libraries, so the draws are written here on top of std::mt19937_64, whose
// output sequence the standard fixes.
#include <cstdint>
#include <random>
#include <vector>

namespace shadowcts::metric {

// SplitMix64 finalizer: derives independent seeds for chunks, meshes and builds from one case
// seed, so results do not depend on the order in which threads reach them.
inline std::uint64_t mix_seed(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
  return mix_seed(mix_seed(mix_seed(seed) ^ a) ^ b);
}

// Seed streams of one case: the clustering and the tree build draw from different ones.
inline constexpr std::uint64_t clustering_stream = 1, tree_stream = 2;

// Uniform in [0, 1): the top 53 bits.
inline double uniform_unit(std::mt19937_64& rng) {
  return double(rng() >> 11) * 0x1p-53;
}

// Uniform in [0, n), n > 0, by rejection (no modulo bias).
inline std::uint64_t uniform_index(std::mt19937_64& rng, std::uint64_t n) {
  const std::uint64_t limit = std::uint64_t(-1) - std::uint64_t(-1) % n;
  std::uint64_t x;
  do x = rng();
  while (x >= limit);
  return x % n;
}

// Fisher-Yates shuffle with uniform_index.
template <class T>
void shuffle(std::vector<T>& values, std::mt19937_64& rng) {
  for (std::size_t i = values.size(); i > 1; --i) {
    const std::size_t j = std::size_t(uniform_index(rng, i));
    std::swap(values[i - 1], values[j]);
  }
}

}  // namespace shadowcts::metric
