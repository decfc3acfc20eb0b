#include "shadowcts/huge_pages.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace shadowcts {
namespace {

std::uintptr_t address(const void* p) {
  return reinterpret_cast<std::uintptr_t>(p);
}

// The VmFlags line of the mapping in /proc/self/smaps that holds p ("" when none is found).
std::string vm_flags_of(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= address(p) && address(p) < end;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

TEST(HugePages, SmallArraysKeepTheirAlignmentAndAreWritable) {
  for (const std::size_t alignment : {1u, 8u, 64u, 256u}) {
    void* p = allocate_large(1000, alignment);
    EXPECT_EQ(address(p) % alignment, 0u);
    std::memset(p, 0xAB, 1000);
    free_large(p);
  }
  free_large(allocate_large(0, 8));  // an empty array is still a valid pointer to free
}

TEST(HugePages, LargeArraysStartOnAHugePageAndAreWritableToTheEnd) {
  const std::size_t bytes = 3 * huge_page_bytes + 12345;
  auto* p = static_cast<unsigned char*>(allocate_large(bytes, 64));
  EXPECT_EQ(address(p) % huge_page_bytes, 0u);
  std::memset(p, 0x5A, bytes);
  EXPECT_EQ(p[bytes - 1], 0x5A);
  free_large(p);
}

TEST(HugePages, LargeArraysAskTheKernelForHugePages) {
  std::ifstream mode_file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(mode_file, mode);
  if (mode.empty() || mode.find("[never]") != std::string::npos)
    GTEST_SKIP() << "transparent huge pages are off or absent here: " << mode;
  auto* p = static_cast<unsigned char*>(allocate_large(4 * huge_page_bytes, 64));
  p[0] = 1;
  // MADV_HUGEPAGE marks the mapping "hg"; whether the kernel then finds free huge pages is its
  // business, so that is not asserted.
  const std::string flags = vm_flags_of(p);
  free_large(p);
  ASSERT_FALSE(flags.empty());
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
}

TEST(HugePages, VectorsBehaveAsVectors) {
  HugePageVector<std::uint32_t> v(std::size_t(1) << 20);  // 4 MiB: on huge pages
  for (const std::uint32_t x : v) ASSERT_EQ(x, 0u);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::uint32_t(i);
  v.push_back(7);
  EXPECT_EQ(v.size(), (std::size_t(1) << 20) + 1);
  EXPECT_EQ(v[12345], 12345u);
  EXPECT_EQ(v.back(), 7u);
  const HugePageVector<std::uint32_t> copy = v;
  EXPECT_EQ(copy, v);
}

TEST(HugePages, AFreedLargeArrayServesTheNextRequestThatFitsItAndNoLargerOne) {
  if (!large_blocks_are_reused()) GTEST_SKIP() << "a sanitizer build frees every block";
  const std::size_t bytes = 5 * huge_page_bytes;
  auto* p = static_cast<unsigned char*>(allocate_large(bytes, 64));
  std::memset(p, 0x3C, bytes);
  free_large(p);
  // Larger than the idle block: a fresh one.
  void* larger = allocate_large(bytes + huge_page_bytes, 64);
  EXPECT_NE(larger, static_cast<void*>(p));
  // Fits (a smaller request rounds up to the same huge pages): the idle block, whole and writable.
  auto* again = static_cast<unsigned char*>(allocate_large(bytes - huge_page_bytes + 1, 8));
  EXPECT_EQ(again, p);
  std::memset(again, 0x11, bytes);
  // Taken: the next request of its size gets another block.
  void* other = allocate_large(bytes, 64);
  EXPECT_NE(other, static_cast<void*>(p));
  free_large(other);
  free_large(again);
  free_large(larger);
}

TEST(HugePages, ARequestOfLessThanHalfAnIdleBlockDoesNotTakeIt) {
  if (!large_blocks_are_reused()) GTEST_SKIP() << "a sanitizer build frees every block";
  void* big = allocate_large(16 * huge_page_bytes, 64);
  free_large(big);
  void* small = allocate_large(4 * huge_page_bytes, 64);
  EXPECT_NE(small, big);
  void* fits = allocate_large(16 * huge_page_bytes, 64);
  EXPECT_EQ(fits, big);
  free_large(small);
  free_large(fits);
}

TEST(HugePages, ImpossibleSizesThrowInsteadOfWrapping) {
  EXPECT_THROW(HugePageAllocator<double>().allocate(std::numeric_limits<std::size_t>::max() / 4),
               std::bad_array_new_length);
  EXPECT_THROW(allocate_large(std::numeric_limits<std::size_t>::max() - 10, 64), std::bad_alloc);
}

}  // namespace
}  // namespace shadowcts
