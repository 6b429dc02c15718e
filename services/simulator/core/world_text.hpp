#pragma once
// Reader for the Java server's world text format (the samples in worlds/ssnar-java load unchanged):
// whitespace-separated tokens, the first `W:H` (world size in centimetres), every further one a wall
// `x1,y1:x2,y2` in centimetres; the four border walls around (0,0)-(W,H) are implied.
#include <filesystem>
#include <string_view>

#include "common/core/result.hpp"
#include "simulator/core/world.hpp"

namespace slam::sim {

// Parses `text`; errors read "<source>: token <n> '<token>': <problem>" (tokens count from 1).
// The world is named after `source`.
Result<World> parse_java_world(std::string_view text, std::string_view source);

// Reads and parses a file; the world is named after the file's stem.
Result<World> load_java_world(const std::filesystem::path& file);

}  // namespace slam::sim
