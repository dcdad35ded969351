#include "core/matmul_precision.h"

#include <atomic>
#include <stdexcept>

namespace lc2wf {
namespace {

std::atomic<MatmulPrecision> g_precision{MatmulPrecision::kFp32};

}  // namespace

MatmulPrecision matmul_precision() { return g_precision.load(std::memory_order_relaxed); }

void set_matmul_precision(MatmulPrecision precision) { g_precision.store(precision, std::memory_order_relaxed); }

MatmulPrecision parse_matmul_precision(const std::string& text, const std::string& what) {
  if (text == "fp32") return MatmulPrecision::kFp32;
  if (text == "bf16") return MatmulPrecision::kBf16;
  if (text == "auto") return cpu_has_bf16_dot_product() ? MatmulPrecision::kBf16 : MatmulPrecision::kFp32;
  throw std::invalid_argument(what + " must be \"fp32\", \"bf16\" or \"auto\", got \"" + text + "\"");
}

std::string to_string(MatmulPrecision precision) { return precision == MatmulPrecision::kBf16 ? "bf16" : "fp32"; }

bool cpu_has_bf16_dot_product() {
#if defined(__x86_64__) && defined(__GNUC__)
  return __builtin_cpu_supports("avx512bf16");
#else
  return false;
#endif
}

}  // namespace lc2wf
