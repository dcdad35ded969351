// Shared by the libFuzzer targets: a reader may reject its input with any documented exception, but an
// allocation failure or an oversized container means a count was trusted before it was checked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>

namespace lc2wf::fuzz {

template <class Read>
void expect_clean_rejection(Read read) {
  try {
    read();
  } catch (const std::bad_alloc&) {
    throw;  // a finding: libFuzzer reports the uncaught exception as a crash
  } catch (const std::length_error&) {
    throw;
  } catch (const std::exception&) {
    // Rejected with a message: the promised behaviour.
  }
}

inline std::string bytes(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

}  // namespace lc2wf::fuzz
