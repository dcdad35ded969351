// matmul (2-D, batched with broadcast batch dims, (...,M,K)x(K,N)) and the fused linear layer.
#include "core/autograd.h"
#include "core/gemm.h"
#include "core/kernels.h"
#include "core/ops.h"
#include "core/small_gemm.h"

namespace lc2wf {

namespace {

// Below this many multiply-adds per batch item, batches run in parallel with one serial GEMM each.
constexpr int64_t kSmallGemm = 1 << 21;

// linear with at most this many input features takes the direct small-K kernel, in row blocks.
constexpr int64_t kSmallK = 16;
constexpr int64_t kSmallKRows = 256;

// Batched op(A) op(B) over contiguous (nb, rows, cols) tensors; no autograd.
Tensor bmm_raw(const Tensor& A, const Tensor& B, bool ta, bool tb) {
  int64_t nb = A.size(0);
  int64_t M = ta ? A.size(2) : A.size(1);
  int64_t K = ta ? A.size(1) : A.size(2);
  int64_t N = tb ? B.size(1) : B.size(2);
  Tensor C = Tensor::empty({nb, M, N}, A.dtype());
  dispatch_float(A.dtype(), "matmul", [&](auto tag) {
    using T = decltype(tag);
    const T* pa = ptr<T>(A);
    const T* pb = ptr<T>(B);
    T* pc = ptr<T>(C);
    int64_t sa = A.size(1) * A.size(2), sb = B.size(1) * B.size(2), sc = M * N;
    int64_t lda = A.size(2), ldb = B.size(2);
    if (M * N * K >= kSmallGemm) {
      for (int64_t i = 0; i < nb; ++i)
        gemm<T>(ta, tb, M, N, K, pa + i * sa, lda, pb + i * sb, ldb, pc + i * sc, N, false);
    } else {
      int64_t grain = std::max<int64_t>(1, kSmallGemm / std::max<int64_t>(1, M * N * K));
      parallel_for_work(nb, grain, M * N * std::max<int64_t>(K, 1), [&](int64_t b0, int64_t b1) {
        for (int64_t i = b0; i < b1; ++i)
          gemm_serial<T>(ta, tb, M, N, K, pa + i * sa, lda, pb + i * sb, ldb, pc + i * sc, N, false);
      });
    }
    return 0;
  });
  return C;
}

Tensor matmul_2d_weight(const Tensor& a, const Tensor& b) {
  int64_t K = a.size(-1), N = b.size(1);
  int64_t M = prod(a.shape(), 0, a.dim() - 1);
  Shape out_shape = a.shape();
  out_shape.back() = N;
  Tensor out = Tensor::empty(out_shape, a.dtype());
  dispatch_float(a.dtype(), "matmul", [&](auto tag) {
    using T = decltype(tag);
    gemm<T>(false, false, M, N, K, ptr<T>(a), K, ptr<T>(b), N, ptr<T>(out), N, false);
    return 0;
  });
  if (needs_grad({&a, &b})) {
    bool ga = a.requires_grad(), gb = b.requires_grad();
    Tensor ad = gb ? a.detach() : Tensor();
    Tensor bd = ga ? b.detach() : Tensor();
    record(out, "matmul", {a, b}, [ad, bd, ga, gb, sa = a.shape(), M, N, K](const Tensor& g) -> std::vector<Tensor> {
      Tensor da, db;
      dispatch_float(g.dtype(), "matmul backward", [&](auto tag) {
        using T = decltype(tag);
        if (ga) {
          da = Tensor::empty(sa, g.dtype());
          gemm<T>(false, true, M, K, N, ptr<T>(g), N, ptr<T>(bd), N, ptr<T>(da), K, false);
        }
        if (gb) {
          db = Tensor::empty({K, N}, g.dtype());
          gemm<T>(true, false, K, N, M, ptr<T>(ad), K, ptr<T>(g), N, ptr<T>(db), N, false);
        }
        return 0;
      });
      return {da, db};
    });
  }
  return out;
}

}  // namespace

Tensor matmul(const Tensor& a, const Tensor& b) {
  check_float(a, "matmul", "a");
  check_float(b, "matmul", "b");
  check_same_dtype(a, b, "matmul");
  if (a.dim() < 2 || b.dim() < 2)
    throw_arg("matmul: both operands need at least 2 dimensions, got " + shape_str(a.shape()) + " and " +
              shape_str(b.shape()));
  if (a.size(-1) != b.size(-2))
    throw_arg("matmul: inner dimensions differ: " + shape_str(a.shape()) + " x " + shape_str(b.shape()));
  if (b.dim() == 2) return matmul_2d_weight(a, b);

  Shape ba(a.shape().begin(), a.shape().end() - 2), bb(b.shape().begin(), b.shape().end() - 2);
  Shape batch = broadcast_shapes(ba, bb);
  int64_t M = a.size(-2), K = a.size(-1), N = b.size(-1);
  Shape full_a = batch, full_b = batch;
  full_a.insert(full_a.end(), {M, K});
  full_b.insert(full_b.end(), {K, N});
  // Broadcast batch dims by an explicit (differentiable) expand; its backward sums them back.
  Tensor ae = a.shape() == full_a ? a : expand(a, full_a);
  Tensor be = b.shape() == full_b ? b : expand(b, full_b);
  int64_t nb = shape_numel(batch);
  Tensor a3 = ae.detach().reshape({nb, M, K});
  Tensor b3 = be.detach().reshape({nb, K, N});
  Shape out_shape = batch;
  out_shape.insert(out_shape.end(), {M, N});
  Tensor out = bmm_raw(a3, b3, false, false).reshape(out_shape);
  if (needs_grad({&ae, &be})) {
    bool ga = ae.requires_grad(), gb = be.requires_grad();
    Tensor ad = gb ? a3 : Tensor();
    Tensor bd = ga ? b3 : Tensor();
    record(out, "matmul", {ae, be}, [ad, bd, ga, gb, full_a, full_b, nb, M, N](const Tensor& g) -> std::vector<Tensor> {
      Tensor g3 = g.reshape({nb, M, N});
      return {ga ? bmm_raw(g3, bd, false, true).reshape(full_a) : Tensor(),
              gb ? bmm_raw(ad, g3, true, false).reshape(full_b) : Tensor()};
    });
  }
  return out;
}

Tensor linear(const Tensor& x, const Tensor& weight, const Tensor& bias) {
  check_float(x, "linear", "x");
  check_float(weight, "linear", "weight");
  check_same_dtype(x, weight, "linear");
  if (weight.dim() != 2 || x.dim() < 1 || x.size(-1) != weight.size(1))
    throw_arg("linear: input " + shape_str(x.shape()) + " does not match weight " + shape_str(weight.shape()) +
              " (expected (..., in) and (out, in))");
  int64_t in = weight.size(1), outf = weight.size(0);
  if (bias.defined()) {
    check_float(bias, "linear", "bias");
    check_same_dtype(x, bias, "linear");
    if (bias.shape() != Shape{outf})
      throw_arg("linear: bias " + shape_str(bias.shape()) + " does not match weight " + shape_str(weight.shape()));
  }
  int64_t M = prod(x.shape(), 0, x.dim() - 1);
  Shape out_shape = x.shape();
  out_shape.back() = outf;
  Tensor out = Tensor::empty(out_shape, x.dtype());
  dispatch_float(x.dtype(), "linear", [&](auto tag) {
    using T = decltype(tag);
    const T* pb = bias.defined() ? ptr<T>(bias) : nullptr;
    if (in <= kSmallK && in > 0) {
      // Tiny K (the first MLP layer sees 6-7 features): a direct register-blocked loop over Wᵀ beats
      // a packed GEMM, whose packing then costs more than the arithmetic.
      std::vector<T> wt(static_cast<size_t>(in * outf));
      transpose_into(outf, in, ptr<T>(weight), in, wt.data());
      const T* px = ptr<T>(x);
      T* py = ptr<T>(out);
      parallel_for_work(M, kSmallKRows, in * outf, [&](int64_t r0, int64_t r1) {
        small_gemm(r1 - r0, outf, in, px + r0 * in, in, wt.data(), outf, py + r0 * outf, outf);
        if (pb)
          for (int64_t r = r0; r < r1; ++r)
            for (int64_t j = 0; j < outf; ++j) py[r * outf + j] += pb[j];
      });
    } else {
      gemm<T>(false, true, M, outf, in, ptr<T>(x), in, ptr<T>(weight), in, ptr<T>(out), outf, false, pb);
    }
    return 0;
  });
  if (needs_grad({&x, &weight, &bias})) {
    bool gx = x.requires_grad(), gw = weight.requires_grad(), gbias = bias.defined() && bias.requires_grad();
    Tensor xd = gw ? x.detach() : Tensor();
    Tensor wd = gx ? weight.detach() : Tensor();
    record(out, "linear", {x, weight, bias},
           [xd, wd, gx, gw, gbias, xs = x.shape(), M, in, outf](const Tensor& g) -> std::vector<Tensor> {
             Tensor dx, dw, db;
             dispatch_float(g.dtype(), "linear backward", [&](auto tag) {
               using T = decltype(tag);
               if (gx) {
                 dx = Tensor::empty(xs, g.dtype());
                 gemm<T>(false, false, M, in, outf, ptr<T>(g), outf, ptr<T>(wd), in, ptr<T>(dx), in, false);
               }
               if (gw) {
                 dw = Tensor::empty({outf, in}, g.dtype());
                 gemm<T>(true, false, outf, in, M, ptr<T>(g), outf, ptr<T>(xd), in, ptr<T>(dw), in, false);
               }
               return 0;
             });
             if (gbias) db = sum(g.reshape({M, outf}), {0}, false);
             return {dx, dw, db};
           });
  }
  return out;
}

}  // namespace lc2wf
