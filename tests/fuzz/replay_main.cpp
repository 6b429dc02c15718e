// Driver for fuzz targets when libFuzzer is not available (GCC builds): runs every seed file given
// (files or directories), then a bounded number of random mutations of them (byte flips, inserts,
// truncations), deterministic with a fixed seed. Build with clang for real coverage-guided fuzzing.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

std::vector<uint8_t> read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void mutate(std::vector<uint8_t>& data, std::mt19937& rng) {
  const int edits = 1 + static_cast<int>(rng() % 8);
  for (int i = 0; i < edits; ++i) {
    const size_t pos = data.empty() ? 0 : rng() % (data.size() + 1);
    switch (rng() % 4) {
      case 0:
        if (!data.empty()) data[pos % data.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
        break;
      case 1:
        data.insert(data.begin() + static_cast<std::ptrdiff_t>(pos), static_cast<uint8_t>(rng()));
        break;
      case 2:
        data.resize(pos);
        break;
      default:
        if (!data.empty()) data[pos % data.size()] = static_cast<uint8_t>(rng());
        break;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::vector<uint8_t>> seeds;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path arg(argv[i]);
    if (std::filesystem::is_directory(arg)) {
      for (const auto& e : std::filesystem::directory_iterator(arg))
        if (e.is_regular_file()) seeds.push_back(read_file(e.path()));
    } else if (std::filesystem::is_regular_file(arg)) {
      seeds.push_back(read_file(arg));
    }
  }
  if (seeds.empty()) seeds.emplace_back();
  for (const auto& s : seeds) LLVMFuzzerTestOneInput(s.data(), s.size());

  std::mt19937 rng(12345);
  constexpr int kMutations = 20000;
  for (int i = 0; i < kMutations; ++i) {
    std::vector<uint8_t> data = seeds[rng() % seeds.size()];
    mutate(data, rng);
    LLVMFuzzerTestOneInput(data.data(), data.size());
  }
  std::printf("replayed %zu seeds and %d mutations\n", seeds.size(), kMutations);
  return 0;
}
