#pragma once
// FNV-1a 64: a stable, dependency-free digest (cache checksums and keys, run ids). Any single
// changed byte changes it (each step is a bijection of the state); not for security.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace sdfbench {

inline uint64_t fnv1a64(std::span<const std::byte> bytes, uint64_t hash = 0xcbf29ce484222325ull) {
  for (std::byte b : bytes) hash = (hash ^ static_cast<uint64_t>(b)) * 0x100000001b3ull;
  return hash;
}

inline uint64_t fnv1a64(std::string_view text, uint64_t hash = 0xcbf29ce484222325ull) {
  return fnv1a64(std::as_bytes(std::span(text.data(), text.size())), hash);
}

}  // namespace sdfbench
