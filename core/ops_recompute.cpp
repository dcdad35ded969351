// Ops that trade a little recomputation in the backward pass for activation memory: a training step's
// peak RSS is its saved activations, so these keep only their inputs and rebuild the rest on demand.
#include <functional>

#include "core/autograd.h"
#include "core/gemm.h"
#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

namespace {

// Fresh leaves over the saved inputs (same storage), requiring grad where the original input did, so
// a recomputation builds its own small graph whose gradients end up on these leaves.
std::vector<Tensor> recompute_leaves(const std::vector<Tensor>& saved, const std::vector<bool>& wants_grad) {
  std::vector<Tensor> leaves(saved.size());
  for (size_t i = 0; i < saved.size(); ++i) {
    if (!saved[i].defined()) continue;
    leaves[i] = saved[i].detach();
    if (wants_grad[i]) leaves[i].set_requires_grad(true);
  }
  return leaves;
}

std::vector<bool> grad_flags(const std::vector<Tensor>& inputs) {
  std::vector<bool> flags(inputs.size());
  for (size_t i = 0; i < inputs.size(); ++i) flags[i] = inputs[i].defined() && inputs[i].requires_grad();
  return flags;
}

std::vector<Tensor> detached(const std::vector<Tensor>& inputs) {
  std::vector<Tensor> out(inputs.size());
  for (size_t i = 0; i < inputs.size(); ++i)
    if (inputs[i].defined()) out[i] = inputs[i].detach();
  return out;
}

std::vector<Tensor> leaf_grads(const std::vector<Tensor>& leaves, const std::vector<bool>& wants_grad) {
  std::vector<Tensor> grads(leaves.size());
  for (size_t i = 0; i < leaves.size(); ++i)
    if (wants_grad[i]) grads[i] = leaves[i].grad();
  return grads;
}

}  // namespace

Tensor checkpoint(const std::vector<Tensor>& inputs, const CheckpointFn& fn) {
  if (!fn) throw_arg("checkpoint: fn is empty");
  if (!needs_grad(inputs)) return fn(inputs, false);
  Tensor out;
  {
    NoGradGuard no_grad;
    out = fn(inputs, false);
  }
  check_float(out, "checkpoint", "fn(inputs)");
  // A fresh handle, so recording never replaces the graph node of an input that fn returned as is.
  out = out.detach();
  std::vector<bool> wants_grad = grad_flags(inputs);
  record(out, "checkpoint", inputs,
         [saved = detached(inputs), wants_grad, fn, out_shape = out.shape()](const Tensor& g) -> std::vector<Tensor> {
           std::vector<Tensor> leaves = recompute_leaves(saved, wants_grad);
           Tensor y;
           {
             EnableGradGuard grad_on;
             y = fn(leaves, true);
           }
           if (!y.defined() || y.shape() != out_shape)
             throw_arg("checkpoint: the recomputation returned " + (y.defined() ? shape_str(y.shape()) : "nothing") +
                       ", the forward pass " + shape_str(out_shape));
           if (y.requires_grad()) run_backward(y, g, false);
           return leaf_grads(leaves, wants_grad);
         });
  return out;
}

Tensor layer_norm_linear(const Tensor& x, const Tensor& norm_weight, const Tensor& norm_bias, double eps,
                         const Tensor& weight, const Tensor& bias) {
  Tensor out;
  {
    // The normalised rows live only until the product has consumed them.
    NoGradGuard no_grad;
    out = linear(layer_norm(x, norm_weight, norm_bias, eps), weight, bias);
  }
  const std::vector<Tensor> inputs{x, norm_weight, norm_bias, weight, bias};
  if (!needs_grad(inputs)) return out;
  std::vector<bool> wants_grad = grad_flags(inputs);
  const int64_t in = weight.size(1), outf = weight.size(0), M = x.numel() / in;
  record(out, "layer_norm_linear", inputs,
         [saved = detached(inputs), wants_grad, eps, M, in, outf](const Tensor& g) -> std::vector<Tensor> {
           std::vector<Tensor> leaves = recompute_leaves(saved, wants_grad);
           const bool norm_grad = wants_grad[0] || wants_grad[1] || wants_grad[2];
           Tensor normed;
           {
             // The same kernel as the forward pass, so the recomputed rows are bit-identical.
             EnableGradGuard grad_on;
             normed = layer_norm(leaves[0], leaves[1], leaves[2], eps);
           }
           Tensor dnormed, dw, db;
           dispatch_float(g.dtype(), "layer_norm_linear backward", [&](auto tag) {
             using T = decltype(tag);
             if (norm_grad) {
               dnormed = Tensor::empty(normed.shape(), g.dtype());
               gemm<T>(false, false, M, in, outf, ptr<T>(g), outf, ptr<T>(saved[3]), in, ptr<T>(dnormed), in, false);
             }
             if (wants_grad[3]) {
               dw = Tensor::empty({outf, in}, g.dtype());
               gemm<T>(true, false, outf, in, M, ptr<T>(g), outf, ptr<T>(normed), in, ptr<T>(dw), in, false);
             }
             return 0;
           });
           if (wants_grad[4]) db = sum(g.reshape({M, outf}), {0}, false);
           std::vector<Tensor> grads{Tensor(), Tensor(), Tensor(), dw, db};
           if (norm_grad) {
             run_backward(normed, dnormed, false);
             for (size_t i = 0; i < 3; ++i)
               if (wants_grad[i]) grads[i] = leaves[i].grad();
           }
           return grads;
         });
  return out;
}

}  // namespace lc2wf
