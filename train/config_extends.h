// Configs that extend another: `"extends": "base.json"` (a path relative to the extending file) plus the keys
// that differ. Objects merge key by key; any other value (numbers, strings, arrays) replaces the base's.
// Chains are allowed; a cycle or a missing file is an error naming the file.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace lc2wf {

// `base` with `overrides` merged into it: objects key by key, everything else replaced.
nlohmann::json merge_config_json(nlohmann::json base, const nlohmann::json& overrides);

// The JSON of `path` with its `extends` chain resolved (no "extends" key left). Throws std::runtime_error
// "<file>: <problem>" for an unreadable file, bad JSON, a non-string "extends", a missing base or a cycle.
nlohmann::json resolve_config_json(const std::filesystem::path& path);

}  // namespace lc2wf
