#include "dataset/splits/splits.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/util/fnv1a.h"
#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/sampling/rng.h"
#include "dataset/formats/text_parse.h"

namespace lc2wf {

void SplitRule::Check() const {
  if (test_count < 0) throw std::invalid_argument("SplitRule.test_count must be >= 0");
  if (val_count < 0) throw std::invalid_argument("SplitRule.val_count must be >= 0");
}

uint64_t split_key(const std::string& name, uint64_t seed) {
  return mix_seed(fnv1a64(name), seed);
}

Splits make_splits(const std::vector<std::string>& names, const SplitRule& rule) {
  rule.Check();
  if (std::set<std::string>(names.begin(), names.end()).size() != names.size()) {
    throw std::invalid_argument("make_splits: duplicate building names");
  }
  if (names.size() < static_cast<size_t>(rule.test_count) + rule.val_count) {
    throw std::invalid_argument("make_splits: fewer names than test_count + val_count");
  }
  std::vector<std::pair<uint64_t, std::string>> keyed;
  for (const auto& n : names) keyed.emplace_back(split_key(n, rule.seed), n);
  std::sort(keyed.begin(), keyed.end());
  Splits s;
  for (size_t i = 0; i < keyed.size(); ++i) {
    auto& list = i < static_cast<size_t>(rule.test_count)                   ? s.test
                 : i < static_cast<size_t>(rule.test_count + rule.val_count) ? s.val
                                                                             : s.train;
    list.push_back(keyed[i].second);
  }
  for (auto* l : {&s.train, &s.val, &s.test}) std::sort(l->begin(), l->end());
  return s;
}

std::vector<std::string> parse_name_list(const std::string& text, const std::string& src) {
  std::istringstream in(text);
  std::vector<std::string> out;
  std::set<std::string> seen;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view t = trim(line);
    if (t.empty() || t.front() == '#') continue;
    if (t.find_first_of(" \t") != std::string_view::npos) throw DataError(src, line_no, "a name must not contain whitespace");
    if (t.find_first_of("/\\") != std::string_view::npos)
      throw DataError(src, line_no, "'" + std::string(t) + "' is a path; expected a building name");
    if (t == "." || t == ".." || t.find('\0') != std::string_view::npos)  // would name a folder or a cut-off path
      throw DataError(src, line_no, "'" + std::string(t.substr(0, t.find('\0'))) + "' is not a building name");
    if (!seen.insert(std::string(t)).second)
      throw DataError(src, line_no, "duplicate building name '" + std::string(t) + "'");
    out.emplace_back(t);
  }
  return out;
}

std::vector<std::string> read_name_list(const std::filesystem::path& path) { return parse_name_list(read_file(path), path.string()); }

void write_name_list(const std::filesystem::path& path, const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += n + "\n";
  write_file_atomic(path, s);
}

}  // namespace lc2wf
