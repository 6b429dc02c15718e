// LocalisationWatch: when an exploring robot is sent back to re-localise, and where to.
#include "planner/core/localisation_watch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace slam::planner {
namespace {

const RelocaliseConfig kConfig{};  // back beyond 12 cm, tied within 6 cm

TEST(LocalisationWatch, ARobotNeverTiedHasNowhereToGoBackTo) {
  LocalisationWatch w;
  EXPECT_FALSE(w.take_return(kConfig));  // nothing reported yet
  // A new trajectory segment starts barely known (2 m): it explores on.
  w.observe_position({1, 1}, kConfig);
  w.observe_uncertainty(2.83, kConfig);
  w.observe_position({4, 1}, kConfig);
  EXPECT_FALSE(w.tied(kConfig));
  EXPECT_FALSE(w.take_return(kConfig));
  // Known well at its trusted start is not tied: nothing old may be there to tie to on return.
  LocalisationWatch started;
  started.observe_position({1, 1}, kConfig);
  started.observe_uncertainty(0.05, kConfig);
  EXPECT_TRUE(started.tied(kConfig));
  started.observe_position({2, 1}, kConfig);
  started.observe_uncertainty(0.08, kConfig);
  started.observe_uncertainty(0.15, kConfig);
  EXPECT_FALSE(started.tied_place());
  EXPECT_FALSE(started.take_return(kConfig));
}

TEST(LocalisationWatch, GoesBackToTheLastPlaceItWasTiedOnceAnExcursion) {
  LocalisationWatch w;
  w.observe_position({1, 1}, kConfig);
  w.observe_uncertainty(0.08, kConfig);
  w.observe_uncertainty(0.04, kConfig);  // shrank: a tie to the old map
  EXPECT_EQ(w.tied_place(), (Vec2{1, 1}));
  w.observe_position({2, 1}, kConfig);  // still tied: the place moves along
  w.observe_uncertainty(0.08, kConfig);
  w.observe_position({3, 1}, kConfig);
  EXPECT_EQ(w.tied_place(), (Vec2{2, 1}));
  EXPECT_FALSE(w.take_return(kConfig));  // between the limits
  w.observe_uncertainty(0.13, kConfig);
  w.observe_position({5, 1}, kConfig);
  EXPECT_EQ(w.take_return(kConfig), (Vec2{2, 1}));
  // The return did not tie it: it is not sent back again until it is tied somewhere.
  w.observe_uncertainty(0.2, kConfig);
  EXPECT_FALSE(w.take_return(kConfig));
  w.observe_position({6, 2}, kConfig);
  w.observe_uncertainty(0.05, kConfig);
  EXPECT_TRUE(w.tied(kConfig));
  EXPECT_EQ(w.tied_place(), (Vec2{6, 2}));
  w.observe_uncertainty(0.15, kConfig);
  EXPECT_EQ(w.take_return(kConfig), (Vec2{6, 2}));
}

TEST(LocalisationWatch, OffAtZeroAndDeafToNonsense) {
  LocalisationWatch w;
  w.observe_position({1, 1}, kConfig);
  w.observe_uncertainty(0.07, kConfig);
  w.observe_uncertainty(0.03, kConfig);
  w.observe_uncertainty(std::numeric_limits<double>::quiet_NaN(), kConfig);
  w.observe_uncertainty(-1.0, kConfig);
  w.observe_position({std::numeric_limits<double>::infinity(), 0}, kConfig);
  EXPECT_EQ(w.sigma_m(), 0.03);
  EXPECT_EQ(w.tied_place(), (Vec2{1, 1}));
  w.observe_uncertainty(0.5, kConfig);
  RelocaliseConfig off = kConfig;
  off.return_sigma_m = 0.0;
  EXPECT_FALSE(w.take_return(off));
  EXPECT_TRUE(w.take_return(kConfig));
}

TEST(LocalisationWatch, ValidatesItsLimits) {
  EXPECT_TRUE(validate(RelocaliseConfig{}));
  EXPECT_TRUE(validate(RelocaliseConfig{0.0, 0.06}));  // off
  EXPECT_FALSE(validate(RelocaliseConfig{0.05, 0.06}));
  EXPECT_FALSE(validate(RelocaliseConfig{-0.1, 0.06}));
  EXPECT_FALSE(validate(RelocaliseConfig{0.12, 0.0}));
  EXPECT_FALSE(validate(RelocaliseConfig{std::nan(""), 0.06}));
}

}  // namespace
}  // namespace slam::planner
