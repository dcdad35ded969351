// Exact JSON numbers: nlohmann's get<int>() turns 4294967298 into 2, 0.7 into 0, true into 1 and 300 into
// 44 for a byte without a word. These read a value only when it fits the target type exactly, and name the
// field otherwise. Header-only; users link nlohmann_json themselves (dataset, nn).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace lc2wf {

template <class T>
T json_exact(const nlohmann::json& v, const std::string& field) {
  if constexpr (std::is_same_v<T, bool>) {
    if (!v.is_boolean()) throw std::invalid_argument(field + ": expected true or false");
    return v.get<bool>();
  } else if constexpr (std::is_integral_v<T>) {
    if (!v.is_number_integer()) throw std::invalid_argument(field + ": expected an integer, got " + v.dump());
    const bool fits = v.is_number_unsigned() ? std::in_range<T>(v.get<std::uint64_t>()) : std::in_range<T>(v.get<std::int64_t>());
    if (!fits) throw std::invalid_argument(field + ": " + v.dump() + " is out of range");
    return v.is_number_unsigned() ? static_cast<T>(v.get<std::uint64_t>()) : static_cast<T>(v.get<std::int64_t>());
  } else {
    static_assert(std::is_floating_point_v<T>, "json_exact reads booleans, integers and floating-point numbers");
    if (!v.is_number()) throw std::invalid_argument(field + ": expected a number, got " + v.dump());
    return v.get<T>();
  }
}

template <class T>
std::vector<T> json_exact_array(const nlohmann::json& v, const std::string& field) {
  if (!v.is_array()) throw std::invalid_argument(field + ": expected an array");
  std::vector<T> out;
  out.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i) out.push_back(json_exact<T>(v[i], field + "[" + std::to_string(i) + "]"));
  return out;
}

}  // namespace lc2wf
