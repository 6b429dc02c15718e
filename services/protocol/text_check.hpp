#pragma once
// Robot ids and state strings end up in topic names, DDS strings and log lines: they must be
// well-formed UTF-8 without control characters, or one bad robot garbles every consumer.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace slam::protocol {

struct TextProblem {
  std::size_t offset = 0;  // byte where the problem starts
  std::string_view what;   // "invalid UTF-8" or "control character"
};

// First problem in `text`: ill-formed UTF-8 (RFC 3629: no overlongs, surrogates or code points
// above U+10FFFF) or a control character (U+0000..U+001F, U+007F, U+0080..U+009F).
std::optional<TextProblem> find_text_problem(std::string_view text);

}  // namespace slam::protocol

namespace slam::protocol {

// `text` made safe for a log line: printable ASCII kept, every other byte as \xNN, cut to
// `max_bytes` input bytes with "..." appended. For echoing untrusted topics and ids.
std::string escape_for_log(std::string_view text, std::size_t max_bytes = 96);

}  // namespace slam::protocol
