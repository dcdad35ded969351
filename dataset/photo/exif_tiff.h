// The TIFF structure inside a JPEG's APP1 "Exif" segment, read with every offset checked against the segment,
// so a broken or hostile file gives a reason (Failure), never a crash. Shared by the GPS and focal-length
// readers (exif_gps.h, exif_focal.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace lc2wf::exif {

struct Failure {
  std::string why;
};

constexpr uint16_t kByte = 1, kAscii = 2, kShort = 3, kLong = 4, kRational = 5;
constexpr uint16_t kExifIfdTag = 0x8769, kGpsIfdTag = 0x8825;  // IFD0 pointers to the Exif and GPS IFDs
constexpr int kMaxEntries = 512;                                // IFDs hold tens of entries; more is a broken file

class Tiff {
 public:
  explicit Tiff(std::string_view data);  // throws Failure when the header is not TIFF's
  uint8_t u8(size_t at) const;
  uint16_t u16(size_t at) const;
  uint32_t u32(size_t at) const;
  void need(size_t at, size_t n) const;  // throws Failure when [at, at + n) leaves the block
  size_t first_ifd() const { return u32(4); }

 private:
  std::string_view d_;
  bool little_ = true;
};

struct Entry {
  uint16_t type = 0;
  uint32_t count = 0;
  size_t value_at = 0;  // where the value is: inside the entry when it fits in 4 bytes, else at its offset
};

// Calls visit(tag, entry) for each entry of the IFD at `at`.
template <typename Visit>
void read_ifd(const Tiff& t, size_t at, Visit visit) {
  const uint16_t n = t.u16(at);
  if (n > kMaxEntries) throw Failure{"EXIF: an IFD with " + std::to_string(n) + " entries"};
  for (uint16_t k = 0; k < n; ++k) {
    const size_t e = at + 2 + 12 * static_cast<size_t>(k);
    Entry entry{t.u16(e + 2), t.u32(e + 4), e + 8};
    const size_t unit = entry.type == kRational ? 8 : entry.type == kAscii || entry.type == kByte ? 1 : entry.type == kShort ? 2 : 4;
    if (static_cast<uint64_t>(unit) * entry.count > 4) entry.value_at = t.u32(e + 8);
    visit(t.u16(e), entry);
  }
}

// A RATIONAL value (throws Failure naming `what` when its denominator is 0).
double rational(const Tiff& t, size_t at, const char* what);

// A SHORT or LONG value as an unsigned number (throws Failure naming `what` for any other type).
uint32_t whole_number(const Tiff& t, const Entry& e, const char* what);

// The TIFF block of a whole JPEG's (or its head's) Exif segment; throws Failure ("not a JPEG", "no EXIF", ...).
std::string_view tiff_block(std::string_view jpeg);

// A file's first 256 KB, where EXIF sits (before the image data). Throws std::runtime_error naming the file.
std::string read_head(const std::filesystem::path& path);

}  // namespace lc2wf::exif
