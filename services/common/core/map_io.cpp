// ROS map_server PGM + YAML reader and writer. Every failure becomes an Error naming the file and the
// problem; yaml-cpp exceptions are caught here and never escape.
#include "common/core/map_io.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <system_error>

namespace slam {
namespace {

constexpr uint8_t kPgmFree = 254;
constexpr uint8_t kPgmOccupied = 0;
constexpr uint8_t kPgmUnknown = 205;

Error fail(std::string_view name, std::string_view what) {
  return Error{std::string(name) + ": " + std::string(what)};
}

std::string format_double(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

// Cursor over a PGM header: whitespace and '#' comments separate tokens.
class PgmCursor {
 public:
  explicit PgmCursor(std::span<const uint8_t> bytes) : bytes_(bytes) {}

  void skip_separators() {
    while (pos_ < bytes_.size()) {
      const uint8_t c = bytes_[pos_];
      if (c == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n' && bytes_[pos_] != '\r') ++pos_;
      } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
        ++pos_;
      } else {
        return;
      }
    }
  }

  // A decimal number of at most 9 digits (values past that are no valid PGM field).
  bool number(uint32_t* out) {
    skip_separators();
    uint32_t v = 0;
    size_t digits = 0;
    while (pos_ < bytes_.size() && bytes_[pos_] >= '0' && bytes_[pos_] <= '9') {
      if (++digits > 9) return false;
      v = v * 10 + static_cast<uint32_t>(bytes_[pos_] - '0');
      ++pos_;
    }
    *out = v;
    return digits > 0;
  }

  size_t pos() const { return pos_; }
  void advance(size_t n) { pos_ += n; }
  size_t remaining() const { return bytes_.size() - pos_; }
  uint8_t peek() const { return bytes_[pos_]; }

 private:
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
};

uint8_t scale_sample(uint32_t v, uint32_t maxval) {
  return static_cast<uint8_t>((v * 255u + maxval / 2) / maxval);
}

Result<std::string> read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(path.string(), "cannot open for reading");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) return fail(path.string(), "read error");
  return text;
}

Status write_atomically(const std::filesystem::path& path, std::string_view data) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return fail(path.string(), "cannot open for writing");
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    out.flush();
    if (!out) return fail(path.string(), "write error");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) return fail(path.string(), "cannot rename temporary file: " + ec.message());
  return Status::ok();
}

}  // namespace

Result<MapYaml> parse_map_yaml(std::string_view text, std::string_view name) {
  MapYaml out;
  try {
    const YAML::Node root = YAML::Load(std::string(text));
    if (!root.IsMap()) return fail(name, "not a YAML mapping");
    const YAML::Node image = root["image"];
    if (!image || !image.IsScalar() || image.Scalar().empty()) return fail(name, "missing key 'image'");
    out.image = image.Scalar();
    const YAML::Node res = root["resolution"];
    if (!res || !res.IsScalar()) return fail(name, "missing key 'resolution'");
    out.resolution = res.as<double>();
    if (!std::isfinite(out.resolution) || out.resolution <= 0.0)
      return fail(name, "resolution must be a finite number > 0");
    const YAML::Node origin = root["origin"];
    if (!origin || !origin.IsSequence() || origin.size() != 3)
      return fail(name, "origin must be a list [x, y, yaw]");
    for (size_t i = 0; i < 3; ++i) {
      out.origin[i] = origin[i].as<double>();
      if (!std::isfinite(out.origin[i])) return fail(name, "origin values must be finite");
    }
    if (const YAML::Node n = root["negate"]) {
      const std::string v = n.IsScalar() ? n.Scalar() : std::string();
      if (v == "0" || v == "false")
        out.negate = false;
      else if (v == "1" || v == "true")
        out.negate = true;
      else
        return fail(name, "negate must be 0 or 1");
    }
    if (const YAML::Node n = root["occupied_thresh"]) out.occupied_thresh = n.as<double>();
    if (const YAML::Node n = root["free_thresh"]) out.free_thresh = n.as<double>();
    if (!(out.occupied_thresh >= 0.0 && out.occupied_thresh <= 1.0))
      return fail(name, "occupied_thresh must be within [0, 1]");
    if (!(out.free_thresh >= 0.0 && out.free_thresh <= 1.0))
      return fail(name, "free_thresh must be within [0, 1]");
    if (out.free_thresh >= out.occupied_thresh)
      return fail(name, "free_thresh must be below occupied_thresh");
    if (const YAML::Node n = root["mode"]) {
      out.mode = n.IsScalar() ? n.Scalar() : std::string();
      if (out.mode == "raw") return fail(name, "mode 'raw' is not supported (use trinary or scale)");
      if (out.mode != "trinary" && out.mode != "scale") return fail(name, "mode must be trinary or scale");
    }
  } catch (const YAML::Exception& e) {
    return fail(name, std::string("invalid YAML: ") + e.what());
  }
  return out;
}

