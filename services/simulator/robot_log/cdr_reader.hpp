#pragma once
// Reading ROS 2 messages as DDS serialises them (what rosbag2 stores with message encoding "cdr"):
// a 4-byte encapsulation header, then the fields in order, each aligned to its size counted from
// the end of the header. Classic CDR (XCDR1) aligns up to 8 bytes, plain CDR2 up to 4; either byte
// order. Every read is bounds-checked and returns false past the end.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/core/result.hpp"

namespace slam::robot_log {

class CdrReader {
 public:
  // Checks the encapsulation header (CDR or plain CDR2, big or little endian).
  static Result<CdrReader> open(std::span<const uint8_t> message);

  bool u32(uint32_t& v);
  bool i32(int32_t& v);
  bool f32(float& v);
  bool f64(double& v);
  // uint32 length (the terminating NUL included), then the bytes.
  bool string(std::string& v);
  // uint32 count, then the floats.
  bool f32_sequence(std::vector<float>& v);
  // Skips a uint32-counted sequence of elements of `element_size` bytes.
  bool skip_sequence(size_t element_size);

 private:
  CdrReader(std::span<const uint8_t> body, bool little_endian, size_t max_align)
      : body_(body), little_endian_(little_endian), max_align_(max_align) {}
  bool align(size_t size);
  bool raw(void* out, size_t size);

  std::span<const uint8_t> body_;
  size_t at_ = 0;
  bool little_endian_ = true;
  size_t max_align_ = 8;
};

}  // namespace slam::robot_log
