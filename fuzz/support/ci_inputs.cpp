#include "ci_inputs.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>

namespace shadowcts::fuzzing {
namespace {

Bytes read_file(const std::filesystem::path& path, std::size_t max_len) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot read seed file");
  Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() > max_len) bytes.resize(max_len);
  return bytes;
}

// Integers that sit at the edges of sizes, counts and signed ranges, little-endian.
constexpr std::array<std::uint64_t, 12> interesting_integers = {
    0,      1,          0x7f,       0x80,       0xff,       0x7fff,
    0xffff, 0x7fffffff, 0x80000000, 0xffffffff, 0xfffffffe, 0xffffffffffffffffull};

// Replacements for a number in a text format: overflows, NaN, subnormals, huge counts.
constexpr std::array<std::string_view, 16> interesting_numbers = {
    "0",    "-1",     "1",     "2",      "2147483647", "4294967295", "18446744073709551616",
    "1e38", "3.5e38", "1e300", "-1e300", "nan",        "inf",        "1e-45",
    "0.5",  "1e-300"};

}  // namespace

std::vector<SeedInput> read_seed_inputs(const std::vector<std::filesystem::path>& paths,
                                        std::size_t max_len) {
  std::vector<SeedInput> seeds;
  for (const std::filesystem::path& root : paths) {
    std::vector<std::filesystem::path> files;
    if (std::filesystem::is_directory(root)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
        if (entry.is_regular_file()) files.push_back(entry.path());
      std::sort(files.begin(), files.end());
    } else if (std::filesystem::is_regular_file(root)) {
      files.push_back(root);
    } else {
      throw std::runtime_error(root.string() + ": not a seed file or folder");
    }
    for (const auto& file : files) seeds.push_back({file.string(), read_file(file, max_len)});
  }
  return seeds;
}

std::uint64_t SplitMix64::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

CiInputGenerator::CiInputGenerator(std::vector<SeedInput> seeds, std::uint64_t seed,
                                   std::size_t max_len)
    : seeds_(std::move(seeds)), random_(seed), max_len_(max_len) {
  for (std::size_t k = 0; k < seeds_.size(); ++k)
    (seeds_[k].bytes.size() > large_seed_bytes ? large_ : ordinary_).push_back(k);
}

Bytes CiInputGenerator::random_bytes() {
  // Mostly short (structured targets read a scene from a few hundred bytes), sometimes long.
  const std::size_t limit = std::min<std::size_t>(max_len_, std::size_t(1) << random_.below(13));
  Bytes bytes(random_.below(limit + 1));
  for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(random_.next());
  return bytes;
}

const SeedInput& CiInputGenerator::pick_seed() {
  const bool large = ordinary_.empty() || (!large_.empty() && random_.below(large_seed_share) == 0);
  const std::vector<std::size_t>& pool = large ? large_ : ordinary_;
  return seeds_[pool[random_.below(pool.size())]];
}

Bytes CiInputGenerator::next() {
  if (seeds_.empty() || random_.below(8) == 0) return random_bytes();
  Bytes data = pick_seed().bytes;
  const std::size_t mutations = 1 + random_.below(4);
  for (std::size_t m = 0; m < mutations; ++m) mutate(data);
  return data;
}

