// std::sort on the pool: the two halves sorted side by side, then merged. For a strict weak order
// under which equivalent elements are equal (unique keys, or plain values), the sorted sequence is
// unique, so the result is std::sort's to the last bit whatever the split and the thread count.
// (Not for orders that leave distinct elements tied: their order would depend on the split.)
#pragma once
#include <algorithm>
#include <iterator>
#include <vector>

#include "util/parallel.h"

namespace offsetopt {

template <class T, class Less>
void sort_in_parts(std::vector<T>& items, Less less, WorkerPool& pool) {
  const long count = static_cast<long>(items.size());
  const long middle = split_point(count, 2, 1);
  pool.run_parts(2, [&](int part) {
    std::sort(items.begin() + (part == 0 ? 0 : middle), items.begin() + (part == 0 ? middle : count), less);
  });
  std::vector<T> merged;
  merged.reserve(items.size());
  std::merge(items.begin(), items.begin() + middle, items.begin() + middle, items.end(), std::back_inserter(merged), less);
  items.swap(merged);
}

}  // namespace offsetopt
