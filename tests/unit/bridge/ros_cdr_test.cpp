// nav_msgs/msg/OccupancyGrid as plain little-endian CDR, read back field by field at the offsets
// CDR's alignment rules give, and its ros2msg definition.
#include "bridge/core/ros_cdr.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace slam::bridge {
namespace {

template <class T>
T at(const std::string& bytes, size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

TEST(RosCdr, OccupancyGridIsPlainLittleEndianCdr) {
  OccupancyGridOut grid;
  grid.stamp = RosTime{12, 345};
  grid.resolution = 0.25f;
  grid.width = 3;
  grid.height = 1;
  grid.origin = {-2.0, 3.5};
  grid.data = {-1, 0, 100};
  const std::string bytes = occupancy_grid_cdr(grid);
  // Offsets below count from the encapsulation header's end (4 bytes: CDR_LE, no options).
  ASSERT_EQ(bytes.substr(0, 4), std::string("\x00\x01\x00\x00", 4));
  const auto body = [&](size_t offset) { return offset + 4; };
  EXPECT_EQ(at<int32_t>(bytes, body(0)), 12);     // header.stamp.sec
  EXPECT_EQ(at<uint32_t>(bytes, body(4)), 345u);  // header.stamp.nanosec
  EXPECT_EQ(at<uint32_t>(bytes, body(8)), 4u);    // frame_id length with its NUL
  EXPECT_EQ(std::string(bytes.data() + body(12), 4), std::string("map\0", 4));
  EXPECT_EQ(at<int32_t>(bytes, body(16)), 12);  // info.map_load_time
  EXPECT_EQ(at<uint32_t>(bytes, body(20)), 345u);
  EXPECT_EQ(at<float>(bytes, body(24)), 0.25f);  // resolution
  EXPECT_EQ(at<uint32_t>(bytes, body(28)), 3u);  // width
  EXPECT_EQ(at<uint32_t>(bytes, body(32)), 1u);  // height
  // origin: 7 doubles aligned to 8 (36 -> 40)
  EXPECT_EQ(at<double>(bytes, body(40)), -2.0);
  EXPECT_EQ(at<double>(bytes, body(48)), 3.5);
  EXPECT_EQ(at<double>(bytes, body(56)), 0.0);
  EXPECT_EQ(at<double>(bytes, body(88)), 1.0);   // orientation.w
  EXPECT_EQ(at<uint32_t>(bytes, body(96)), 3u);  // data count
  EXPECT_EQ(at<int8_t>(bytes, body(100)), -1);
  EXPECT_EQ(at<int8_t>(bytes, body(101)), 0);
  EXPECT_EQ(at<int8_t>(bytes, body(102)), 100);
  EXPECT_EQ(bytes.size(), body(103));
}

TEST(RosCdr, DefinitionListsTheMessageThenEachDependencyOnce) {
  const std::string text = kOccupancyGridDefinition;
  EXPECT_EQ(text.rfind("std_msgs/Header header\nMapMetaData info\nint8[] data\n", 0), 0u);
  for (const char* dependency : {"std_msgs/Header", "builtin_interfaces/Time", "nav_msgs/MapMetaData",
                                 "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion"}) {
    const std::string header = std::string("\nMSG: ") + dependency + "\n";
    const size_t first = text.find(header);
    EXPECT_NE(first, std::string::npos) << dependency;
    EXPECT_EQ(text.find(header, first + 1), std::string::npos) << dependency;
  }
}

}  // namespace
}  // namespace slam::bridge
