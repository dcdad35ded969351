// The train / validation / test split: a pure function of the building names and a seed, so anyone can
// recompute and check the published lists in configs/splits/.
// Rule: key(name) = mix(FNV-1a-64(name), seed); sort names by (key, name); the first `test_count` are
// test, the next `val_count` validation, the rest train. Each list is written sorted by name.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lc2wf {

struct SplitRule {
  uint64_t seed = 1555;  // the release's training seed
  int test_count = 757;  // the paper's test-set size
  int val_count = 200;   // carved from the 2,826 non-test buildings for model selection
  void Check() const;
};

struct Splits {
  std::vector<std::string> train, val, test;
};

uint64_t split_key(const std::string& name, uint64_t seed);

// Throws std::invalid_argument on duplicate names or fewer names than test + val.
Splits make_splits(const std::vector<std::string>& names, const SplitRule& rule = {});

// One name per line; blank lines and '#' comments ignored, spaces trimmed. Throws DataError naming file
// and line on names with whitespace or path separators, and on duplicates.
std::vector<std::string> read_name_list(const std::filesystem::path& path);
// The same from the file's text; `src` names the source in errors.
std::vector<std::string> parse_name_list(const std::string& text, const std::string& src);
void write_name_list(const std::filesystem::path& path, const std::vector<std::string>& names);

}  // namespace lc2wf
