// sort_in_parts against std::sort: the same sequence for plain values with many repeats, unique
// composite keys carrying a payload, and the edge sizes (empty, one, two), on one and two threads.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "util/rng.h"
#include "util/sort_in_parts.h"

using namespace offsetopt;

TEST_CASE("sort_in_parts gives std::sort's sequence") {
  Rng rng(7);
  for (const int threads : {1, 2}) {
    WorkerPool pool(threads);
    for (const int size : {0, 1, 2, 3, 17, 1000, 40001}) {
      std::vector<std::int64_t> values(static_cast<std::size_t>(size));
      for (auto& v : values) v = static_cast<std::int64_t>(rng.next_u64() % 97);  // many repeats
      std::vector<std::int64_t> want = values;
      std::sort(want.begin(), want.end());
      sort_in_parts(values, std::less<std::int64_t>(), pool);
      CHECK(values == want);

      // Unique keys (a shuffled 0..size-1 in two parts) with a payload that follows the key.
      std::vector<std::pair<std::array<std::int64_t, 2>, double>> keyed;
      for (int i = 0; i < size; ++i) keyed.push_back({{i / 7, i % 7}, rng.uniform()});
      for (int i = size - 1; i > 0; --i) std::swap(keyed[static_cast<std::size_t>(i)], keyed[rng.next_u64() % static_cast<std::uint64_t>(i + 1)]);
      auto by_key = [](const auto& a, const auto& b) { return a.first < b.first; };
      auto want_keyed = keyed;
      std::sort(want_keyed.begin(), want_keyed.end(), by_key);
      sort_in_parts(keyed, by_key, pool);
      CHECK(keyed == want_keyed);
    }
  }
}
