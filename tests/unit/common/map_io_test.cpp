// ROS map_server PGM + YAML: round trip, row order, P2 and 16-bit input, negate/thresholds,
// relative image paths, and bad files whose errors name the file and the problem.
#include "common/core/map_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace slam {
namespace {

class MapIo : public ::testing::Test {
 protected:
  void write(const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
  }
  testkit::TempDir dir_{"map-io"};
};

std::span<const uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

MapImage sample() {
  MapImage m;
  m.width = 3;
  m.height = 2;
  m.resolution = 0.05;
  m.origin_x = -1.25;
  m.origin_y = 2.5;
  m.origin_yaw = 0.1;
  m.cells = {kMapFree,     kMapOccupied, kMapUnknown,  // bottom row
             kMapOccupied, kMapUnknown,  kMapFree};
  return m;
}

TEST_F(MapIo, RoundTrip) {
  const MapImage m = sample();
  ASSERT_TRUE(write_ros_map(dir_ / "room.yaml", m).is_ok());
  ASSERT_TRUE(std::filesystem::exists(dir_ / "room.pgm"));
  auto back = read_ros_map(dir_ / "room.yaml");
  ASSERT_TRUE(back.is_ok()) << back.message();
  EXPECT_EQ(back->width, 3u);
  EXPECT_EQ(back->height, 2u);
  EXPECT_DOUBLE_EQ(back->resolution, 0.05);
  EXPECT_DOUBLE_EQ(back->origin_x, -1.25);
  EXPECT_DOUBLE_EQ(back->origin_y, 2.5);
  EXPECT_DOUBLE_EQ(back->origin_yaw, 0.1);
  EXPECT_EQ(back->cells, m.cells);
}

TEST_F(MapIo, PgmFirstRowIsTheTopOfTheMap) {
  const std::vector<uint8_t> pgm = encode_pgm(sample());
  const std::string header = "P5\n# slam-mapper\n3 2\n255\n";
  ASSERT_EQ(pgm.size(), header.size() + 6);
  // Top row (map row 1) first: occupied, unknown, free.
  EXPECT_EQ(std::vector<uint8_t>(pgm.begin() + static_cast<long>(header.size()), pgm.end()),
            (std::vector<uint8_t>{0, 205, 254, 254, 0, 205}));
  const std::string yaml = encode_map_yaml(sample(), "room.pgm");
  EXPECT_NE(yaml.find("mode: trinary"), std::string::npos);
  EXPECT_NE(yaml.find("image: 'room.pgm'"), std::string::npos);
}

TEST_F(MapIo, AcceptsAsciiSixteenBitCommentsAndRelativeImage) {
  std::filesystem::create_directories(dir_ / "img");
  write("img/a.pgm", "P2\n# made by hand\n2 2\n# max\n65535\n0 65535\n 52685 65535\n");
  write("a.yaml",
        "image: img/a.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
        "free_thresh: 0.196\n");
  auto m = read_ros_map(dir_ / "a.yaml");
  ASSERT_TRUE(m.is_ok()) << m.message();
  EXPECT_EQ(m->cells, (std::vector<uint8_t>{kMapUnknown, kMapFree, kMapOccupied, kMapFree}));
}

TEST_F(MapIo, NegateAndScaleMode) {
  MapYaml y;
  y.resolution = 1.0;
  y.negate = true;
  y.mode = "scale";
  PgmImage p{2, 1, {0, 255}};
  auto m = decode_map(y, p, "x");
  ASSERT_TRUE(m.is_ok());
  EXPECT_EQ(m->cells, (std::vector<uint8_t>{kMapFree, kMapOccupied}));
}

TEST_F(MapIo, BadFilesNameTheFileAndProblem) {
  const auto expect_error = [&](const std::string& yaml, const std::string& pgm, const std::string& needle) {
    write("bad.yaml", yaml);
    write("bad.pgm", pgm);
    auto m = read_ros_map(dir_ / "bad.yaml");
    ASSERT_FALSE(m.is_ok()) << needle;
    EXPECT_NE(m.message().find("bad."), std::string::npos) << m.message();
    EXPECT_NE(m.message().find(needle), std::string::npos) << m.message();
  };
  const std::string good_pgm = "P5 1 1 255\n\xfe";
  const std::string good_yaml = "image: bad.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  expect_error("image: bad.pgm\nresolution: 0\norigin: [0, 0, 0]\n", good_pgm, "resolution");
  expect_error("image: bad.pgm\nresolution: -1\norigin: [0, 0, 0]\n", good_pgm, "resolution");
  expect_error("resolution: 0.05\norigin: [0, 0, 0]\n", good_pgm, "image");
  expect_error("image: bad.pgm\nresolution: 0.05\norigin: [0, 0]\n", good_pgm, "origin");
  expect_error("image: bad.pgm\nresolution: abc\norigin: [0, 0, 0]\n", good_pgm, "invalid YAML");
  expect_error("image: bad.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nmode: raw\n", good_pgm, "raw");
  expect_error("image: bad.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nfree_thresh: 0.9\n", good_pgm,
               "free_thresh");
  expect_error("[1, 2", good_pgm, "invalid YAML");
  expect_error(good_yaml, "P6 1 1 255\n\x01\x02\x03", "P5 or P2");
  expect_error(good_yaml, "P5 4 4 255\n\x01\x02", "truncated");
  expect_error(good_yaml, "P5 0 4 255\n", "zero width");
  expect_error(good_yaml, "P5 100000 100000 255\n", "too large");
  expect_error(good_yaml, "P2 2 1 10\n3 11\n", "exceeds maxval");
  expect_error(good_yaml, "P5 1 1 70000\n\x00\x00", "maxval");
  std::filesystem::remove(dir_ / "bad.pgm");
  auto missing = read_ros_map(dir_ / "bad.yaml");
  ASSERT_FALSE(missing.is_ok());
  EXPECT_NE(missing.message().find("cannot open"), std::string::npos) << missing.message();
  auto no_yaml = read_ros_map(dir_ / "nothing.yaml");
  ASSERT_FALSE(no_yaml.is_ok());
  EXPECT_NE(no_yaml.message().find("nothing.yaml"), std::string::npos);
}

TEST_F(MapIo, WriteRejectsInconsistentMapsAndUnwritablePaths) {
  MapImage m = sample();
  m.cells.pop_back();
  EXPECT_FALSE(write_ros_map(dir_ / "x.yaml", m).is_ok());
  auto s = write_ros_map(dir_ / "missing_dir" / "x.yaml", sample());
  ASSERT_FALSE(s.is_ok());
  EXPECT_NE(s.message().find("x.pgm"), std::string::npos) << s.message();
  EXPECT_FALSE(parse_pgm(bytes_of(""), "e").is_ok());
}

}  // namespace
}  // namespace slam
