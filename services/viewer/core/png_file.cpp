// PNG encoding and atomic file replacement (see png_file.hpp).
#include "viewer/core/png_file.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace slam::viewer {
namespace {

void append(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  const auto* bytes = static_cast<const uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

Result<std::vector<uint8_t>> encode_png(const RgbImage& image) {
  const size_t row = static_cast<size_t>(image.width) * 3;
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != row * static_cast<size_t>(image.height))
    return Error{"image of " + std::to_string(image.width) + "x" + std::to_string(image.height) + " has " +
                 std::to_string(image.pixels.size()) + " bytes of pixels"};
  const uint8_t* top = image.pixels.data();
  int stride = static_cast<int>(row);
  if (image.bottom_up) {  // start at the last row and step backwards: no flipped copy
    top += row * static_cast<size_t>(image.height - 1);
    stride = -stride;
  }
  std::vector<uint8_t> out;
  out.reserve(image.pixels.size() / 4);
  if (!stbi_write_png_to_func(append, &out, image.width, image.height, 3, top, stride))
    return Error{"PNG encoding failed"};
  return out;
}

Status write_file_atomically(const std::string& path, const std::string& temp_path,
                             const std::vector<uint8_t>& bytes) {
  std::FILE* f = std::fopen(temp_path.c_str(), "wb");
  if (!f) return Error{"cannot create " + temp_path + ": " + std::strerror(errno)};
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const int write_errno = errno;
  if (std::fclose(f) != 0 || !written) {
    std::remove(temp_path.c_str());
    return Error{"cannot write " + temp_path + ": " + std::strerror(written ? errno : write_errno)};
  }
  if (std::rename(temp_path.c_str(), path.c_str()) != 0) {
    const int e = errno;
    std::remove(temp_path.c_str());
    return Error{"cannot rename " + temp_path + " to " + path + ": " + std::strerror(e)};
  }
  return {};
}

Status write_png(const std::string& path, const RgbImage& image) {
  auto bytes = encode_png(image);
  if (!bytes) return Error{"cannot write " + path + ": " + bytes.message()};
  return write_file_atomically(path, path + ".tmp", *bytes);
}

}  // namespace slam::viewer