void CiInputGenerator::mutate(Bytes& data) {
  const auto byte = [this] { return static_cast<std::uint8_t>(random_.next()); };
  const auto position = [&](std::size_t extra) { return random_.below(data.size() + extra); };
  switch (random_.below(11)) {
    case 0:  // flip one bit
      if (!data.empty()) data[position(0)] ^= static_cast<std::uint8_t>(1u << random_.below(8));
      break;
    case 1:  // replace one byte
      if (!data.empty()) data[position(0)] = byte();
      break;
    case 2: {  // insert a few random bytes
      const std::size_t at = position(1), n = 1 + random_.below(8);
      Bytes inserted(n);
      for (std::uint8_t& b : inserted) b = byte();
      data.insert(data.begin() + std::ptrdiff_t(at), inserted.begin(), inserted.end());
      break;
    }
    case 3: {  // erase a range
      if (data.empty()) break;
      const std::size_t at = position(0);
      const std::size_t n = 1 + random_.below(std::min<std::size_t>(data.size() - at, 64));
      data.erase(data.begin() + std::ptrdiff_t(at), data.begin() + std::ptrdiff_t(at + n));
      break;
    }
    case 4: {  // copy a chunk over another place
      if (data.size() < 2) break;
      const std::size_t from = position(0), to = position(0);
      const std::size_t n =
          1 + random_.below(std::min({data.size() - from, data.size() - to, std::size_t(64)}));
      std::memmove(data.data() + to, data.data() + from, n);
      break;
    }
    case 5: {  // duplicate a chunk in place
      if (data.empty()) break;
      const std::size_t from = position(0);
      const std::size_t n = 1 + random_.below(std::min<std::size_t>(data.size() - from, 64));
      const Bytes chunk(data.begin() + std::ptrdiff_t(from),
                        data.begin() + std::ptrdiff_t(from + n));
      data.insert(data.begin() + std::ptrdiff_t(position(1)), chunk.begin(), chunk.end());
      break;
    }
    case 6: {  // an interesting integer of 1, 2, 4 or 8 bytes, little- or big-endian
      const std::size_t width = std::size_t(1) << random_.below(4);
      if (data.size() < width) break;
      std::uint64_t value = interesting_integers[random_.below(interesting_integers.size())];
      const bool big_endian = random_.below(2) == 1;
      const std::size_t at = random_.below(data.size() - width + 1);
      for (std::size_t k = 0; k < width; ++k) {
        data[at + (big_endian ? width - 1 - k : k)] = static_cast<std::uint8_t>(value);
        value >>= 8;
      }
      break;
    }
    case 7: {  // a number token of a text format replaced by an extreme one
      if (data.empty()) break;
      std::size_t at = position(0);
      while (at < data.size() && !(data[at] >= '0' && data[at] <= '9')) ++at;
      if (at == data.size()) break;
      std::size_t end = at;
      while (end < data.size() && ((data[end] >= '0' && data[end] <= '9') || data[end] == '.' ||
                                   data[end] == 'e' || data[end] == 'E' || data[end] == '-'))
        ++end;
      const std::string_view number =
          interesting_numbers[random_.below(interesting_numbers.size())];
      data.erase(data.begin() + std::ptrdiff_t(at), data.begin() + std::ptrdiff_t(end));
      data.insert(data.begin() + std::ptrdiff_t(at), number.begin(), number.end());
      break;
    }
    case 8: {  // splice: this input's head, another seed's tail
      const Bytes& other = pick_seed().bytes;
      data.resize(position(1));
      const std::size_t from = random_.below(other.size() + 1);
      data.insert(data.end(), other.begin() + std::ptrdiff_t(from), other.end());
      break;
    }
    case 9: {  // a short chunk repeated 2 .. 2^15 times: deep nesting, long lists, huge counts
      if (data.empty()) break;
      const std::size_t from = position(0);
      const std::size_t n = 1 + random_.below(std::min<std::size_t>(data.size() - from, 8));
      const Bytes chunk(data.begin() + std::ptrdiff_t(from),
                        data.begin() + std::ptrdiff_t(from + n));
      const std::size_t room = max_len_ > data.size() ? (max_len_ - data.size()) / n : 0;
      const std::size_t repeats = std::min(std::size_t(2) << random_.below(15), room);
      Bytes run;
      run.reserve(repeats * n);
      for (std::size_t r = 0; r < repeats; ++r) run.insert(run.end(), chunk.begin(), chunk.end());
      data.insert(data.begin() + std::ptrdiff_t(from), run.begin(), run.end());
      break;
    }
    default:  // truncate
      data.resize(position(1));
      break;
  }
  if (data.size() > max_len_) data.resize(max_len_);
}

void InputDigest::add(const std::uint8_t* data, std::size_t size) {
  const auto mix = [this](std::uint8_t b) {
    hash_ ^= b;
    hash_ *= 1099511628211ull;
  };
  for (int k = 0; k < 8; ++k) mix(static_cast<std::uint8_t>(std::uint64_t(size) >> (8 * k)));
  for (std::size_t i = 0; i < size; ++i) mix(data[i]);
}

std::string InputDigest::hex() const {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash_));
  return text;
}

}  // namespace shadowcts::fuzzing