Result<PgmImage> parse_pgm(std::span<const uint8_t> bytes, std::string_view name) {
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '2'))
    return fail(name, "not a PGM image (expected P5 or P2 magic)");
  const bool binary = bytes[1] == '5';
  PgmCursor cur(bytes);
  cur.advance(2);
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t maxval = 0;
  if (!cur.number(&width) || !cur.number(&height) || !cur.number(&maxval))
    return fail(name, "malformed PGM header (width, height, maxval)");
  if (width == 0 || height == 0) return fail(name, "PGM image has zero width or height");
  if (maxval == 0 || maxval > 65535) return fail(name, "PGM maxval must be within 1..65535");
  const uint64_t count = uint64_t{width} * height;
  if (count > kMaxMapPixels) return fail(name, "PGM image is too large");

  PgmImage img;
  img.width = width;
  img.height = height;
  if (binary) {
    // Exactly one whitespace byte separates maxval from the raster.
    if (cur.remaining() == 0) return fail(name, "PGM raster missing");
    cur.advance(1);
    const uint64_t sample_bytes = maxval < 256 ? 1 : 2;
    if (cur.remaining() < count * sample_bytes)
      return fail(name, "PGM raster truncated (" + std::to_string(cur.remaining()) + " bytes for " +
                            std::to_string(count) + " pixels)");
    img.pixels.resize(static_cast<size_t>(count));
    const uint8_t* p = bytes.data() + cur.pos();
    for (size_t i = 0; i < img.pixels.size(); ++i) {
      const uint32_t v = sample_bytes == 1 ? p[i] : (uint32_t{p[2 * i]} << 8) | p[2 * i + 1];
      if (v > maxval) return fail(name, "PGM sample exceeds maxval");
      img.pixels[i] = scale_sample(v, maxval);
    }
  } else {
    // Every ASCII sample takes at least two bytes (digit + separator) except possibly the last.
    if ((cur.remaining() + 1) / 2 < count) return fail(name, "PGM raster truncated");
    img.pixels.resize(static_cast<size_t>(count));
    for (auto& px : img.pixels) {
      uint32_t v = 0;
      if (!cur.number(&v)) return fail(name, "PGM raster truncated or not a number");
      if (v > maxval) return fail(name, "PGM sample exceeds maxval");
      px = scale_sample(v, maxval);
    }
  }
  return img;
}

