// Small strict number parsing helpers for the text readers (no locale, no silent partial parses).
#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace lc2wf {

std::string_view trim(std::string_view s);
// Splits on any of `delims`, dropping empty tokens.
std::vector<std::string_view> split_tokens(std::string_view s, std::string_view delims);
// Whole-token parses; nullopt on junk, overflow or (for doubles) NaN/Inf.
std::optional<double> parse_finite_double(std::string_view token);
std::optional<long long> parse_int(std::string_view token);

}  // namespace lc2wf
