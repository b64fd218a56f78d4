// Disjoint sets over the elements 0 .. n-1 (union-find with path halving). The smaller root wins
// every union, so each set's root is its smallest element whatever the order of the unions: the
// numbering of shells, fans and facets built on it is deterministic.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace offsetopt {

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n = 0) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i] = static_cast<std::uint32_t>(i);
  }

  // The smallest element of x's set.
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b) parent_[b] = a;
    else parent_[a] = b;
  }

  std::size_t size() const { return parent_.size(); }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace offsetopt
