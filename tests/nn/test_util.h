// Helpers shared by the nn tests: fixture paths, prefix selection from safetensors files, tolerance
// checks and the deterministic "hashed" weights that tools/make_golden.py also produces.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "core/rng.h"
#include "core/tensor.h"
#include "core/util/fnv1a.h"
#include "nn/module.h"
#include "nn/safetensors.h"

namespace lc2wf::test {

inline std::string fixture(const std::string& name) { return std::string(LC2WF_SOURCE_DIR) + "/tests/data/nn/" + name; }

// Tensors whose name starts with `prefix`, with the prefix removed.
inline std::map<std::string, Tensor> with_prefix(const SafetensorsFile& file, const std::string& prefix) {
  std::map<std::string, Tensor> out;
  for (const auto& [name, t] : file.tensors)
    if (name.rfind(prefix, 0) == 0) out[name.substr(prefix.size())] = t;
  return out;
}

inline const Tensor& get(const SafetensorsFile& file, const std::string& name) {
  auto it = file.tensors.find(name);
  if (it == file.tensors.end()) throw std::runtime_error("fixture lacks tensor " + name);
  return it->second;
}

// max|a - b| <= rel * max|ref| + abs: relative to the tensor's scale, with a small absolute floor for
// gradients that are zero in exact arithmetic (biases in front of a BatchNorm).
inline ::testing::AssertionResult close(const Tensor& actual, const Tensor& ref, double rel = 1e-4, double abs = 1e-6) {
  if (actual.shape() != ref.shape())
    return ::testing::AssertionFailure() << "shape " << shape_str(actual.shape()) << " vs " << shape_str(ref.shape());
  const std::vector<double> a = actual.to_vector(), b = ref.to_vector();
  double scale = 0.0, err = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i])) return ::testing::AssertionFailure() << "non-finite value at " << i;
    scale = std::max(scale, std::abs(b[i]));
    err = std::max(err, std::abs(a[i] - b[i]));
  }
  if (err <= rel * scale + abs) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max abs error " << err << " exceeds " << rel << " * " << scale << " + " << abs;
}

// Same rule as hashed_value() in tools/make_golden.py.
inline void fill_hashed(Module& module) {
  for (auto& [name, t] : module.state_dict()) {
    double lo = 0.5, hi = 1.5;
    auto ends_with = [&](const std::string& s) {
      return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
    };
    if (ends_with("running_var")) lo = 0.5, hi = 1.5;
    else if (ends_with("running_mean")) lo = -0.2, hi = 0.2;
    else if (t.dim() == 2) hi = 1.0 / std::sqrt(static_cast<double>(t.size(1))), lo = -hi;
    else if (ends_with("bias")) lo = -0.1, hi = 0.1;
    const Rng rng(fnv1a64(name));
    float* d = t.data<float>();
    for (int64_t i = 0; i < t.numel(); ++i)
      d[i] = static_cast<float>(lo + (hi - lo) * static_cast<double>(rng.uniform_f(static_cast<uint64_t>(i))));
  }
}

}  // namespace lc2wf::test
