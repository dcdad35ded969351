#include "dataset/photo/exif_tiff.h"

#include <fstream>
#include <stdexcept>

namespace lc2wf::exif {

Tiff::Tiff(std::string_view data) : d_(data) {
  if (d_.size() < 8) throw Failure{"EXIF: TIFF header cut short"};
  if (d_.substr(0, 4) == std::string_view("II*\0", 4)) little_ = true;
  else if (d_.substr(0, 4) == std::string_view("MM\0*", 4)) little_ = false;
  else throw Failure{"EXIF: not a TIFF header"};
}

void Tiff::need(size_t at, size_t n) const {
  if (at > d_.size() || n > d_.size() - at) throw Failure{"EXIF: offset beyond the segment"};
}

uint8_t Tiff::u8(size_t at) const {
  need(at, 1);
  return static_cast<uint8_t>(d_[at]);
}

uint16_t Tiff::u16(size_t at) const {
  need(at, 2);
  const auto b = [&](size_t k) { return static_cast<uint16_t>(static_cast<uint8_t>(d_[at + k])); };
  return little_ ? static_cast<uint16_t>(b(0) | b(1) << 8) : static_cast<uint16_t>(b(0) << 8 | b(1));
}

uint32_t Tiff::u32(size_t at) const {
  need(at, 4);
  const auto b = [&](size_t k) { return static_cast<uint32_t>(static_cast<uint8_t>(d_[at + k])); };
  return little_ ? b(0) | b(1) << 8 | b(2) << 16 | b(3) << 24 : b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
}

double rational(const Tiff& t, size_t at, const char* what) {
  const uint32_t num = t.u32(at), den = t.u32(at + 4);
  if (den == 0) throw Failure{std::string("EXIF: ") + what + " with denominator 0"};
  return static_cast<double>(num) / den;
}

uint32_t whole_number(const Tiff& t, const Entry& e, const char* what) {
  if (e.count < 1 || (e.type != kShort && e.type != kLong)) throw Failure{std::string("EXIF: ") + what + " that is not a whole number"};
  return e.type == kShort ? t.u16(e.value_at) : t.u32(e.value_at);
}

std::string_view tiff_block(std::string_view jpeg) {
  if (jpeg.size() < 4 || static_cast<uint8_t>(jpeg[0]) != 0xFF || static_cast<uint8_t>(jpeg[1]) != 0xD8) throw Failure{"not a JPEG"};
  size_t at = 2;
  // Marker segments up to the image data: FF xx, then a 2-byte big-endian length that counts itself.
  while (at + 4 <= jpeg.size()) {
    if (static_cast<uint8_t>(jpeg[at]) != 0xFF) throw Failure{"no EXIF (broken marker)"};
    const uint8_t marker = static_cast<uint8_t>(jpeg[at + 1]);
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0xDA || marker == 0xD9) break;  // image data or end: EXIF comes before
    const size_t length = static_cast<size_t>(static_cast<uint8_t>(jpeg[at + 2])) << 8 | static_cast<uint8_t>(jpeg[at + 3]);
    if (length < 2 || at + 2 + length > jpeg.size()) throw Failure{"no EXIF (a segment runs past the end)"};
    const std::string_view payload = jpeg.substr(at + 4, length - 2);
    if (marker == 0xE1 && payload.size() >= 6 && payload.substr(0, 6) == std::string_view("Exif\0\0", 6)) return payload.substr(6);
    at += 2 + length;
  }
  throw Failure{"no EXIF"};
}

std::string read_head(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read");
  std::string head(256 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

}  // namespace lc2wf::exif
