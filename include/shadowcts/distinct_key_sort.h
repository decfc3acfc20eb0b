#pragma once
// Distinct keys in ascending order: Highway's vectorized quicksort on two halves at once, then the
// halves merged in two parts at once (oneTBB). The keys are distinct, so the result is std::sort's
// whatever the split. Users link hwy::hwy_contrib.
#include <algorithm>
#include <cstddef>

#include <hwy/contrib/sort/vqsort.h>
#include <tbb/parallel_invoke.h>

namespace shadowcts {

// Sorts keys[0, n) by halves in place, then merges them into out[0, n). `less` is the order that
// hwy::SortAscending sorts Key in.
template <class Key, class Less>
void sort_distinct_keys(Key* keys, std::size_t n, Key* out, Less less) {
  const std::size_t half = n / 2;
  Key* const first = keys;
  Key* const second = first + half;
  Key* const end = first + n;
  tbb::parallel_invoke([&] { hwy::Sorter()(first, half, hwy::SortAscending()); },
                       [&] { hwy::Sorter()(second, n - half, hwy::SortAscending()); });
  // The keys of both halves below the first half's median go first.
  Key* const first_split = first + half / 2;
  Key* const second_split = half == 0 ? second : std::lower_bound(second, end, *first_split, less);
  tbb::parallel_invoke([&] { std::merge(first, first_split, second, second_split, out, less); },
                       [&] {
                         std::merge(first_split, second, second_split, end,
                                    out + (first_split - first) + (second_split - second), less);
                       });
}

}  // namespace shadowcts
