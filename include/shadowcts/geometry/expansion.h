#pragma once
// Exact arithmetic on floating-point expansions, for host and device: a real number held as a sum
// of doubles ordered by increasing magnitude, no two overlapping in their bits (Priest 1991;
// Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates",
// 1997). Sums and products of doubles are exact as expansions, so the sign of a polynomial in
// float or double inputs is decided exactly without a heap, big integers or GMP: what exact
// fallbacks inside device kernels and SIMD loops need.
//
// Every operation drops zero components, so the last component carries the sign. Capacities are
// compile-time worst cases (an expansion of n components grown by one double has at most n + 1,
// scaled by one double at most 2n); nothing here can overflow its array. The arithmetic is exact
// as long as no product underflows: inputs of magnitude at least 2^-300 or zero keep every
// product of up to six of them far above the smallest double.
#include <cmath>

#include "shadowcts/geometry/rounded_arithmetic.h"
#include "shadowcts/host_device.h"

namespace shadowcts::geometry {
SHADOWCTS_GEOMETRY_ABI_BEGIN

template <int Capacity>
struct Expansion {
  static_assert(Capacity > 0);
  double component[Capacity];
  int size = 0;  // components in use; 0 is the number zero
};

// a + b = sum + error exactly (Knuth's two-sum: no order of magnitudes needed).
SHADOWCTS_HD inline void two_sum(double a, double b, double& sum, double& error) {
  sum = rounded_add(a, b);
  const double b_virtual = rounded_sub(sum, a);
  const double a_virtual = rounded_sub(sum, b_virtual);
  error = rounded_add(rounded_sub(a, a_virtual), rounded_sub(b, b_virtual));
}

// a + b = sum + error exactly, for |a| >= |b| (or a = 0).
SHADOWCTS_HD inline void fast_two_sum(double a, double b, double& sum, double& error) {
  sum = rounded_add(a, b);
  error = rounded_sub(b, rounded_sub(sum, a));
}

// a * b = product + error exactly: the fused multiply-add rounds a * b - product once, and that
// difference is a double.
SHADOWCTS_HD inline void two_product(double a, double b, double& product, double& error) {
  product = rounded_mul(a, b);
  error = fma(a, b, -product);
}

template <int N>
SHADOWCTS_HD inline int sign(const Expansion<N>& e) {
  if (e.size == 0) return 0;
  return e.component[e.size - 1] > 0.0 ? 1 : -1;
}

// The sum of the components, rounded: relative error below 2^-50 for the short expansions of the
// predicates here.
template <int N>
SHADOWCTS_HD inline double estimate(const Expansion<N>& e) {
  double sum = 0.0;
  for (int i = 0; i < e.size; ++i) sum += e.component[i];
  return sum;
}

SHADOWCTS_HD inline Expansion<1> expansion_of(double x) {
  Expansion<1> e;
  e.size = 0;
  if (x != 0.0) e.component[e.size++] = x;
  return e;
}

// a - b as an expansion of at most two components.
SHADOWCTS_HD inline Expansion<2> difference(double a, double b) {
  double d = 0.0, error = 0.0;
  two_sum(a, -b, d, error);
  // Fixed slots, no stores at a computed index: the caller's copy then stays in registers.
  Expansion<2> e;
  e.component[0] = error != 0.0 ? error : d;
  e.component[1] = d;
  e.size = (error != 0.0) + (d != 0.0);
  return e;
}

template <int N>
SHADOWCTS_HD inline Expansion<N> negated(const Expansion<N>& e) {
  Expansion<N> out;
  out.size = e.size;
  for (int i = 0; i < e.size; ++i) out.component[i] = -e.component[i];
  return out;
}

// e += b, in place (each output component is written at or below the input component just read,
// as Shewchuk's grow-expansion allows); e.size < Capacity.
template <int M>
SHADOWCTS_HD inline void grow(Expansion<M>& e, double b) {
  double q = b;
  int k = 0;
  for (int i = 0; i < e.size; ++i) {
    double s = 0.0, error = 0.0;
    two_sum(q, e.component[i], s, error);
    q = s;
    if (error != 0.0) e.component[k++] = error;
  }
  if (q != 0.0) e.component[k++] = q;
  e.size = k;
}

// e + f: f's components grown into e one by one.
template <int N, int M>
SHADOWCTS_HD inline Expansion<N + M> sum(const Expansion<N>& e, const Expansion<M>& f) {
  Expansion<N + M> out;
  out.size = e.size;
  for (int i = 0; i < e.size; ++i) out.component[i] = e.component[i];
  for (int j = 0; j < f.size; ++j) grow(out, f.component[j]);
  return out;
}

// e * b.
template <int N>
SHADOWCTS_HD inline Expansion<2 * N> scaled(const Expansion<N>& e, double b) {
  Expansion<2 * N> out;
  out.size = 0;
  if (e.size == 0 || b == 0.0) return out;
  double q = 0.0, error = 0.0;
  two_product(e.component[0], b, q, error);
  if (error != 0.0) out.component[out.size++] = error;
  for (int i = 1; i < e.size; ++i) {
    double product = 0.0, product_error = 0.0;
    two_product(e.component[i], b, product, product_error);
    double sum1 = 0.0, error1 = 0.0;
    two_sum(q, product_error, sum1, error1);
    if (error1 != 0.0) out.component[out.size++] = error1;
    double sum2 = 0.0, error2 = 0.0;
    fast_two_sum(product, sum1, sum2, error2);
    if (error2 != 0.0) out.component[out.size++] = error2;
    q = sum2;
  }
  if (q != 0.0) out.component[out.size++] = q;
  return out;
}

// e * f: the scaled copies of e grown into one sum (at most 2 N components per copy).
template <int N, int M>
SHADOWCTS_HD inline Expansion<2 * N * M> product(const Expansion<N>& e, const Expansion<M>& f) {
  Expansion<2 * N * M> out;
  out.size = 0;
  for (int j = 0; j < f.size; ++j) {
    const Expansion<2 * N> term = scaled(e, f.component[j]);
    for (int i = 0; i < term.size; ++i) grow(out, term.component[i]);
  }
  return out;
}

// The same number in as few components as the bits allow (Shewchuk's compression): the result
// fits wherever e fits, and the largest component approximates the value to within one ulp.
template <int N>
SHADOWCTS_HD inline Expansion<N> compressed(const Expansion<N>& e) {
  if (e.size < 2) return e;
  // g's components are written (from the top down) before they are read: no copy of e's array.
  Expansion<N> g;
  int bottom = e.size - 1;
  double q = e.component[e.size - 1];
  for (int i = e.size - 2; i >= 0; --i) {
    double sum = 0.0, error = 0.0;
    fast_two_sum(q, e.component[i], sum, error);
    if (error != 0.0) {
      g.component[bottom--] = sum;
      q = error;
    } else {
      q = sum;
    }
  }
  g.component[bottom] = q;
  Expansion<N> h;
  h.size = 0;
  for (int i = bottom + 1; i < e.size; ++i) {
    double sum = 0.0, error = 0.0;
    fast_two_sum(g.component[i], q, sum, error);
    if (error != 0.0) h.component[h.size++] = error;
    q = sum;
  }
  h.component[h.size++] = q;
  if (h.size == 1 && h.component[0] == 0.0) h.size = 0;
  return h;
}

// A copy of e in an array of M components; false (and out untouched) when e has more.
template <int M, int N>
SHADOWCTS_HD inline bool narrowed(const Expansion<N>& e, Expansion<M>& out) {
  if (e.size > M) return false;
  out.size = e.size;
  for (int i = 0; i < e.size; ++i) out.component[i] = e.component[i];
  return true;
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts::geometry
