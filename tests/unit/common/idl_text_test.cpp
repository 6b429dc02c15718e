// The embedded IDL files and the one-text schemas made from them.
#include "common/core/idl_text.hpp"

#include <gtest/gtest.h>

namespace slam {
namespace {

TEST(IdlText, EmbedsEveryIdlFile) {
  std::vector<std::string_view> names;
  for (const IdlFile& f : idl_files()) names.push_back(f.name);
  for (const char* expected : {"common.idl", "map.idl", "robot.idl", "system.idl"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
}

TEST(IdlText, SchemaHoldsTheTypeAfterItsIncludesWithoutIncludeLines) {
  auto schema = omgidl_schema("slam::GridSnapshot");
  ASSERT_TRUE(schema) << schema.message();
  const size_t point = schema->find("struct Point2");
  const size_t snapshot = schema->find("struct GridSnapshot");
  ASSERT_NE(point, std::string::npos);
  ASSERT_NE(snapshot, std::string::npos);
  EXPECT_LT(point, snapshot);
  EXPECT_EQ(schema->find("#include"), std::string::npos);
  EXPECT_EQ(schema->find("struct Point2", point + 1), std::string::npos);  // common.idl once
}

TEST(IdlText, SchemaOfATypeWithoutIncludesIsItsFile) {
  auto schema = omgidl_schema("slam::Heartbeat");
  ASSERT_TRUE(schema) << schema.message();
  EXPECT_NE(schema->find("struct Heartbeat"), std::string::npos);
  EXPECT_EQ(schema->find("struct Point2"), std::string::npos);
}

TEST(IdlText, RefusesAnUnknownType) {
  auto schema = omgidl_schema("slam::NoSuchType");
  ASSERT_FALSE(schema);
  EXPECT_NE(schema.message().find("slam::NoSuchType"), std::string::npos);
}

}  // namespace
}  // namespace slam
