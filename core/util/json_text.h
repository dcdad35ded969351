// JSON text that never throws on names: building and image names come from file names, which need not be
// UTF-8, and nlohmann's dump() throws on such strings. Invalid bytes are written as U+FFFD. Header-only.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace lc2wf {

inline std::string json_text(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace lc2wf
