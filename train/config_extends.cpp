#include "train/config_extends.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "core/util/input_file.h"

namespace lc2wf {
namespace fs = std::filesystem;

namespace {

constexpr std::uintmax_t kMaxConfigBytes = std::uintmax_t{64} << 20;  // configs are a few KB
constexpr size_t kMaxChain = 64;  // far beyond any real chain; bounds a chain of distinct files

nlohmann::json parse_config_file(const fs::path& path) {
  const std::string text = read_input_file(path, kMaxConfigBytes);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // a syntax error, or a number that overflows a double (1e309)
    throw std::runtime_error(path.string() + ": not valid JSON: " + e.what());
  }
}

std::string chain_text(const std::vector<fs::path>& chain, const fs::path& last) {
  std::string text;
  for (const fs::path& p : chain) text += p.string() + " -> ";
  return text + last.string();
}

// `chain` holds the files already being resolved (outermost first), as canonical paths for the cycle check
// and as written for the messages.
nlohmann::json resolve(const fs::path& path, std::vector<fs::path>& canonical_chain, std::vector<fs::path>& chain) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (chain.empty()) throw std::runtime_error(path.string() + ": no such config file");
    throw std::runtime_error(chain.back().string() + ": \"extends\" names " + path.string() + ", which does not exist");
  }
  const fs::path canonical = fs::weakly_canonical(path, ec);
  for (const fs::path& seen : canonical_chain)
    if (seen == canonical)
      throw std::runtime_error(chain.front().string() + ": \"extends\" cycle: " + chain_text(chain, path));
  if (chain.size() >= kMaxChain) throw std::runtime_error(chain.front().string() + ": \"extends\" chain longer than 64 files");
  nlohmann::json j = parse_config_file(path);
  if (!j.is_object() || !j.contains("extends")) return j;
  const nlohmann::json& base_name = j["extends"];
  if (!base_name.is_string() || base_name.get<std::string>().empty())
    throw std::runtime_error(path.string() + ": \"extends\" must name a config file (a path relative to this file)");
  const fs::path base_path = path.parent_path() / base_name.get<std::string>();
  canonical_chain.push_back(canonical);
  chain.push_back(path);
  nlohmann::json base = resolve(base_path, canonical_chain, chain);
  canonical_chain.pop_back();
  chain.pop_back();
  j.erase("extends");
  return merge_config_json(std::move(base), j);
}

}  // namespace

nlohmann::json merge_config_json(nlohmann::json base, const nlohmann::json& overrides) {
  if (!base.is_object() || !overrides.is_object()) return overrides;
  for (auto it = overrides.begin(); it != overrides.end(); ++it)
    base[it.key()] = base.contains(it.key()) ? merge_config_json(std::move(base[it.key()]), it.value()) : it.value();
  return base;
}

nlohmann::json resolve_config_json(const fs::path& path) {
  std::vector<fs::path> canonical_chain, chain;
  return resolve(path, canonical_chain, chain);
}

}  // namespace lc2wf
