// Topic and filter checks shared by the options validator and the viewer's requests.
#include "gateway/core/topic_filter.hpp"

#include <string>

#include "protocol/text_check.hpp"

namespace slam::gateway {

namespace {

Status check_text(std::string_view what, std::string_view text) {
  std::string quoted(1, '\'');  // built by appending: GCC 12 misreports "'" + string as -Wrestrict
  quoted += protocol::escape_for_log(text);
  quoted += '\'';
  if (text.empty()) return Error{std::string(what) + " is empty"};
  if (text.size() > kMaxTopicBytes) {
    return Error{std::string(what) + " " + quoted + " is " + std::to_string(text.size()) + " bytes, limit " +
                 std::to_string(kMaxTopicBytes)};
  }
  if (auto problem = protocol::find_text_problem(text)) {
    return Error{std::string(what) + " " + quoted + " has " + std::string(problem->what) + " at byte " +
                 std::to_string(problem->offset)};
  }
  return Status::ok();
}

}  // namespace

Status validate_filter(std::string_view filter) {
  if (auto s = check_text("filter", filter); !s) return s;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = filter.find('/', start);
    const std::string_view level =
        filter.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
    const bool has_wildcard = level.find_first_of("+#") != std::string_view::npos;
    if (has_wildcard && level.size() != 1) {
      return Error{"filter '" + protocol::escape_for_log(filter) + "': a wildcard must be a whole level"};
    }
    if (level == "#" && end != std::string_view::npos) {
      return Error{"filter '" + protocol::escape_for_log(filter) + "': '#' must be the last level"};
    }
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return Status::ok();
}

Status validate_topic_name(std::string_view topic) {
  if (auto s = check_text("topic", topic); !s) return s;
  if (topic.find_first_of("+#") != std::string_view::npos) {
    return Error{"topic '" + protocol::escape_for_log(topic) + "' contains a wildcard ('+' or '#')"};
  }
  return Status::ok();
}

}  // namespace slam::gateway
