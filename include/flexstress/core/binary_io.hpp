// Little-endian binary writing and bounds-checked reading, and a checksum: what the versioned
// file formats (modal body files, scene checkpoints) share.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace flexstress::binary {

/// FNV-1a, 64 bit: detects corruption (not tampering).
inline std::uint64_t fnv1a(const unsigned char* data, std::size_t size) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= data[i];
    h *= 1099511628211ull;
  }
  return h;
}

inline bool little_endian_host() {
  const std::uint32_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

/// Appends values in the host's byte order (the formats require a little-endian host; checked
/// by their writers).
class Writer {
 public:
  template <class T>
  void put(T value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    buffer.insert(buffer.end(), bytes, bytes + sizeof(T));
  }
  void put_doubles(const double* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) put(p[i]);
  }
  std::vector<unsigned char> buffer;
};

/// Reads values from a byte range, failing (not reading past the end) when it runs out.
class Reader {
 public:
  Reader(const unsigned char* data, std::size_t size) : data_(data), size_(size) {}
  template <class T>
  bool get(T& value) {
    if (size_ - pos_ < sizeof(T)) return false;
    std::memcpy(&value, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool get_doubles(double* p, std::size_t n) {
    if ((size_ - pos_) / sizeof(double) < n) return false;
    std::memcpy(p, data_ + pos_, n * sizeof(double));
    pos_ += n * sizeof(double);
    return true;
  }
  std::size_t remaining() const { return size_ - pos_; }

 private:
  const unsigned char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace flexstress::binary
