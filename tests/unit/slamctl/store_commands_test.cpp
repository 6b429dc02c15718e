// slamctl store stats: the report names what the store keeps.
#include "slamctl/store_commands.hpp"

#include <gtest/gtest.h>

namespace slam::ctl {
namespace {

TEST(StoreStats, TheReportSaysRowsKeyframesCompactedTilesSizeAndTheOldestRawObservation) {
  mapper::StoreStats s;
  s.rows = 1234;
  s.keyframes = 56;
  s.raw_keyframes = 7;
  s.compacted_tiles = 89;
  s.compacted_through = 4000;
  s.bytes = 3 * 1024 * 1024;
  s.file_bytes = 4 * 1024 * 1024;
  s.oldest_stamp_ns = 1'800'000'000'000'000'000;  // 2027-01-15 08:00:00 UTC
  s.newest_stamp_ns = s.oldest_stamp_ns + 7'200'000'000'000;
  const std::string text = describe_store("map.db", s);
  EXPECT_NE(text.find("raw observations     1234"), std::string::npos) << text;
  EXPECT_NE(text.find("56 (7 with raw observations)"), std::string::npos) << text;
  EXPECT_NE(text.find("compacted tiles      89"), std::string::npos) << text;
  EXPECT_NE(text.find("up to row 4000"), std::string::npos) << text;
  EXPECT_NE(text.find("3.0 MB in use, 4.0 MB file"), std::string::npos) << text;
  EXPECT_NE(text.find("2027-01-15 08:00:00 UTC (2.0 h before the newest)"), std::string::npos) << text;
  s.rows = 0;
  EXPECT_NE(describe_store("map.db", s).find("oldest raw           none"), std::string::npos);
}

}  // namespace
}  // namespace slam::ctl