Result<MapImage> decode_map(const MapYaml& yaml, const PgmImage& pgm, std::string_view name) {
  if (pgm.pixels.size() != size_t{pgm.width} * pgm.height)
    return fail(name, "image size does not match its header");
  MapImage map;
  map.width = pgm.width;
  map.height = pgm.height;
  map.resolution = yaml.resolution;
  map.origin_x = yaml.origin[0];
  map.origin_y = yaml.origin[1];
  map.origin_yaw = yaml.origin[2];
  map.cells.resize(pgm.pixels.size());
  // map_server's rule: occupancy probability from darkness (or brightness when negated).
  uint8_t lut[256];
  for (int v = 0; v < 256; ++v) {
    const double p = yaml.negate ? v / 255.0 : (255 - v) / 255.0;
    lut[v] = p > yaml.occupied_thresh ? kMapOccupied : (p < yaml.free_thresh ? kMapFree : kMapUnknown);
  }
  for (uint32_t r = 0; r < pgm.height; ++r) {
    const uint8_t* src = pgm.pixels.data() + size_t{r} * pgm.width;
    uint8_t* dst = map.cells.data() + size_t{pgm.height - 1 - r} * pgm.width;
    for (uint32_t c = 0; c < pgm.width; ++c) dst[c] = lut[src[c]];
  }
  return map;
}

std::vector<uint8_t> encode_pgm(const MapImage& map) {
  const std::string header =
      "P5\n# slam-mapper\n" + std::to_string(map.width) + " " + std::to_string(map.height) + "\n255\n";
  std::vector<uint8_t> out(header.begin(), header.end());
  out.reserve(header.size() + map.cells.size());
  for (uint32_t r = map.height; r-- > 0;) {
    const uint8_t* row = map.cells.data() + size_t{r} * map.width;
    for (uint32_t c = 0; c < map.width; ++c)
      out.push_back(row[c] == kMapOccupied ? kPgmOccupied : (row[c] == kMapFree ? kPgmFree : kPgmUnknown));
  }
  return out;
}

std::string encode_map_yaml(const MapImage& map, std::string_view image_name) {
  std::string quoted = "'";  // single-quoted YAML scalar: only ' itself needs escaping (doubled)
  for (const char c : image_name) quoted += c == '\'' ? std::string("''") : std::string(1, c);
  quoted += "'";
  return "image: " + quoted + "\nresolution: " + format_double(map.resolution) + "\norigin: [" +
         format_double(map.origin_x) + ", " + format_double(map.origin_y) + ", " +
         format_double(map.origin_yaw) +
         "]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n";
}

Result<MapImage> read_ros_map(const std::filesystem::path& yaml_path) {
  auto text = read_text(yaml_path);
  if (!text) return text.error();
  auto yaml = parse_map_yaml(*text, yaml_path.string());
  if (!yaml) return yaml.error();
  std::filesystem::path image = yaml->image;
  if (image.is_relative()) image = yaml_path.parent_path() / image;
  auto bytes = read_text(image);
  if (!bytes) return bytes.error();
  const auto* data = reinterpret_cast<const uint8_t*>(bytes->data());
  auto pgm = parse_pgm(std::span<const uint8_t>(data, bytes->size()), image.string());
  if (!pgm) return pgm.error();
  return decode_map(*yaml, *pgm, image.string());
}

Status write_ros_map(const std::filesystem::path& yaml_path, const MapImage& map) {
  const std::string name = yaml_path.string();
  if (map.width == 0 || map.height == 0) return fail(name, "map is empty");
  if (map.cells.size() != size_t{map.width} * map.height)
    return fail(name, "cell count does not match width*height");
  if (!std::isfinite(map.resolution) || map.resolution <= 0.0) return fail(name, "resolution must be > 0");
  if (!std::isfinite(map.origin_x) || !std::isfinite(map.origin_y) || !std::isfinite(map.origin_yaw))
    return fail(name, "origin must be finite");
  std::filesystem::path pgm_path = yaml_path;
  pgm_path.replace_extension(".pgm");
  if (pgm_path == yaml_path) return fail(name, "the YAML file must not have the .pgm extension");
  const std::vector<uint8_t> pgm = encode_pgm(map);
  if (Status s =
          write_atomically(pgm_path, std::string_view(reinterpret_cast<const char*>(pgm.data()), pgm.size()));
      !s)
    return s;
  return write_atomically(yaml_path, encode_map_yaml(map, pgm_path.filename().string()));
}

}  // namespace slam
