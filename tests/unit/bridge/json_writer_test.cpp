#include "bridge/core/json_writer.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>

namespace slam::bridge {
namespace {

TEST(JsonWriter, WritesNestedContainersWithCommas) {
  std::string out;
  JsonWriter w(out);
  w.begin_object().key("a").value(1).key("b").begin_array().value(true).value("x").end_array();
  w.empty_array("c").key("d").begin_object().end_object().end_object();
  EXPECT_EQ(out, R"({"a":1,"b":[true,"x"],"c":[],"d":{}})");
}

TEST(JsonWriter, EscapesStringsAndReadsBack) {
  std::string out;
  JsonWriter w(out);
  const std::string tricky = "quote\" back\\ nl\n ctl\x01 é";
  w.begin_object().key("s").value(tricky).end_object();
  EXPECT_EQ(nlohmann::json::parse(out)["s"], tricky);
}

TEST(JsonWriter, DoublesRoundTripAndNonFiniteBecomesZero) {
  std::string out;
  JsonWriter w(out);
  w.begin_array().value(0.1).value(-2.5e-7).value(std::numeric_limits<double>::quiet_NaN()).end_array();
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j[0].get<double>(), 0.1);
  EXPECT_EQ(j[1].get<double>(), -2.5e-7);
  EXPECT_EQ(j[2].get<double>(), 0.0);
}

TEST(JsonWriter, WritesBase64Strings) {
  std::string out;
  JsonWriter w(out);
  const uint8_t bytes[] = {'f', 'o', 'o'};
  w.begin_object().key("data").base64_value(bytes).end_object();
  EXPECT_EQ(out, R"({"data":"Zm9v"})");
}

}  // namespace
}  // namespace slam::bridge
