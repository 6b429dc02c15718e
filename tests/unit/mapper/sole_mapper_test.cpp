#include "mapper/core/sole_mapper.hpp"

#include <gtest/gtest.h>

namespace slam::mapper {
namespace {

MapperPeer peer(const std::string& id, bool holds) {
  return MapperPeer{id, "h", 42, holds};
}

TEST(SoleMapper, AloneItStays) {
  EXPECT_FALSE(yield_to("h:2", {}));
  EXPECT_FALSE(yield_to("h:2", {peer("h:2", false)}));  // its own heartbeat
}

TEST(SoleMapper, YieldsToOneThatHoldsTheDomainWhateverTheIds) {
  const auto y = yield_to("a:1", {peer("z:9", true)});
  ASSERT_TRUE(y);
  EXPECT_EQ(y->instance_id, "z:9");
}

TEST(SoleMapper, OfTwoStartingTogetherExactlyTheLowerIdStays) {
  const std::vector<MapperPeer> both{peer("h:100", false), peer("h:200", false)};
  EXPECT_FALSE(yield_to("h:100", both));
  const auto y = yield_to("h:200", both);
  ASSERT_TRUE(y);
  EXPECT_EQ(y->instance_id, "h:100");
}

TEST(SoleMapper, RefusalNamesTheOtherMapper) {
  const std::string line = refusal(MapperPeer{"box:77", "box", 77, true}, 5);
  EXPECT_NE(line.find("host box, pid 77"), std::string::npos) << line;
  EXPECT_NE(line.find("DDS domain 5"), std::string::npos) << line;
  EXPECT_EQ(line.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace slam::mapper
