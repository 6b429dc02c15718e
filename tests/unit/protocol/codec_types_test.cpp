// Limits validation (a configuration error names its key) and reuse of decoded structs.
#include "protocol/codec_types.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace slam::protocol {
namespace {

TEST(CodecLimits, DefaultsAreValid) {
  EXPECT_TRUE(validate(CodecLimits{}).is_ok());
}

TEST(CodecLimits, BadValuesNameTheirKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    CodecLimits limits;
    const char* key;
  };
  CodecLimits upm_nan, upm_zero, upm_neg, no_points, tiny_payload, coord_inf, coord_zero, angle_nan;
  upm_nan.units_per_meter = nan;
  upm_zero.units_per_meter = 0.0;
  upm_neg.units_per_meter = -100.0;
  no_points.max_points = 0;
  tiny_payload.max_payload_bytes = 3;
  coord_inf.max_abs_coordinate_m = inf;
  coord_zero.max_abs_coordinate_m = 0.0;
  angle_nan.max_abs_angle_rad = nan;
  for (const Case& c : {Case{upm_nan, "units_per_meter"}, Case{upm_zero, "units_per_meter"},
                        Case{upm_neg, "units_per_meter"}, Case{no_points, "max_points"},
                        Case{tiny_payload, "max_payload_bytes"}, Case{coord_inf, "max_abs_coordinate_m"},
                        Case{coord_zero, "max_abs_coordinate_m"}, Case{angle_nan, "max_abs_angle_rad"}}) {
    const Status status = validate(c.limits);
    EXPECT_FALSE(status.is_ok()) << c.key;
    EXPECT_NE(status.message().find(c.key), std::string::npos) << status.message();
  }
}

TEST(DecodedObservation, ClearKeepsCapacity) {
  DecodedObservation obs;
  obs.x = 1.0;
  obs.has_pose = obs.has_heading = true;
  obs.hits.resize(100);
  obs.misses.resize(50);
  obs.clear();
  EXPECT_EQ(obs.x, 0.0);
  EXPECT_FALSE(obs.has_pose);
  EXPECT_FALSE(obs.has_heading);
  EXPECT_TRUE(obs.hits.empty());
  EXPECT_TRUE(obs.misses.empty());
  EXPECT_GE(obs.hits.capacity(), 100u);
  EXPECT_GE(obs.misses.capacity(), 50u);
}

TEST(DecodedStatus, ClearResetsToUnknown) {
  DecodedStatus status;
  status.battery = 0.5f;
  status.state = "exploring";
  status.offline = true;
  status.clear();
  EXPECT_LT(status.battery, 0.0f);
  EXPECT_TRUE(status.state.empty());
  EXPECT_FALSE(status.offline);
}

}  // namespace
}  // namespace slam::protocol
