// CDR reading (cdr_reader.hpp).
#include "simulator/robot_log/cdr_reader.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

namespace slam::robot_log {

Result<CdrReader> CdrReader::open(std::span<const uint8_t> message) {
  if (message.size() < 4) return Error{"shorter than its 4-byte CDR header"};
  // Representation identifier (big-endian uint16): 0/1 CDR, 6/7 plain CDR2; odd = little endian.
  const unsigned id = (unsigned{message[0]} << 8) | message[1];
  if (id != 0 && id != 1 && id != 6 && id != 7)
    return Error{"CDR representation " + std::to_string(id) + " is not plain CDR or CDR2"};
  return CdrReader(message.subspan(4), (id & 1u) != 0, id >= 6 ? 4 : 8);
}

bool CdrReader::align(size_t size) {
  const size_t a = std::min(size, max_align_);
  const size_t padded = (at_ + a - 1) / a * a;
  if (padded > body_.size()) return false;
  at_ = padded;
  return true;
}

bool CdrReader::raw(void* out, size_t size) {
  if (!align(size) || body_.size() - at_ < size) return false;
  uint8_t bytes[8];
  std::memcpy(bytes, body_.data() + at_, size);
  if (little_endian_ != (std::endian::native == std::endian::little)) std::reverse(bytes, bytes + size);
  std::memcpy(out, bytes, size);
  at_ += size;
  return true;
}

bool CdrReader::u32(uint32_t& v) {
  return raw(&v, 4);
}
bool CdrReader::i32(int32_t& v) {
  return raw(&v, 4);
}
bool CdrReader::f32(float& v) {
  return raw(&v, 4);
}
bool CdrReader::f64(double& v) {
  return raw(&v, 8);
}

bool CdrReader::string(std::string& v) {
  uint32_t n = 0;
  if (!u32(n) || n > body_.size() - at_) return false;
  const char* p = reinterpret_cast<const char*>(body_.data() + at_);
  v.assign(p, n > 0 && p[n - 1] == '\0' ? n - 1 : n);
  at_ += n;
  return true;
}

bool CdrReader::f32_sequence(std::vector<float>& v) {
  uint32_t n = 0;
  if (!u32(n) || n > (body_.size() - at_) / 4) return false;
  v.resize(n);
  for (float& x : v)
    if (!f32(x)) return false;
  return true;
}

bool CdrReader::skip_sequence(size_t element_size) {
  uint32_t n = 0;
  if (!u32(n)) return false;
  if (n == 0) return true;
  if (!align(element_size) || n > (body_.size() - at_) / element_size) return false;
  at_ += n * element_size;
  return true;
}

}  // namespace slam::robot_log
