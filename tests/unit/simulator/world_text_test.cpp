// Java world text format: every legacy sample loads, and malformed input is rejected with the
// file, token number and problem in the message.
#include "simulator/core/world_text.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "temp_dir.hpp"

namespace slam::sim {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kSamples = std::filesystem::path(SIM_TEST_WORLDS) / "ssnar-java";

TEST(WorldText, EverySampleFileLoads) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSamples)) {
    if (entry.path().extension() != ".txt") continue;
    ++files;
    const auto world = load_java_world(entry.path());
    ASSERT_TRUE(world) << world.message();
    EXPECT_EQ(world->name(), entry.path().stem().string());
    EXPECT_GT(world->walls().size(), 4u) << entry.path();
  }
  EXPECT_EQ(files, 5);
}

TEST(WorldText, SampleGeometryIsInMetres) {
  // a_office.txt: "104:141" then two walls; no trailing newline.
  const auto world = load_java_world(kSamples / "a_office.txt");
  ASSERT_TRUE(world) << world.message();
  EXPECT_DOUBLE_EQ(world->bounds().max.x, 1.04);
  EXPECT_DOUBLE_EQ(world->bounds().max.y, 1.41);
  ASSERT_EQ(world->walls().size(), 6u);  // four implied borders first
  const Segment& w = world->walls()[4];
  EXPECT_DOUBLE_EQ(w.a.x, 0.0);
  EXPECT_DOUBLE_EQ(w.a.y, 0.41);
  EXPECT_DOUBLE_EQ(w.b.x, 0.55);
  EXPECT_DOUBLE_EQ(w.b.y, 0.41);
}

TEST(WorldText, BigMapHasEveryWall) {
  const auto world = load_java_world(kSamples / "k_big_map.txt");
  ASSERT_TRUE(world) << world.message();
  EXPECT_EQ(world->walls().size(), 4u + 7u);
  EXPECT_DOUBLE_EQ(world->bounds().width(), 6.0);
}

TEST(WorldText, AcceptsAnyWhitespaceAndDecimals) {
  const auto world = parse_java_world("  200:100\r\n\t10.5,20:30,40   50,50:50,90\n\n", "inline");
  ASSERT_TRUE(world) << world.message();
  EXPECT_EQ(world->walls().size(), 6u);
  EXPECT_DOUBLE_EQ(world->walls()[4].a.x, 0.105);
}

struct Malformed {
  const char* text;
  const char* expected;
};

class WorldTextMalformed : public ::testing::TestWithParam<Malformed> {};

TEST_P(WorldTextMalformed, IsRejectedWithReason) {
  const auto world = parse_java_world(GetParam().text, "bad.txt");
  ASSERT_FALSE(world);
  EXPECT_THAT(world.message(), HasSubstr("bad.txt"));
  EXPECT_THAT(world.message(), HasSubstr(GetParam().expected));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, WorldTextMalformed,
    ::testing::Values(Malformed{"", "empty world file"}, Malformed{" \n\t ", "empty world file"},
                      Malformed{"100", "token 1 '100': expected the world size W:H"},
                      Malformed{"100:x", "token 1"}, Malformed{"100:50:20", "token 1"},
                      Malformed{"0:100", "must be positive"}, Malformed{"-5:100", "must be positive"},
                      Malformed{"inf:100", "token 1"}, Malformed{"nan:100", "token 1"},
                      Malformed{"2000000:100", "larger than"},
                      Malformed{"100:100 10,10:20", "token 2 '10,10:20': expected a wall x1,y1:x2,y2"},
                      Malformed{"100:100 10,10:20,20 1,2,3:4,5", "token 3"},
                      Malformed{"100:100 10,10:20,20 10,10:20,20:30,30", "token 3"},
                      Malformed{"100:100 10,10;20,20", "token 2"},
                      Malformed{"100:100 10,10:20,2e", "token 2"},
                      Malformed{"100:100 10,10:200,20", "token 2 '10,10:200,20': wall end outside the world"},
                      Malformed{"100:100 -1,10:20,20", "outside the world"},
                      Malformed{"100:100\n10,10:10,10", "token 2 '10,10:10,10': wall has zero length"}));

TEST(WorldText, MessageShowsUnprintableBytesSafely) {
  const auto world = parse_java_world(std::string_view("100:100 \x01\x02", 10), "bin");
  ASSERT_FALSE(world);
  EXPECT_THAT(world.message(), HasSubstr("token 2 '?"
                                         "?'"));
}

TEST(WorldText, MissingFileNamesThePath) {
  const auto world = load_java_world("/nonexistent/world.txt");
  ASSERT_FALSE(world);
  EXPECT_THAT(world.message(), HasSubstr("/nonexistent/world.txt"));
}

TEST(WorldText, FileErrorsNameTheFile) {
  const testkit::TempDir dir("world-text");
  const auto path = dir / "broken_world.txt";
  std::ofstream(path) << "300:300\n0,0:100,100\n0,0:100\n";
  const auto world = load_java_world(path);
  ASSERT_FALSE(world);
  EXPECT_THAT(world.message(), HasSubstr(path.string() + ": token 3"));
}

}  // namespace
}  // namespace slam::sim
