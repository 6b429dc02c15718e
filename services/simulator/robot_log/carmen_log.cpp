// Reading CARMEN logs (carmen_log.hpp).
#include "simulator/robot_log/carmen_log.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <array>
#include <memory>
#include <string>

namespace slam::robot_log {

namespace {

// A line longer than this is junk (a 1 081-beam ROBOTLASER1 with remissions is about 20 kB).
constexpr size_t kMaxLineBytes = size_t{1} << 20;

struct GzCloser {
  void operator()(gzFile_s* f) const { gzclose(f); }
};
using GzFile = std::unique_ptr<gzFile_s, GzCloser>;

}  // namespace

void CarmenLogBuilder::mark_bad(std::string_view reason) {
  LogStats& s = log_.stats;
  if (s.bad_lines == 0) s.first_bad = fmt::format("line {}: {}", s.lines, reason);
  ++s.bad_lines;
}

void CarmenLogBuilder::add_bad_line(std::string_view reason) {
  ++log_.stats.lines;
  mark_bad(reason);
}

void CarmenLogBuilder::add_line(std::string_view line) {
  LogStats& s = log_.stats;
  ++s.lines;
  auto record = parse_carmen_line(line, context_, options_);
  if (!record) {
    mark_bad(record.message());
    return;
  }
  switch (record->kind) {
    case CarmenKind::Comment:
      ++s.comments;
      break;
    case CarmenKind::Odometry:
      ++s.odometry;
      break;
    case CarmenKind::Unknown:
      ++s.unknown_kinds;
      break;
    case CarmenKind::Param:
      break;
    case CarmenKind::Scan:
      count_scan(*record->scan, log_.scans.empty() ? nullptr : &log_.scans.back(), s);
      log_.scans.push_back(std::move(*record->scan));
      break;
  }
}

RobotLog parse_carmen_text(std::string_view text, const CarmenOptions& options) {
  CarmenLogBuilder builder(options);
  while (!text.empty()) {
    const size_t eol = std::min(text.find('\n'), text.size());
    builder.add_line(text.substr(0, eol));
    text.remove_prefix(std::min(eol + 1, text.size()));
  }
  return builder.take();
}

Result<RobotLog> read_carmen_log(const std::filesystem::path& path, const CarmenOptions& options) {
  SLAM_TRY(options.validate());
  // gzopen reads a plain file as it is, so one path serves .clf and .clf.gz.
  GzFile file(gzopen(path.c_str(), "rb"));
  if (!file) return Error{fmt::format("cannot open {}", path.string())};
  gzbuffer(file.get(), 1 << 17);
  CarmenLogBuilder builder(options);
  std::array<char, 1 << 16> chunk{};
  std::string line;
  bool too_long = false;
  while (gzgets(file.get(), chunk.data(), static_cast<int>(chunk.size())) != nullptr) {
    const std::string_view piece(chunk.data());
    const bool complete = !piece.empty() && piece.back() == '\n';
    if (!too_long) line.append(piece.substr(0, piece.size() - (complete ? 1 : 0)));
    if (line.size() > kMaxLineBytes) {
      too_long = true;
      line.clear();
    }
    if (!complete && !gzeof(file.get())) continue;
    if (too_long)
      builder.add_bad_line(fmt::format("longer than {} bytes", kMaxLineBytes));
    else
      builder.add_line(line);
    line.clear();
    too_long = false;
  }
  int code = Z_OK;
  const char* message = gzerror(file.get(), &code);
  if (code != Z_OK && code != Z_STREAM_END)
    return Error{fmt::format("{}: reading stopped after line {}: {}", path.string(),
                             builder.take().stats.lines, message)};
  return builder.take();
}

}  // namespace slam::robot_log
