#pragma once
// The mapper's failure causes, the code on its Errors (common/core/result.hpp): what a reply's
// MapResult says (map.idl), known to the caller without reading the message.
#include <cstdint>

#include "common/core/result.hpp"

namespace slam::mapper {

enum class MapError : uint16_t { InvalidRequest = 1, Io, BadFile, UnknownRobot };
constexpr ErrorDomain error_domain(MapError) {
  return ErrorDomain::Map;
}

}  // namespace slam::mapper
