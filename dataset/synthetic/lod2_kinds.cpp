#include "dataset/synthetic/lod2_kinds.h"

#include <cmath>
#include <stdexcept>

namespace lc2wf {
namespace {

constexpr std::array<const char*, kLod2KindCount> kNames = {
    "flat",   "flat_multi", "gabled",  "hipped",  "pyramid",   "shed",    "mansard",    "gambrel", "saw_tooth",
    "multi_part", "l_shape", "t_shape", "u_shape", "courtyard", "dormers", "row_houses", "tower",   "large_block"};

}  // namespace

const char* lod2_kind_name(Lod2Kind kind) { return kNames.at(static_cast<size_t>(kind)); }

std::optional<Lod2Kind> parse_lod2_kind(std::string_view name) {
  for (int i = 0; i < kLod2KindCount; ++i)
    if (name == kNames[i]) return static_cast<Lod2Kind>(i);
  return std::nullopt;
}

void Lod2KindWeights::Check() const {
  double total = 0;
  for (int i = 0; i < kLod2KindCount; ++i) {
    if (!(std::isfinite(weight[i]) && weight[i] >= 0))
      throw std::invalid_argument(std::string("Lod2KindWeights: the weight of ") + kNames[i] + " must be a number >= 0");
    total += weight[i];
  }
  if (!(total > 0)) throw std::invalid_argument("Lod2KindWeights: at least one kind needs a weight > 0");
}

Lod2Kind Lod2KindWeights::pick(double u) const {
  double total = 0;
  for (double w : weight) total += w;
  double at = u * total;
  int last = 0;
  for (int i = 0; i < kLod2KindCount; ++i) {
    if (weight[i] <= 0) continue;
    last = i;
    if (at < weight[i]) return static_cast<Lod2Kind>(i);
    at -= weight[i];
  }
  return static_cast<Lod2Kind>(last);
}

Lod2KindWeights parse_lod2_kind_weights(const std::string& spec) {
  Lod2KindWeights w;
  if (spec == "all") return w;
  w.weight.fill(0.0);
  size_t start = 0;
  while (start <= spec.size()) {
    const size_t end = std::min(spec.find(',', start), spec.size());
    const std::string entry = spec.substr(start, end - start);
    const size_t colon = entry.find(':');
    const std::string name = entry.substr(0, colon);
    const auto kind = parse_lod2_kind(name);
    if (!kind) {
      std::string known;
      for (const char* n : kNames) known += (known.empty() ? "" : ", ") + std::string(n);
      throw std::invalid_argument("unknown building kind '" + name + "' (kinds: " + known + ")");
    }
    double value = 1.0;
    if (colon != std::string::npos) {
      const std::string number = entry.substr(colon + 1);
      size_t used = 0;
      try {
        value = std::stod(number, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (number.empty() || used != number.size() || !std::isfinite(value) || value < 0)
        throw std::invalid_argument("weight of '" + name + "' must be a number >= 0, got '" + number + "'");
    }
    w[*kind] = value;
    start = end + 1;
  }
  w.Check();
  return w;
}

}  // namespace lc2wf
