// Java world text parsing. Strict: every token must parse completely, sizes must be positive and
// walls inside the world, so a typo is reported with its token instead of silently moving a wall.
#include "simulator/core/world_text.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace slam::sim {
namespace {

constexpr double kCmPerMetre = 100.0;
constexpr std::uintmax_t kMaxFileBytes = 64u << 20;

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

// The token as it should appear in a message: bounded and printable.
std::string shown(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string out;
  for (char c : token.substr(0, kMax)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (token.size() > kMax) out += "...";
  return out;
}

std::optional<double> parse_number(std::string_view s) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// Splits "a<sep>b" at the only separator; nullopt unless there is exactly one.
std::optional<std::pair<std::string_view, std::string_view>> split_once(std::string_view s, char sep) {
  const size_t at = s.find(sep);
  if (at == std::string_view::npos || s.find(sep, at + 1) != std::string_view::npos) return std::nullopt;
  return std::pair{s.substr(0, at), s.substr(at + 1)};
}

std::optional<Vec2> parse_point(std::string_view s) {
  const auto parts = split_once(s, ',');
  if (!parts) return std::nullopt;
  const auto x = parse_number(parts->first), y = parse_number(parts->second);
  if (!x || !y) return std::nullopt;
  return Vec2{*x / kCmPerMetre, *y / kCmPerMetre};
}

Result<World> parse(std::string_view text, std::string_view source, std::string name) {
  size_t token_no = 0;
  std::string_view token;
  auto fail = [&](std::string_view problem) {
    return Error{fmt::format("{}: token {} '{}': {}", source, token_no, shown(token), problem)};
  };

  std::optional<Bounds> bounds;
  std::vector<Segment> walls;
  size_t pos = 0;
  while (true) {
    while (pos < text.size() && is_space(text[pos])) ++pos;
    if (pos == text.size()) break;
    const size_t start = pos;
    while (pos < text.size() && !is_space(text[pos])) ++pos;
    token = text.substr(start, pos - start);
    ++token_no;

    if (!bounds) {
      const auto parts = split_once(token, ':');
      const auto w = parts ? parse_number(parts->first) : std::nullopt;
      const auto h = parts ? parse_number(parts->second) : std::nullopt;
      if (!w || !h) return fail("expected the world size W:H in centimetres, e.g. 400:300");
      if (*w <= 0.0 || *h <= 0.0) return fail("world width and height must be positive");
      if (*w / kCmPerMetre > World::kMaxExtent || *h / kCmPerMetre > World::kMaxExtent)
        return fail(fmt::format("world larger than {} m", World::kMaxExtent));
      bounds = Bounds{{0.0, 0.0}, {*w / kCmPerMetre, *h / kCmPerMetre}};
      continue;
    }
    const auto ends = split_once(token, ':');
    const auto a = ends ? parse_point(ends->first) : std::nullopt;
    const auto b = ends ? parse_point(ends->second) : std::nullopt;
    if (!a || !b) return fail("expected a wall x1,y1:x2,y2 in centimetres, e.g. 0,50:120,50");
    if (!bounds->contains(*a) || !bounds->contains(*b))
      return fail(fmt::format("wall end outside the world 0,0:{},{}", bounds->max.x * kCmPerMetre,
                              bounds->max.y * kCmPerMetre));
    if (a->x == b->x && a->y == b->y) return fail("wall has zero length");
    walls.push_back({*a, *b});
  }
  if (!bounds) return Error{fmt::format("{}: empty world file: expected the world size W:H first", source)};
  return World::create(std::move(name), *bounds, std::move(walls));
}

}  // namespace

Result<World> parse_java_world(std::string_view text, std::string_view source) {
  return parse(text, source, std::string(source));
}

Result<World> load_java_world(const std::filesystem::path& file) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) return Error{fmt::format("{}: cannot read world file: {}", file.string(), ec.message())};
  if (size > kMaxFileBytes)
    return Error{
        fmt::format("{}: world file of {} bytes exceeds {} bytes", file.string(), size, kMaxFileBytes)};
  std::ifstream in(file, std::ios::binary);
  if (!in) return Error{fmt::format("{}: cannot open world file", file.string())};
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), file.string(), file.stem().string());
}

}  // namespace slam::sim
