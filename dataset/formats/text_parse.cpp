#include "dataset/formats/text_parse.h"

#include <charconv>
#include <cmath>

namespace lc2wf {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

std::vector<std::string_view> split_tokens(std::string_view s, std::string_view delims) {
  std::vector<std::string_view> out;
  size_t pos = 0;
  while (pos < s.size()) {
    const size_t next = s.find_first_of(delims, pos);
    const size_t end = next == std::string_view::npos ? s.size() : next;
    const std::string_view tok = trim(s.substr(pos, end - pos));
    if (!tok.empty()) out.push_back(tok);
    if (next == std::string_view::npos) break;
    pos = next + 1;
  }
  return out;
}

std::optional<double> parse_finite_double(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<long long> parse_int(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  long long v = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return v;
}

}  // namespace lc2wf
