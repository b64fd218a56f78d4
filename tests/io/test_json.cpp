// The report writer: shortest round-trip doubles, stable key order, parse(dump(x)) == x.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "io/json.h"
#include "util/format_double.h"
#include "util/rng.h"

using namespace offsetopt;

TEST_CASE("doubles round-trip bit-exactly through their shortest text") {
  Rng rng(42);
  for (int i = 0; i < 10000; ++i) {
    const double x = (rng.uniform() - 0.5) * std::ldexp(1.0, static_cast<int>(rng.below(200)) - 100);
    const std::string text = format_double(x);
    CHECK(std::strtod(text.c_str(), nullptr) == x);
  }
  CHECK(format_double(0.1) == "0.1");
  CHECK(format_double(1e300) == "1e+300");
  CHECK(format_double(-0.0) == "-0");
}

TEST_CASE("dump keeps insertion order, maps non-finite to null and parses back") {
  Json j = Json::object();
  j["zeta"] = 1;
  j["alpha"] = 0.25;
  j["nan"] = std::numeric_limits<double>::quiet_NaN();
  j["list"] = Json::array_of({1.5, -2.0, 3e-20});
  j["nested"]["name"] = "quote\" and \\ and \n";
  j["nested"]["flag"] = true;
  const std::string compact = j.dump(-1);
  CHECK(compact ==
        "{\"zeta\":1,\"alpha\":0.25,\"nan\":null,\"list\":[1.5,-2,3e-20],"
        "\"nested\":{\"name\":\"quote\\\" and \\\\ and \\n\",\"flag\":true}}");
  const Json back = Json::parse(j.dump(2));
  CHECK(back.dump(-1) == compact);
  CHECK(back.at("list").at(2).as_number() == 3e-20);
  CHECK(back.at("nested").at("name").as_string() == "quote\" and \\ and \n");
  CHECK_THROWS(Json::parse("{\"a\":1,}"));
  CHECK_THROWS(Json::parse("[1 2]"));
}

TEST_CASE("compact dump of arrays of objects stays on one line") {
  Json j = Json::array();
  j.push_back(Json::object());
  j.push_back(Json::object());
  j.elements();
  Json inner = Json::object();
  inner["a"] = 1;
  j.push_back(inner);
  CHECK(j.dump(-1) == "[{},{},{\"a\":1}]");
  CHECK(Json::parse(j.dump(2)).dump(-1) == j.dump(-1));
}
