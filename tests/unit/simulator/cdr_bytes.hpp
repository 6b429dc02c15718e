#pragma once
// Test helper: CDR messages built field by field, as a ROS 2 publisher serialises them.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace slam::robot_log {

// Builds a CDR message: the encapsulation header, then aligned fields.
class CdrBytes {
 public:
  explicit CdrBytes(bool little_endian = true, bool cdr2 = false)
      : little_(little_endian),
        max_align_(cdr2 ? 4 : 8),
        bytes_{0, static_cast<uint8_t>((cdr2 ? 6 : 0) | (little_endian ? 1 : 0)), 0, 0} {}
  CdrBytes& u32(uint32_t v) { return put(&v, 4); }
  CdrBytes& i32(int32_t v) { return put(&v, 4); }
  CdrBytes& f32(float v) { return put(&v, 4); }
  CdrBytes& f64(double v) { return put(&v, 8); }
  CdrBytes& string(const std::string& s) {
    u32(static_cast<uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
    return *this;
  }
  CdrBytes& header(int32_t sec, uint32_t nanosec, const std::string& frame) {
    return i32(sec).u32(nanosec).string(frame);
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  CdrBytes& put(const void* v, size_t n) {
    const size_t a = std::min(n, max_align_);
    while ((bytes_.size() - 4) % a != 0) bytes_.push_back(0);
    uint8_t b[8];
    std::memcpy(b, v, n);
    if (little_ != (std::endian::native == std::endian::little)) std::reverse(b, b + n);
    bytes_.insert(bytes_.end(), b, b + n);
    return *this;
  }
  bool little_;
  size_t max_align_;
  std::vector<uint8_t> bytes_;
};

}  // namespace slam::robot_log
