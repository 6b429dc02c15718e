// PNG files: pixels survive encoding (bottom-up rows come out top-down), writes are atomic (the
// final name appears complete, no temp file is left), and failures name the file.
#include "viewer/core/png_file.hpp"

#include <gtest/gtest.h>

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <filesystem>

#include "temp_dir.hpp"

namespace slam::viewer {
namespace {

namespace fs = std::filesystem;

// 4 x 3 image whose every pixel encodes its own position.
RgbImage test_image(bool bottom_up) {
  RgbImage img{4, 3, bottom_up, {}};
  for (int row = 0; row < 3; ++row) {
    const int y = bottom_up ? 2 - row : row;  // the top-down row this memory row shows
    for (int x = 0; x < 4; ++x)
      img.pixels.insert(img.pixels.end(), {static_cast<uint8_t>(10 * x), static_cast<uint8_t>(100 + y), 7});
  }
  return img;
}

void expect_decodes_top_down(const uint8_t* png, size_t size) {
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load_from_memory(png, static_cast<int>(size), &w, &h, &n, 3);
  ASSERT_NE(px, nullptr);
  EXPECT_EQ(w, 4);
  EXPECT_EQ(h, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      const unsigned char* p = px + (y * 4 + x) * 3;
      EXPECT_EQ(p[0], 10 * x);
      EXPECT_EQ(p[1], 100 + y);
      EXPECT_EQ(p[2], 7);
    }
  stbi_image_free(px);
}

TEST(PngFile, EncodesTopDownAndBottomUpRows) {
  for (bool bottom_up : {false, true}) {
    auto png = encode_png(test_image(bottom_up));
    ASSERT_TRUE(png) << png.message();
    expect_decodes_top_down(png->data(), png->size());
  }
}

TEST(PngFile, RejectsAPixelBufferOfTheWrongSize) {
  RgbImage img = test_image(false);
  img.pixels.pop_back();
  auto png = encode_png(img);
  ASSERT_FALSE(png);
  EXPECT_NE(png.message().find("4x3"), std::string::npos) << png.message();
}

TEST(PngFile, WritesThroughATempNameAndReplacesTheOldFile) {
  testkit::TempDir dir("png-file");
  const std::string path = (dir.path() / "a.png").string(), temp = (dir.path() / ".a.png.tmp").string();
  ASSERT_TRUE(write_file_atomically(path, temp, {1, 2, 3}));
  ASSERT_TRUE(write_png(path, test_image(true)));
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  std::vector<uint8_t> bytes(fs::file_size(path));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(std::fread(bytes.data(), 1, bytes.size(), f), bytes.size());
  std::fclose(f);
  expect_decodes_top_down(bytes.data(), bytes.size());
}

TEST(PngFile, AFailedWriteNamesTheFileAndLeavesNothing) {
  testkit::TempDir dir("png-file");
  const std::string missing = (dir.path() / "no" / "such" / "dir" / "a.png").string();
  const Status s = write_png(missing, test_image(false));
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find(missing), std::string::npos) << s.message();
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace slam::viewer
