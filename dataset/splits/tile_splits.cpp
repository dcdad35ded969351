#include "dataset/splits/tile_splits.h"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

namespace lc2wf {

void TileSplitRule::Check() const {
  if (!(tile_size_m > 0 && std::isfinite(tile_size_m))) throw std::invalid_argument("tile_size_m must be > 0");
  if (!(test_share >= 0 && val_share >= 0 && test_share + val_share < 1))
    throw std::invalid_argument("test_share and val_share must be >= 0 with a sum below 1");
}

std::string tile_key(const TileSplitEntry& e, double tile_size_m) {
  const auto cell = [&](double v) { return std::to_string(static_cast<long long>(std::floor(v / tile_size_m))); };
  return e.file + "#" + cell(e.x) + "," + cell(e.y);
}

Splits make_tile_splits(const std::vector<TileSplitEntry>& entries, const TileSplitRule& rule) {
  rule.Check();
  std::set<std::string> names;
  // source -> tile -> building names
  std::map<std::string, std::map<std::string, std::vector<std::string>>> tiles;
  std::map<std::string, size_t> source_size;
  for (const TileSplitEntry& e : entries) {
    if (!names.insert(e.name).second) throw std::invalid_argument("make_tile_splits: duplicate building name " + e.name);
    if (!std::isfinite(e.x) || !std::isfinite(e.y) || std::abs(e.x) > 1e12 || std::abs(e.y) > 1e12)
      throw std::invalid_argument("make_tile_splits: building " + e.name + " has no finite position");
    tiles[e.source][tile_key(e, rule.tile_size_m)].push_back(e.name);
    ++source_size[e.source];
  }
  Splits s;
  for (auto& [source, by_tile] : tiles) {
    std::vector<std::pair<uint64_t, std::string>> order;
    for (const auto& [key, members] : by_tile) order.emplace_back(split_key(key, rule.seed), key);
    std::sort(order.begin(), order.end());
    const double total = static_cast<double>(source_size[source]);
    size_t test = 0, val = 0;
    for (const auto& [hash, key] : order) {
      const std::vector<std::string>& members = by_tile[key];
      std::vector<std::string>* list = &s.train;
      if (test < rule.test_share * total) {
        list = &s.test;
        test += members.size();
      } else if (val < rule.val_share * total) {
        list = &s.val;
        val += members.size();
      }
      list->insert(list->end(), members.begin(), members.end());
    }
  }
  for (auto* l : {&s.train, &s.val, &s.test}) std::sort(l->begin(), l->end());
  return s;
}

std::string source_of(const std::string& relative_path, const std::vector<std::string>& rules) {
  for (const std::string& r : rules) {
    const size_t eq = r.rfind('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == r.size())
      throw std::invalid_argument("source rule '" + r + "' is not PATTERN=SOURCE");
    if (fnmatch(r.substr(0, eq).c_str(), relative_path.c_str(), 0) == 0) return r.substr(eq + 1);
  }
  return "";
}

}  // namespace lc2wf
