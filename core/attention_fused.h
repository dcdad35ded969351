// The fused float attention kernel (AVX2 + FMA; softmax rows on AVX-512 where the build has it): forward
// and backward of every (batch item, head) in one cache-resident pass each (a forward pass over thousands
// of keys in blocks of query rows); the reference kernel in ops_attention.cpp covers the other cases.
#pragma once

#include <cstdint>

#include "core/attention_layout.h"

namespace lc2wf::attention {

// True when this build has the kernel and the shape fits it (key count and head width multiples of 8).
bool fused_supported(int64_t Lk, int64_t D);

// The key count a shape the kernel does not take is padded to (masked keys) at inference: a multiple of the
// softmax rows' lane width, 16 where the build has AVX-512.
int64_t padded_key_count(int64_t Lk);

// What the forward pass keeps for the backward pass instead of the probabilities: per query row the
// shifted maximum and the inverse sum of the softmax (2 floats), and with dropout the keep bits
// (Lk / 8 bytes, the counter-based mask drawn once).
inline int64_t fused_stats_floats(const Shape4& s) { return s.B * s.H * s.Lq * 2; }
inline int64_t fused_keep_bytes(const Shape4& s) { return s.B * s.H * s.Lq * (s.Lk / 8); }

// o = dropout(softmax(q k^T * scale, masked keys excluded)) v. probs (B, H, Lq, Lk), stats and
// keep_bits may be null.
void fused_forward(const Shape4& s, const float* q, Layout lq, const float* k, Layout lk, const float* v, Layout lv,
                   float* o, Layout lo, const uint8_t* mask, float scale, const DropoutPlan& drop, float* probs,
                   float* stats, uint8_t* keep_bits);

// dq, dk, dv of every head from the output gradient go and what fused_forward kept.
void fused_backward(const Shape4& s, const float* q, Layout lq, const float* k, Layout lk, const float* v, Layout lv,
                    const float* go, Layout lo, const uint8_t* mask, float scale, const DropoutPlan& drop,
                    const float* stats, const uint8_t* keep_bits, float* dq, Layout ldq, float* dk, Layout ldk,
                    float* dv, Layout ldv);

}  // namespace lc2wf::attention
