// The only translation unit of the light-assignment oracle that uses CGAL, GMP and MPFR.
#include "oracles/light_assignment/light_volume_predicates.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include <CGAL/Exact_rational.h>
#include <gmpxx.h>
#include <mpfr.h>

namespace shadowcts {
namespace {

// CGAL is configured with GMPXX here (CGAL_USE_GMPXX), so its exact rational is mpq_class and
// its mpq_t can be handed to MPFR for the comparison with the transcendental cosine.
using Rational = CGAL::Exact_rational;
static_assert(std::is_same_v<Rational, mpq_class>, "CGAL::Exact_rational is expected to be GMP's");

constexpr double unit_roundoff = 0x1p-53;
// Far below any value a product of float-derived numbers can take in a decided comparison; it
// absorbs subnormal rounding (absolute error <= 2^-1075 per operation) in the error bounds.
constexpr double underflow_guard = 0x1p-1000;

std::atomic<std::uint64_t> fallbacks{0};

void count_fallback() {
  fallbacks.fetch_add(1, std::memory_order_relaxed);
}

// x_i - c_i for x = base + delta * move, rounded twice (delta * move is exact: move is -1, 0 or
// 1). The error is at most 2.0001 u A with A = |base| + delta + |c|, returned in `magnitude`.
double moved_difference(const LightQueryPoint& x, int i, double c, double& magnitude) {
  const double moved = x.base[i] + x.delta * double(x.move[i]);
  magnitude = std::fabs(x.base[i]) + x.delta + std::fabs(c);
  return moved - c;
}

Rational moved_coordinate(const LightQueryPoint& x, int i) {
  return Rational(x.base[i]) + Rational(x.delta) * x.move[i];
}

std::array<Rational, 3> exact_difference(const LightQueryPoint& x, const glm::dvec3& c) {
  return {moved_coordinate(x, 0) - Rational(c.x), moved_coordinate(x, 1) - Rational(c.y),
          moved_coordinate(x, 2) - Rational(c.z)};
}

// Compares the rational r with cos^2(theta) for a float theta in (0, pi): -1 if r < cos^2,
// +1 if r > cos^2. Never 0 (cos^2 theta = (1 + cos 2 theta) / 2 is transcendental).
int compare_with_cos_squared(const Rational& r, float theta) {
  for (mpfr_prec_t precision = 64; precision <= 65536; precision *= 2) {
    mpfr_t angle, low, high;
    mpfr_inits2(precision, angle, low, high, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_d(angle, double(theta), MPFR_RNDN);  // exact: a float fits
    mpfr_cos(low, angle, MPFR_RNDD);
    mpfr_cos(high, angle, MPFR_RNDU);
    // |cos| between the absolute bounds, then squared with outward rounding.
    if (mpfr_sgn(high) < 0) {
      mpfr_swap(low, high);
      mpfr_abs(low, low, MPFR_RNDN);  // exact
      mpfr_abs(high, high, MPFR_RNDN);
    }
    int result = 0;
    if (mpfr_sgn(low) >= 0) {
      mpfr_sqr(low, low, MPFR_RNDD);
      mpfr_sqr(high, high, MPFR_RNDU);
      if (mpfr_cmp_q(low, r.get_mpq_t()) > 0)
        result = -1;  // r < cos^2
      else if (mpfr_cmp_q(high, r.get_mpq_t()) < 0)
        result = 1;
    }
    mpfr_clears(angle, low, high, static_cast<mpfr_ptr>(nullptr));
    if (result != 0) return result;
  }
  throw std::logic_error("light_volume_predicates: cos^2 of a float angle did not separate");
}

// The sign of cos(theta) for a float theta in (0, pi): the 53-bit enclosure decides, since no
// float lies within 4e-8 of pi / 2.
int cos_sign(const ExactLightVolume& light) {
  if (light.cos_low > 0.0) return 1;
  if (light.cos_high < 0.0) return -1;
  throw std::logic_error("light_volume_predicates: a float half angle too close to pi / 2");
}

bool sphere_contains_exact(const ExactLightVolume& light, const LightQueryPoint& x) {
  const auto v = exact_difference(x, light.centre);
  return v[0] * v[0] + v[1] * v[1] + v[2] * v[2] <= Rational(light.range) * Rational(light.range);
}

bool cone_contains_exact(const ExactLightVolume& light, const LightQueryPoint& x) {
  const auto v = exact_difference(x, light.centre);
  const Rational length_squared = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  if (length_squared == 0) return true;  // the apex
  const Rational a[3] = {Rational(light.axis.x), Rational(light.axis.y), Rational(light.axis.z)};
  const Rational dot = v[0] * a[0] + v[1] * a[1] + v[2] * a[2];
  const Rational axis_squared = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  // In the cone iff dot >= |v| |a| cos(theta).
  if (cos_sign(light) > 0) {
    if (dot <= 0) return false;
    const Rational ratio = dot * dot / (length_squared * axis_squared);
    return compare_with_cos_squared(ratio, light.cone_half_angle) > 0;
  }
  if (dot >= 0) return true;
  const Rational ratio = dot * dot / (length_squared * axis_squared);
  return compare_with_cos_squared(ratio, light.cone_half_angle) < 0;
}

bool in_front_exact(const glm::vec3& normal, const ExactLightVolume& light,
                    const LightQueryPoint& x) {
  const auto v = exact_difference(x, light.centre);  // x - c
  const Rational dot =
      v[0] * Rational(normal.x) + v[1] * Rational(normal.y) + v[2] * Rational(normal.z);
  return dot < 0;  // n . (c - x) > 0
}

bool sphere_meets_box_exact(const glm::vec3& centre, float range, const Aabb& box) {
  Rational distance_squared = 0;
  for (int i = 0; i < 3; ++i) {
    const Rational c(centre[i]), low(box.min[i]), high(box.max[i]);
    Rational gap = 0;
    if (c < low) gap = low - c;
    if (c > high) gap = c - high;
    distance_squared += gap * gap;
  }
  return distance_squared <= Rational(range) * Rational(range);
}

// Filtered sphere test: +1 inside, -1 outside, 0 undecided.
int sphere_filter(const ExactLightVolume& light, const LightQueryPoint& x, double& length_squared,
                  double& magnitude_squared) {
  double a0, a1, a2;
  const double v0 = moved_difference(x, 0, light.centre.x, a0);
  const double v1 = moved_difference(x, 1, light.centre.y, a1);
  const double v2 = moved_difference(x, 2, light.centre.z, a2);
  length_squared = v0 * v0 + v1 * v1 + v2 * v2;
  magnitude_squared = a0 * a0 + a1 * a1 + a2 * a2;
  // |computed - exact| <= sum e_i (2 |v_i| + e_i) + gamma_3 sum v_i^2 <= 7.01 u sum A_i^2; the
  // bound takes 32 u, which also covers the rounding of the bound and of the comparison.
  const double error = 32.0 * unit_roundoff * magnitude_squared + underflow_guard;
  if (length_squared + error < light.range_squared) return 1;
  if (length_squared - error > light.range_squared) return -1;
  return 0;
}

// Filtered cone test (given the sphere filter's sums): +1 inside, -1 outside, 0 undecided.
int cone_filter(const ExactLightVolume& light, const LightQueryPoint& x, double length_squared,
                double magnitude_squared) {
  const double u = unit_roundoff;
  double dot = 0.0, dot_magnitude = 0.0;
  for (int i = 0; i < 3; ++i) {
    double a = 0.0;
    const double v = moved_difference(x, i, light.centre[i], a);
    dot += v * light.axis[i];
    dot_magnitude += a * std::fabs(light.axis[i]);
  }
  // Error of the dot product: sum e_i |d_i| + gamma_3 sum |v_i| |d_i| <= 5.01 u sum A_i |d_i|.
  const double dot_error = 8.0 * u * dot_magnitude;
  // |v| from the rounded squared length: |sqrt(s~) - sqrt(s)| <= min(sqrt(E), E / sqrt(s~)).
  const double length_squared_error = 16.0 * u * magnitude_squared;
  const double length = std::sqrt(length_squared);
  double length_error = std::sqrt(length_squared_error);
  if (length > 0.0) length_error = std::min(length_error, length_squared_error / length);
  length_error = 1.01 * length_error + 2.0 * u * length;
  const double axis_length = light.axis_length;  // relative error <= 2.6 u
  const double cos_mid = 0.5 * (light.cos_low + light.cos_high);
  const double cos_error = 0.5 * (light.cos_high - light.cos_low) + 2.0 * u * std::fabs(cos_mid);
  const double threshold = length * axis_length * cos_mid;
  const double margin = dot - threshold;
  const double length_upper = length + length_error;
  const double error = dot_error + length_upper * axis_length * (cos_error + 4.0 * u) +
                       std::fabs(cos_mid) * axis_length * (length_error + 4.0 * u * length_upper) +
                       3.0 * u * std::fabs(threshold) + u * std::fabs(margin);
  const double bound = 2.0 * error + underflow_guard;
  if (margin > bound) return 1;
  if (margin < -bound) return -1;
  return 0;
}

}  // namespace

ExactLightVolume prepare_light_volume(const RangedLight& light) {
  ExactLightVolume v;
  v.kind = light.kind;
  v.centre = glm::dvec3(light.centre);
  v.range = double(light.range);
  v.range_squared = v.range * v.range;
  if (light.kind == RangedLightKind::spot) {
    v.axis = glm::dvec3(light.direction);
    v.axis_length = std::sqrt(v.axis.x * v.axis.x + v.axis.y * v.axis.y + v.axis.z * v.axis.z);
    v.cone_half_angle = light.cone_half_angle;
    mpfr_t angle, cosine;
    mpfr_inits2(53, angle, cosine, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_d(angle, double(light.cone_half_angle), MPFR_RNDN);
    mpfr_cos(cosine, angle, MPFR_RNDD);
    v.cos_low = mpfr_get_d(cosine, MPFR_RNDD);
    mpfr_cos(cosine, angle, MPFR_RNDU);
    v.cos_high = mpfr_get_d(cosine, MPFR_RNDU);
    mpfr_clears(angle, cosine, static_cast<mpfr_ptr>(nullptr));
  }
  return v;
}

bool light_volume_contains(const ExactLightVolume& light, const LightQueryPoint& x) {
  double length_squared = 0.0, magnitude_squared = 0.0;
  const int sphere = sphere_filter(light, x, length_squared, magnitude_squared);
  if (sphere < 0) return false;
  if (sphere == 0) {
    count_fallback();
    if (!sphere_contains_exact(light, x)) return false;
  }
  if (light.kind == RangedLightKind::sphere) return true;
  const int cone = cone_filter(light, x, length_squared, magnitude_squared);
  if (cone != 0) return cone > 0;
  count_fallback();
  return cone_contains_exact(light, x);
}

bool light_in_front_of(const glm::vec3& normal, const ExactLightVolume& light,
                       const LightQueryPoint& x) {
  double dot = 0.0, magnitude = 0.0;
  for (int i = 0; i < 3; ++i) {
    double a = 0.0;
    const double v = moved_difference(x, i, light.centre[i], a);  // x - c
    dot -= v * double(normal[i]);
    magnitude += a * std::fabs(double(normal[i]));
  }
  // As the dot product of the cone filter: <= 5.01 u sum A_i |n_i|, taken as 16 u.
  const double error = 16.0 * unit_roundoff * magnitude + underflow_guard;
  if (dot > error) return true;
  if (dot < -error) return false;
  count_fallback();
  return in_front_exact(normal, light, x);
}

bool sphere_meets_box(const glm::vec3& centre, float range, const Aabb& box) {
  double distance_squared = 0.0, magnitude_squared = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double c = centre[i], low = box.min[i], high = box.max[i];
    // Rounding is monotone, so the max of the rounded gaps is the rounded true gap:
    // error <= u (|low| + |c| + |high|) per axis.
    const double gap = std::max({0.0, low - c, c - high});
    const double b = std::fabs(low) + std::fabs(c) + std::fabs(high);
    distance_squared += gap * gap;
    magnitude_squared += b * b;
  }
  const double r2 = double(range) * double(range);
  const double error = 16.0 * unit_roundoff * magnitude_squared + underflow_guard;
  if (distance_squared + error < r2) return true;
  if (distance_squared - error > r2) return false;
  count_fallback();
  return sphere_meets_box_exact(centre, range, box);
}

namespace exact_only {

bool light_volume_contains(const ExactLightVolume& light, const LightQueryPoint& x) {
  if (!sphere_contains_exact(light, x)) return false;
  return light.kind == RangedLightKind::sphere || cone_contains_exact(light, x);
}

bool light_in_front_of(const glm::vec3& normal, const ExactLightVolume& light,
                       const LightQueryPoint& x) {
  return in_front_exact(normal, light, x);
}

bool sphere_meets_box(const glm::vec3& centre, float range, const Aabb& box) {
  return sphere_meets_box_exact(centre, range, box);
}

}  // namespace exact_only

std::uint64_t exact_light_predicate_fallbacks() {
  return fallbacks.load(std::memory_order_relaxed);
}

}  // namespace shadowcts
