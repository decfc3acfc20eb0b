// The exact zero-area test of shadowcts/geometry/triangle_area.h.
#include "shadowcts/geometry/triangle_area.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include <glm/vec3.hpp>

namespace shadowcts {
namespace {

TEST(ExactSumIsZero, SeesThroughCancellationThatDoubleSummationLoses) {
  // Summed left to right in double, both of these give 0.
  const double lost_one[6] = {1e30, 1.0, -1e30, 0.0, 0.0, 0.0};
  EXPECT_FALSE(exact_sum_is_zero(lost_one));
  const double lost_tiny[6] = {0x1p-60, 1.0, -1.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(exact_sum_is_zero(lost_tiny));
  // And these sum to exactly zero although double summation does not see it.
  const double zero[6] = {1e30, 1.0, -1e30, -1.0, 0x1p-100, -0x1p-100};
  EXPECT_TRUE(exact_sum_is_zero(zero));
  const double thirds[6] = {0.1, 0.2, -0.1, -0.2, 0.3, -0.3};
  EXPECT_TRUE(exact_sum_is_zero(thirds));
  const double empty[6] = {0.0, -0.0, 0.0, 0.0, 0.0, 0.0};
  EXPECT_TRUE(exact_sum_is_zero(empty));
}

TEST(ExactSumIsZero, AgreesWithIntegerArithmeticOnRandomDyadicTerms) {
  // Terms k * 2^e with |k| <= 2^20 and e in [-20, 20]: scaled by 2^20 they are integers below
  // 2^60, so a 64-bit integer sum is the truth, while the 60-bit spread exceeds double precision.
  std::mt19937_64 random(3);
  std::uniform_int_distribution<int> mantissa(-(1 << 20), 1 << 20);
  std::uniform_int_distribution<int> exponent(-20, 20);
  int zeros = 0, rounded_wrongly = 0;
  for (int i = 0; i < 20000; ++i) {
    double terms[6];
    std::int64_t exact = 0;
    double naive = 0.0;
    for (int j = 0; j < 5; ++j) {
      const int k = mantissa(random), e = exponent(random);
      terms[j] = std::ldexp(static_cast<double>(k), e);
      exact += static_cast<std::int64_t>(k) * (std::int64_t{1} << (e + 20));
    }
    // Half the time, close the sum to zero when the closing term is a double.
    const double closing = -std::ldexp(static_cast<double>(exact), -20);
    const bool close = i % 2 == 0 && static_cast<std::int64_t>(std::ldexp(-closing, 20)) == exact;
    terms[5] = close ? closing : 0.0;
    if (close) exact = 0;
    for (const double term : terms) naive += term;
    zeros += exact == 0 ? 1 : 0;
    rounded_wrongly += (naive == 0.0) != (exact == 0) ? 1 : 0;
    EXPECT_EQ(exact_sum_is_zero(terms), exact == 0) << i;
  }
  EXPECT_GT(zeros, 1000);
  EXPECT_GT(rounded_wrongly, 10);  // the cases are hard enough to need exact arithmetic
}

TEST(TriangleHasZeroArea, CollinearAndCoincidentVertices) {
  const glm::vec3 a(0.1f, -2.5f, 7.0f), b(3.5f, 0.25f, -1.0f);
  EXPECT_TRUE(triangle_has_zero_area(a, a, a));
  EXPECT_TRUE(triangle_has_zero_area(a, a, b));
  EXPECT_TRUE(triangle_has_zero_area(a, b, b));
  EXPECT_TRUE(triangle_has_zero_area(glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 3.0f),
                                     glm::vec3(-3.0f, -6.0f, -9.0f)));
  EXPECT_TRUE(triangle_has_zero_area(glm::vec3(1e30f, 0.0f, 0.0f), glm::vec3(-1e-30f, 0.0f, 0.0f),
                                     glm::vec3(5.0f, 0.0f, 0.0f)));
  EXPECT_FALSE(triangle_has_zero_area(glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f),
                                      glm::vec3(0.0f, 1.0f, 0.0f)));
}

TEST(TriangleHasZeroArea, OneUlpOffTheLineHasArea) {
  const glm::vec3 a(1.0f, 2.0f, 3.0f), d(0.25f, -0.5f, 0.125f);
  const glm::vec3 b = a + 4.0f * d, c = a + 12.0f * d;
  ASSERT_TRUE(triangle_has_zero_area(a, b, c));
  for (int axis = 0; axis < 3; ++axis) {
    glm::vec3 nudged = c;
    nudged[axis] = std::nextafter(nudged[axis], 100.0f);
    EXPECT_FALSE(triangle_has_zero_area(a, b, nudged)) << axis;
  }
  // Large coordinates: the area is tiny relative to them but not zero.
  const glm::vec3 far(1e7f, 1e7f, 1e7f);
  EXPECT_FALSE(triangle_has_zero_area(far, far + glm::vec3(1.0f, 0.0f, 0.0f),
                                      far + glm::vec3(2.0f, 1.0f, 0.0f)));
}

}  // namespace
}  // namespace shadowcts
