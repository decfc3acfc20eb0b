#include "reference/ptsv/exact_orientation.h"

#include <array>
#include <cmath>
#include <limits>

namespace shadowcts::ptsv {
namespace {

// Both determinants are sums of signed products of three floats:
//   det[b - a, c - a, l - a] = l . N - det[a, b, c],   det[b - a, c - a, d] = d . N,
// with N = a x b + b x c + c x a. A product of two floats is exact in double; times a third float
// it is exactly hi + lo with lo = fma(p, w, -hi) (Dekker's two-product). The signed sum of those
// doubles is decided by a floating-point filter first and, where the filter cannot tell, exactly
// by Shewchuk's grow-expansion (a nonoverlapping expansion's sign is its largest component's).
class ExactSum {
 public:
  void add_product(double sign, float u, float v, float w) {
    const double uv = double(u) * double(v);  // exact: 48 significand bits
    const double hi = uv * double(w);
    const double lo = std::fma(uv, double(w), -hi);
    terms_[count_++] = sign * hi;
    terms_[count_++] = sign * lo;
  }

  int sign() const {
    double sum = 0.0, magnitude = 0.0;
    for (int i = 0; i < count_; ++i) {
      sum += terms_[i];
      magnitude += std::fabs(terms_[i]);
    }
    // Recursive summation of n terms errs by at most (n - 1) u sum|t_i|; twice that, plus an
    // allowance for underflow, is a safe filter.
    const double bound = 2.0 * double(count_) * std::numeric_limits<double>::epsilon() * magnitude +
                         std::numeric_limits<double>::min();
    if (sum > bound) return 1;
    if (sum < -bound) return -1;
    return exact_sign();
  }

 private:
  int exact_sign() const {
    std::array<double, max_terms> expansion{};
    int length = 0;
    for (int i = 0; i < count_; ++i) {
      double carry = terms_[i];
      int kept = 0;
      for (int j = 0; j < length; ++j) {
        // Knuth's two-sum: carry + expansion[j] == sum + error exactly.
        const double sum = carry + expansion[j];
        const double b_virtual = sum - carry;
        const double a_virtual = sum - b_virtual;
        const double error = (carry - a_virtual) + (expansion[j] - b_virtual);
        if (error != 0.0) expansion[kept++] = error;
        carry = sum;
      }
      if (carry != 0.0) expansion[kept++] = carry;
      length = kept;
    }
    if (length == 0) return 0;
    return expansion[length - 1] > 0.0 ? 1 : -1;
  }

  static constexpr int max_terms = 48;
  std::array<double, max_terms> terms_{};
  int count_ = 0;
};

// Adds factor . (a x b + b x c + c x a), one product of three floats per term.
void add_dot_vector_area(ExactSum& sum, const glm::vec3& factor, const glm::vec3& a,
                         const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3* vertices[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const glm::vec3& p = *vertices[k];
    const glm::vec3& q = *vertices[(k + 1) % 3];
    // p x q = (p.y q.z - p.z q.y, p.z q.x - p.x q.z, p.x q.y - p.y q.x)
    sum.add_product(1.0, factor.x, p.y, q.z);
    sum.add_product(-1.0, factor.x, p.z, q.y);
    sum.add_product(1.0, factor.y, p.z, q.x);
    sum.add_product(-1.0, factor.y, p.x, q.z);
    sum.add_product(1.0, factor.z, p.x, q.y);
    sum.add_product(-1.0, factor.z, p.y, q.x);
  }
}

}  // namespace

int orientation_towards_point(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                              const glm::vec3& light) {
  ExactSum sum;
  add_dot_vector_area(sum, light, a, b, c);
  // - det[a, b, c] = - a . (b x c)
  sum.add_product(-1.0, a.x, b.y, c.z);
  sum.add_product(1.0, a.x, b.z, c.y);
  sum.add_product(-1.0, a.y, b.z, c.x);
  sum.add_product(1.0, a.y, b.x, c.z);
  sum.add_product(-1.0, a.z, b.x, c.y);
  sum.add_product(1.0, a.z, b.y, c.x);
  return sum.sign();
}

int orientation_towards_direction(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                                  const glm::vec3& towards_light) {
  ExactSum sum;
  add_dot_vector_area(sum, towards_light, a, b, c);
  return sum.sign();
}

}  // namespace shadowcts::ptsv
