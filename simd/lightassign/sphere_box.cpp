#include "simd/lightassign/sphere_box.h"

#include "shadowcts/geometry/expansion.h"

namespace shadowcts::simd {

bool sphere_meets_box_exact(const glm::vec3& centre, float range, const Aabb& box) {
  using namespace shadowcts::geometry;
  // sum_i gap_i^2 - r^2 as an expansion: every gap is the difference of two floats (exact in two
  // components), every square and sum exact, so its sign is the answer.
  Expansion<8> square[3];
  for (int i = 0; i < 3; ++i) {
    square[i].size = 0;
    const float c = centre[i];
    if (c < box.min[i])
      square[i] = product(difference(box.min[i], c), difference(box.min[i], c));
    else if (c > box.max[i])
      square[i] = product(difference(c, box.max[i]), difference(c, box.max[i]));
  }
  const Expansion<2> minus_r2 = negated(scaled(expansion_of(double(range)), double(range)));
  return sign(sum(sum(sum(minus_r2, square[0]), square[1]), square[2])) <= 0;
}

}  // namespace shadowcts::simd
