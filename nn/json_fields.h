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

#include "core/util/json_number.h"

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

  // Field-visitor form (see fields_from_json): nested config structs go through their own from_json.
  template <class T>
  void operator()(const char* key, T& out) {
    if constexpr (requires(const nlohmann::json& j, const std::string& w, T base) { T::from_json(j, w, base); })
      read_struct(key, out);
    else
      read(key, out);
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
    if constexpr (std::is_arithmetic_v<T>) {
      return json_exact<T>(v, name);  // no silent narrowing (4294967298 -> 2 in an int)
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

// Writes a struct's fields as a JSON object; nested config structs go through their own to_json.
class JsonWriter {
 public:
  template <class T>
  void operator()(const char* key, const T& value) {
    if constexpr (requires { value.to_json(); })
      json_[key] = value.to_json();
    else
      json_[key] = value;
  }
  nlohmann::json take() { return std::move(json_); }

 private:
  nlohmann::json json_ = nlohmann::json::object();
};

// Config structs list their keys once, in `template <class S, class V> static void fields(S& self, V& v)`
// calling v("key", self.member) per field; these two turn that one list into to_json and from_json.
template <class T>
nlohmann::json fields_to_json(const T& config) {
  JsonWriter writer;
  T::fields(config, writer);
  return writer.take();
}

template <class T>
T fields_from_json(const nlohmann::json& j, const std::string& where, T config) {
  JsonFields reader(j, where);
  T::fields(config, reader);
  reader.finish();
  return config;
}

}  // namespace lc2wf
