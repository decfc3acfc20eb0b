// The compiler keeps every float rounding the code writes (CMakeLists.txt: GCC 12's SLP vectorizer
// otherwise drops a double -> float -> double round trip in two of three lanes).
#include <gtest/gtest.h>

namespace {

struct Point {
  double x, y, z;
};

[[gnu::noinline]] Point rounded_to_float(const Point& p) {
  return Point{double(float(p.x)), double(float(p.y)), double(float(p.z))};
}

TEST(FloatRounding, ARoundTripThroughFloatRoundsEveryLane) {
  volatile double seed = 0.1;  // not a constant the compiler could fold
  const Point p = rounded_to_float(Point{seed, 2 * seed, 3 * seed});
  EXPECT_EQ(p.x, double(0.1f));
  EXPECT_EQ(p.y, double(float(0.2)));
  EXPECT_EQ(p.z, double(float(3 * 0.1)));
}

}  // namespace
