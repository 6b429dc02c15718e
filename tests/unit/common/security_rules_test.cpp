// compose/security/permissions.rules against the topic table: every topic a service can create has
// a rule, or DDS Security refuses its reader or writer and the service stops at start.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/fastdds/any_topic.hpp"

namespace slam::dds {
namespace {

// The topic names (or name prefixes ending in *) of the rules file's `topic` lines.
std::vector<std::string> rule_topics() {
  std::ifstream in(SLAM_SOURCE_DIR "/compose/security/permissions.rules");
  std::vector<std::string> out;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword, name;
    if (words >> keyword >> name && keyword == "topic") out.push_back(name);
  }
  return out;
}

bool covered(const std::string& topic, const std::vector<std::string>& rules) {
  for (const std::string& r : rules) {
    if (r == topic) return true;
    if (!r.empty() && r.back() == '*' && topic.starts_with(r.substr(0, r.size() - 1))) return true;
  }
  return false;
}

TEST(SecurityRules, EveryTopicOfTheTableHasARule) {
  const std::vector<std::string> rules = rule_topics();
  ASSERT_FALSE(rules.empty()) << "no topic lines read from compose/security/permissions.rules";
  for (const AnyTopic& t : all_topics()) EXPECT_TRUE(covered(t.info.name, rules)) << t.info.name;
}

}  // namespace
}  // namespace slam::dds
