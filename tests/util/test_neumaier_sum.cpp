// util/neumaier_sum.h: the compensated sum keeps what a plain sum loses to cancellation, and
// adds the terms in the caller's order.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "util/neumaier_pair.h"
#include "util/neumaier_sum.h"
#include "util/quote_bytes.h"
#include "util/rng.h"

using namespace offsetopt;

TEST_CASE("NeumaierSum: a small term survives the cancellation of two large ones") {
  NeumaierSum sum;
  for (const double term : {1e100, 1.0, -1e100}) sum.add(term);
  CHECK(sum.value() == 1.0);
  NeumaierSum tenths;
  for (int i = 0; i < 10; ++i) tenths.add(0.1);
  CHECK(tenths.value() == 1.0);
}

TEST_CASE("NeumaierPair: each lane is bit for bit a NeumaierSum fed the same terms") {
  auto bits = [](double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  // Terms across magnitudes and signs (so both branches of |sum| >= |term| are taken, in both
  // lanes independently), cancellations, signed zeros; then an infinity and a NaN in one lane.
  Rng rng(21);
  std::vector<double> first, second;
  for (int i = 0; i < 2000; ++i) {
    first.push_back(rng.uniform(-1.0, 1.0) * std::pow(10.0, rng.uniform(-12.0, 12.0)));
    second.push_back(i % 7 == 0 ? -first.back() : rng.uniform(-1.0, 1.0) * std::pow(10.0, rng.uniform(-3.0, 3.0)));
  }
  for (const double special : {0.0, -0.0, 1e300, -1e300, 1e-310}) {
    first.push_back(special);
    second.push_back(-special);
  }
  NeumaierPair pair;
  NeumaierSum lane0, lane1;
  for (std::size_t i = 0; i < first.size(); ++i) {
    pair.add(first[i], second[i]);
    lane0.add(first[i]);
    lane1.add(second[i]);
    if (i % 97 == 0) {
      REQUIRE(bits(pair.value(0)) == bits(lane0.value()));
      REQUIRE(bits(pair.value(1)) == bits(lane1.value()));
    }
  }
  CHECK(bits(pair.value(0)) == bits(lane0.value()));
  CHECK(bits(pair.value(1)) == bits(lane1.value()));
  // Only negative zeros: the sum stays -0 in that lane, as NeumaierSum's does.
  NeumaierPair zeros;
  NeumaierSum negative_zeros;
  for (int i = 0; i < 3; ++i) {
    zeros.add(-0.0, 0.0);
    negative_zeros.add(-0.0);
  }
  CHECK(bits(zeros.value(0)) == bits(negative_zeros.value()));
  // Non-finite terms: the lane goes non-finite exactly as a NeumaierSum does; the other lane is untouched.
  NeumaierPair odd;
  NeumaierSum odd0, odd1;
  for (const double term : {1.0, std::numeric_limits<double>::infinity(), 2.0}) {
    odd.add(term, std::numeric_limits<double>::quiet_NaN());
    odd0.add(term);
    odd1.add(std::numeric_limits<double>::quiet_NaN());
  }
  CHECK(bits(odd.value(0)) == bits(odd0.value()));
  CHECK(std::isnan(odd.value(1)) == std::isnan(odd1.value()));
}

TEST_CASE("quote_bytes: printable ASCII kept, the rest as \\xNN, cut at 40 characters") {
  CHECK(quote_bytes("abc") == "abc");
  CHECK(quote_bytes(std::string_view("a\0'\\", 4)) == "a\\x00\\x27\\x5c");
  CHECK(quote_bytes(std::string(50, 'x')) == std::string(40, 'x') + "...");
}
