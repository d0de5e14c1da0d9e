// Little-endian binary writing and bounds-checked reading, a checksum, and the sealed envelope
// (magic, version, byte order, signature, size, checksum): what the versioned file formats
// (modal body files, model checkpoints, damage-meter checkpoints) share.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "flexstress/core/status.hpp"

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
    // Byte by byte: GCC 12 flags a range insert from a raw pointer into a vector that may be
    // empty (-Wnonnull on its null data, a false positive) where this is inlined.
    for (unsigned char b : bytes) buffer.push_back(b);
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

/// Writes bytes to a file; errors name the file.
inline Status write_file(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  if (!out) return make_error(ErrorCode::io_error, "cannot open '", path, "' for writing");
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  if (!out) return make_error(ErrorCode::io_error, "writing '", path, "' failed");
  return Status::success();
}

/// A file's bytes; errors name the file.
inline Result<std::vector<unsigned char>> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::io_error, "cannot open '", path, "' for reading");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) return make_error(ErrorCode::io_error, "reading '", path, "' failed");
  return bytes;
}

/// The header of a format whose data belongs to one configuration (a model, a damage meter's
/// grid and S-N curve):
///   8-byte magic, u32 version, u32 byte-order mark 0x01020304,
///   u64 signature of the configuration, u64 payload size, u64 FNV-1a checksum of the payload.
/// open() checks all of it before anything reads the payload, and names what is wrong.
struct Envelope {
  const char* magic;      ///< exactly 8 characters
  std::uint32_t version;  ///< the version this library writes and reads
  const char* kind;       ///< what the data is, for messages: "checkpoint"

  static constexpr std::size_t header_size = 8 + 4 + 4 + 8 + 8 + 8;
  static constexpr std::uint32_t byte_order_mark = 0x01020304u;

  /// The sealed image: header, then the payload.
  std::vector<unsigned char> seal(std::uint64_t signature,
                                  const std::vector<unsigned char>& payload) const {
    Writer out;
    for (int k = 0; k < 8; ++k) out.buffer.push_back(static_cast<unsigned char>(magic[k]));
    out.put(version);
    out.put(byte_order_mark);
    out.put(signature);
    out.put(static_cast<std::uint64_t>(payload.size()));
    out.put(fnv1a(payload.data(), payload.size()));
    out.buffer.insert(out.buffer.end(), payload.begin(), payload.end());
    return std::move(out.buffer);
  }

  /// The payload of a sealed image whose signature must be `signature`; `name` (a file name)
  /// and `other_configuration` (what a signature mismatch means) go into the messages.
  Result<Reader> open(const unsigned char* data, std::size_t size, std::uint64_t signature,
                      const std::string& name, const std::string& other_configuration) const {
    auto bad = [&](const auto&... parts) {
      return make_error(ErrorCode::bad_file_format, "'", name, "': ", parts...);
    };
    if (size < 8 || std::memcmp(data, magic, 8) != 0)
      return bad("not a flexstress ", kind, " (the first 8 bytes are not \"", std::string(magic, 8),
                 "\")");
    if (size < header_size)
      return bad("truncated header (", size, " bytes, the header alone is ", header_size, ")");
    Reader header(data + 8, header_size - 8);
    std::uint32_t file_version = 0, bom = 0;
    std::uint64_t file_signature = 0, payload = 0, checksum = 0;
    header.get(file_version);
    header.get(bom);
    header.get(file_signature);
    header.get(payload);
    header.get(checksum);
    if (bom != byte_order_mark)
      return bad("byte-order mark ", bom, " is not ", byte_order_mark,
                 " (written on a host of the other byte order)");
    if (file_version != version)
      return bad("format version ", file_version, " is not supported (this library reads version ",
                 version, ")");
    if (file_signature != signature) return bad(other_configuration);
    if (payload != size - header_size)
      return bad("the header announces ", payload, " bytes of data but the file holds ",
                 size - header_size, " (truncated or padded)");
    const unsigned char* body = data + header_size;
    if (fnv1a(body, static_cast<std::size_t>(payload)) != checksum)
      return bad("checksum mismatch: the data is corrupted");
    return Reader(body, static_cast<std::size_t>(payload));
  }
};

}  // namespace flexstress::binary
