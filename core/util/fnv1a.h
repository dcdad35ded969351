// FNV-1a, 64 bit: a stable hash of a name (split keys, per-building seeds, test tensors), the same on every
// compiler and platform, unlike std::hash.
#pragma once

#include <cstdint>
#include <string_view>

namespace lc2wf {

constexpr uint64_t fnv1a64(std::string_view text) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : text) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  return h;
}

}  // namespace lc2wf
