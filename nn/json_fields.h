// Strict JSON object reading for config structs: every key must be known, every value must have the
// right type, and errors name the offending field ("junction.lpt.hidden_dim: expected an integer").
#pragma once

#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

namespace lc2wf {

class JsonFields {
 public:
  JsonFields(const nlohmann::json& object, std::string where) : object_(object), where_(std::move(where)) {
    if (!object_.is_object()) throw std::invalid_argument(where_ + ": expected a JSON object");
  }

  // Reads `key` into out when present (absent keys keep the default).
  template <class T>
  void read(const char* key, T& out) {
    seen_.insert(key);
    auto it = object_.find(key);
    if (it != object_.end()) out = convert<T>(*it, field(key));
  }

  // Reads a nested config struct with its own from_json(json, where).
  template <class T>
  void read_struct(const char* key, T& out) {
    seen_.insert(key);
    auto it = object_.find(key);
    if (it != object_.end()) out = T::from_json(*it, field(key), out);
  }

  // Throws on the first key no read() asked for.
  void finish() const {
    for (auto it = object_.begin(); it != object_.end(); ++it)
      if (!seen_.count(it.key())) throw std::invalid_argument(where_ + ": unknown key '" + it.key() + "'");
  }

 private:
  std::string field(const char* key) const { return where_.empty() ? key : where_ + "." + key; }

  template <class T>
  static T convert(const nlohmann::json& v, const std::string& name) {
    if constexpr (std::is_same_v<T, bool>) {
      if (!v.is_boolean()) throw std::invalid_argument(name + ": expected true or false");
      return v.get<bool>();
    } else if constexpr (std::is_integral_v<T>) {
      if (!v.is_number_integer()) throw std::invalid_argument(name + ": expected an integer");
      return v.get<T>();
    } else if constexpr (std::is_floating_point_v<T>) {
      if (!v.is_number()) throw std::invalid_argument(name + ": expected a number");
      return v.get<T>();
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (!v.is_string()) throw std::invalid_argument(name + ": expected a string");
      return v.get<std::string>();
    } else {
      if (!v.is_array()) throw std::invalid_argument(name + ": expected an array");
      T out;
      for (size_t i = 0; i < v.size(); ++i)
        out.push_back(convert<typename T::value_type>(v[i], name + "[" + std::to_string(i) + "]"));
      return out;
    }
  }

  const nlohmann::json& object_;
  std::string where_;
  std::set<std::string> seen_;
};

}  // namespace lc2wf
