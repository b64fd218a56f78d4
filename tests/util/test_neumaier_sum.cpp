// util/neumaier_sum.h: the compensated sum keeps what a plain sum loses to cancellation, and
// adds the terms in the caller's order.
#include <doctest/doctest.h>

#include "util/neumaier_sum.h"
#include "util/quote_bytes.h"

using namespace offsetopt;

TEST_CASE("NeumaierSum: a small term survives the cancellation of two large ones") {
  NeumaierSum sum;
  for (const double term : {1e100, 1.0, -1e100}) sum.add(term);
  CHECK(sum.value() == 1.0);
  NeumaierSum tenths;
  for (int i = 0; i < 10; ++i) tenths.add(0.1);
  CHECK(tenths.value() == 1.0);
}

TEST_CASE("quote_bytes: printable ASCII kept, the rest as \\xNN, cut at 40 characters") {
  CHECK(quote_bytes("abc") == "abc");
  CHECK(quote_bytes(std::string_view("a\0'\\", 4)) == "a\\x00\\x27\\x5c");
  CHECK(quote_bytes(std::string(50, 'x')) == std::string(40, 'x') + "...");
}
