// How large matrix products round their operands: fp32 (default) or bf16 operands with fp32 accumulation
// (mixed precision, as CPU autocast does). Process-wide, because the worker threads of one product must agree.
#pragma once

#include <string>

namespace lc2wf {

enum class MatmulPrecision { kFp32, kBf16 };

MatmulPrecision matmul_precision();
void set_matmul_precision(MatmulPrecision precision);

// "fp32", "bf16" or "auto" (bf16 where the CPU has a bf16 dot product, else fp32: a bf16 training run matched
// fp32 within run-to-run noise, train/README.md); anything else throws std::invalid_argument naming `what`
// and the value.
MatmulPrecision parse_matmul_precision(const std::string& text, const std::string& what);
std::string to_string(MatmulPrecision precision);

// Whether this CPU has a bf16 dot-product instruction (AVX512-BF16). Without it bf16 products are
// emulated: fp32 kernels on operands rounded to bf16, the same numbers but no speed-up.
bool cpu_has_bf16_dot_product();

// Sets a precision for a scope (tests, benchmarks) and restores the previous one.
class MatmulPrecisionGuard {
 public:
  explicit MatmulPrecisionGuard(MatmulPrecision precision) : previous_(matmul_precision()) {
    set_matmul_precision(precision);
  }
  ~MatmulPrecisionGuard() { set_matmul_precision(previous_); }
  MatmulPrecisionGuard(const MatmulPrecisionGuard&) = delete;
  MatmulPrecisionGuard& operator=(const MatmulPrecisionGuard&) = delete;

 private:
  MatmulPrecision previous_;
};

}  // namespace lc2wf
