// Fuzz target for the VDA 5050 topic parser and the robot message decoders. Input: "<topic>\n<payload>".
// The topic goes through parse_vda_topic() and, when accepted, selects the decoder; the payload also
// goes through every robot message decoder regardless, so a mutated topic does not hide the JSON paths.
// Accepted output must be bounded (positions, battery, text) and name a robot id validate_robot_id()
// accepts.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

#include "fuzz_topic_input.hpp"
#include "protocol/text_check.hpp"
#include "protocol/topic.hpp"
#include "protocol/vda5050_codec.hpp"

namespace {

using namespace slam::protocol;

void check(bool condition) {
  if (!condition) std::abort();
}

void check_message(const VdaMessage& m, const CodecLimits& limits) {
  if (m.has_position) {
    check(std::isfinite(m.x) && std::abs(m.x) <= limits.max_abs_coordinate_m);
    check(std::isfinite(m.y) && std::abs(m.y) <= limits.max_abs_coordinate_m);
    check(std::isfinite(m.theta) && std::abs(m.theta) <= limits.max_abs_angle_rad);
    check(!find_text_problem(m.map_id));
  }
  check(m.battery <= 1.0f && (m.battery >= 0.0f || m.battery == -1.0f));
  check(m.operating_mode.size() <= kMaxStateBytes && !find_text_problem(m.operating_mode));
  check(m.node_states <= limits.max_points && m.edge_states <= limits.max_points);
  check(m.errors.size() <= limits.max_points);
  for (const VdaError& e : m.errors) check(!find_text_problem(e.type) && !find_text_problem(e.description));
  check(m.action_states.size() <= limits.max_points);
  for (const VdaActionState& a : m.action_states)
    check(!find_text_problem(a.action_id) && !find_text_problem(a.status));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto [topic, payload] = slam::fuzz::split_topic_input(data, size);

  static const VdaTree tree;
  CodecLimits limits;
  limits.max_points = 64;  // small enough for the fuzzer to reach the limit

  static VdaMessage message;
  static std::string id;
  VdaAddress address;
  if (parse_vda_topic(topic, tree, address)) {
    check(!address.manufacturer.empty() && !address.serial_number.empty());
    if (vda_robot_id(address.manufacturer, address.serial_number, id)) check(validate_robot_id(id).is_ok());
    if (decode_vda_message(address.topic, address, payload, tree, limits, message)) {
      check(message.topic == address.topic);
      check_message(message, limits);
    }
  }
  const VdaAddress fixed{VdaTopic::State, "Acme", "agv-1"};
  for (const VdaTopic t :
       {VdaTopic::Connection, VdaTopic::State, VdaTopic::Visualization, VdaTopic::Factsheet})
    if (decode_vda_message(t, fixed, payload, tree, limits, message)) check_message(message, limits);
  return 0;
}
