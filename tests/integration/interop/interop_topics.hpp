#pragma once
// The interop test's topic names: each real topic (name and QoS from topics.hpp), and beside it an
// echo topic on which the other vendor sends back exactly what it decoded.
#include <string>

#include "common/core/topics.hpp"

namespace slam::interop {

inline std::string echo_name(const char* topic) {
  return std::string(topic) + "/echo";
}

}  // namespace slam::interop
