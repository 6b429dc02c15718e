#pragma once
// PNG files from RGB pixels, written so that no reader ever sees a partial file: the bytes go to a
// temp name in the same directory, which is then renamed over the final name (atomic on POSIX).
// Plain C++ (stb_image_write), so the snapshot writer thread and the tests use it without GL.
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/result.hpp"

namespace slam::viewer {

struct RgbImage {
  int width = 0;
  int height = 0;
  bool bottom_up = false;       // rows as glReadPixels returns them (first row = bottom)
  std::vector<uint8_t> pixels;  // width * height * 3
};

// The PNG bytes of `image` (rows written top-down).
Result<std::vector<uint8_t>> encode_png(const RgbImage& image);

// Writes `bytes` to `temp_path`, then renames it to `path`; on failure the temp file is removed.
Status write_file_atomically(const std::string& path, const std::string& temp_path,
                             const std::vector<uint8_t>& bytes);

// encode_png + write_file_atomically(path, path + ".tmp").
Status write_png(const std::string& path, const RgbImage& image);

}  // namespace slam::viewer
