// bfloat16 rounding: the 8 exponent bits of fp32 and 7 of its 23 mantissa bits, rounded to nearest even.
// Values are kept as fp32 with the low 16 bits zero, so a product of two is exact in fp32 and an fp32
// accumulation of such products is what a bf16 dot-product instruction computes.
#pragma once

#include <bit>
#include <cstdint>

namespace lc2wf {

inline float round_to_bf16(float x) {
  uint32_t u = std::bit_cast<uint32_t>(x);
  // NaN stays NaN (quiet bit set, so clearing the low half cannot turn it into an infinity).
  if ((u & 0x7fffffffu) > 0x7f800000u) return std::bit_cast<float>((u | 0x00400000u) & 0xffff0000u);
  u += 0x7fffu + ((u >> 16) & 1u);  // ties to even; overflow past the largest bf16 carries into infinity
  return std::bit_cast<float>(u & 0xffff0000u);
}

}  // namespace lc2wf
