#include "common/core/reply_cache.hpp"

#include <gtest/gtest.h>

#include <string>

namespace slam {
namespace {

TEST(ReplyCache, NewIdIsExecuted) {
  ReplyCache<std::string> cache;
  EXPECT_EQ(cache.admit(7).admission, Admission::Execute);
}

TEST(ReplyCache, RepeatWhileExecutingIsNotExecutedAgain) {
  ReplyCache<std::string> cache;
  ASSERT_EQ(cache.admit(7).admission, Admission::Execute);
  const auto repeat = cache.admit(7);
  EXPECT_EQ(repeat.admission, Admission::Executing);
  EXPECT_FALSE(repeat.reply.has_value());
}

TEST(ReplyCache, RepeatAfterTheReplyGetsTheSameReply) {
  ReplyCache<std::string> cache;
  ASSERT_EQ(cache.admit(7).admission, Admission::Execute);
  cache.complete(7, "obstructed");
  for (int i = 0; i < 3; ++i) {
    const auto repeat = cache.admit(7);
    EXPECT_EQ(repeat.admission, Admission::Answered);
    EXPECT_EQ(repeat.reply, "obstructed");
  }
}

TEST(ReplyCache, IdZeroIsAlwaysExecutedAndNeverKept) {
  ReplyCache<std::string> cache;
  EXPECT_EQ(cache.admit(0).admission, Admission::Execute);
  cache.complete(0, "x");
  EXPECT_EQ(cache.admit(0).admission, Admission::Execute);
  EXPECT_EQ(cache.size(), 0u);
}

TEST(ReplyCache, KeepsOnlyTheLastIds) {
  ReplyCache<std::string> cache(3);
  for (uint64_t id = 1; id <= 4; ++id) {
    ASSERT_EQ(cache.admit(id).admission, Admission::Execute);
    cache.complete(id, std::to_string(id));
  }
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_EQ(cache.admit(4).reply, "4");
  EXPECT_EQ(cache.admit(2).reply, "2");
  EXPECT_EQ(cache.admit(1).admission, Admission::Execute);  // evicted: the oldest went first
}

TEST(ReplyCache, ReplyWithoutAdmissionIsKept) {
  ReplyCache<std::string> cache;
  cache.complete(9, "done");
  EXPECT_EQ(cache.admit(9).reply, "done");
}

}  // namespace
}  // namespace slam
