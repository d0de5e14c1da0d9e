// Damage that every flexstress binary file format (modal body files, geometric stiffness
// files) must refuse with an error that says what is wrong.
#pragma once

#include <string>
#include <vector>

#include <doctest/doctest.h>

namespace flexstress::testing {

/// Truncation (of the data, then of the header), a flipped bit (the checksum) and a newer
/// format version (byte 8): `error_of(bytes)` returns the loader's message for bytes it must
/// refuse.
template <class ErrorOf>
void check_common_damage(const std::vector<unsigned char>& good, ErrorOf error_of) {
  auto bytes = good;
  bytes.resize(bytes.size() - 64);
  CHECK(error_of(bytes).find("truncated") != std::string::npos);
  bytes.resize(20);
  CHECK(error_of(bytes).find("truncated header") != std::string::npos);
  bytes = good;
  bytes[bytes.size() / 2] ^= 0x10;
  CHECK(error_of(bytes).find("checksum") != std::string::npos);
  bytes = good;
  bytes[8] = 2;
  CHECK(error_of(bytes).find("version 2") != std::string::npos);
}

}  // namespace flexstress::testing
