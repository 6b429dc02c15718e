// guarded_callback: results pass through, every exception is caught and replaced by the safe value.
#include "common/core/guarded_callback.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace slam {
namespace {

TEST(GuardedCallback, ReturnsTheCallbackResult) {
  EXPECT_EQ(guarded_callback("test", -1, [] { return 7; }), 7);
}

TEST(GuardedCallback, ReturnsTheSafeValueWhenAStandardExceptionIsThrown) {
  EXPECT_EQ(guarded_callback("test", -1, []() -> int { throw std::runtime_error("boom"); }), -1);
}

TEST(GuardedCallback, ReturnsTheSafeValueWhenANonStandardExceptionIsThrown) {
  EXPECT_EQ(guarded_callback("test", 0, []() -> int { throw 42; }), 0);
}

TEST(GuardedCallback, RunsAVoidCallbackAndSwallowsWhatItThrows) {
  int calls = 0;
  guarded_callback("test", [&] { ++calls; });
  EXPECT_EQ(calls, 1);
  EXPECT_NO_THROW(guarded_callback("test", [&] {
    ++calls;
    throw std::logic_error("boom");
  }));
  EXPECT_EQ(calls, 2);
}

TEST(GuardedCallback, IsNoexcept) {
  auto throws = []() -> int { throw 1; };
  static_assert(noexcept(guarded_callback("test", 0, throws)));
  static_assert(noexcept(guarded_callback("test", [] {})));
  SUCCEED();
}

}  // namespace
}  // namespace slam
