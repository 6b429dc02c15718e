// Backoff: doubling, ceiling, reset.
#include "gateway/backoff.hpp"

#include <gtest/gtest.h>

namespace slam::gateway {
namespace {

using std::chrono::milliseconds;

TEST(Backoff, DoublesUpToTheCeilingAndResets) {
  Backoff b(milliseconds(250), milliseconds(1500));
  EXPECT_EQ(b.next(), milliseconds(250));
  EXPECT_EQ(b.next(), milliseconds(500));
  EXPECT_EQ(b.next(), milliseconds(1000));
  EXPECT_EQ(b.next(), milliseconds(1500));
  EXPECT_EQ(b.next(), milliseconds(1500));
  EXPECT_EQ(b.failures(), 5u);
  b.reset();
  EXPECT_EQ(b.failures(), 0u);
  EXPECT_EQ(b.next(), milliseconds(250));
}

TEST(Backoff, ACeilingBelowTheStartIsTheStart) {
  Backoff b(milliseconds(100), milliseconds(10));
  EXPECT_EQ(b.next(), milliseconds(100));
  EXPECT_EQ(b.next(), milliseconds(100));
}

}  // namespace
}  // namespace slam::gateway
