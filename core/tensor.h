// Tensor: an N-d, contiguous, row-major array with reverse-mode autodiff.
//
// A Tensor is a *handle*. Copying a Tensor (or passing it by value) aliases the same data, the same
// gradient and the same graph node, like copying a shared_ptr. Use clone() for an independent copy.
// reshape()/view() share storage with the source; permute()/transpose() copy into a new layout
// (every tensor is contiguous, so kernels never deal with strides).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lc2wf {

// F32 for training and inference, F64 for finite-difference gradient checks.
// Bool (1 byte per element) is for masks, I64 for indices and class targets; neither carries gradients.
enum class DType : uint8_t { F32, F64, Bool, I64 };

const char* dtype_name(DType dtype);
size_t dtype_size(DType dtype);

using Shape = std::vector<int64_t>;
std::string shape_str(const Shape& shape);  // "[2, 3, 4]"
int64_t shape_numel(const Shape& shape);

struct TensorImpl;  // storage + offset + shape + autograd state (core/tensor_impl.h)

class Tensor {
 public:
  Tensor() = default;  // undefined handle; defined() is false

  // --- construction (results do not require grad) ---
  static Tensor empty(const Shape& shape, DType dtype = DType::F32);  // uninitialised
  static Tensor zeros(const Shape& shape, DType dtype = DType::F32);
  static Tensor ones(const Shape& shape, DType dtype = DType::F32);
  static Tensor full(const Shape& shape, double value, DType dtype = DType::F32);
  static Tensor scalar(double value, DType dtype = DType::F32);  // shape []
  static Tensor from_vector(const std::vector<float>& values, const Shape& shape);
  static Tensor from_vector(const std::vector<double>& values, const Shape& shape);
  static Tensor from_vector(const std::vector<int64_t>& values, const Shape& shape);  // I64
  static Tensor from_mask(const std::vector<uint8_t>& values, const Shape& shape);    // Bool

  // --- metadata ---
  bool defined() const { return impl_ != nullptr; }
  const Shape& shape() const;
  int64_t dim() const;
  int64_t size(int64_t axis) const;  // negative axes count from the end
  int64_t numel() const;
  DType dtype() const;
  std::string str(int max_elements = 16) const;  // short human-readable dump for errors and debugging

  // --- raw data access (throws std::invalid_argument if T does not match dtype) ---
  template <class T> T* data();
  template <class T> const T* data() const;
  double item() const;                  // single-element tensors only
  std::vector<double> to_vector() const;  // any dtype, converted to double

  // --- layout (differentiable) ---
  Tensor reshape(const Shape& shape) const;  // shares storage; one dimension may be -1
  Tensor view(const Shape& shape) const { return reshape(shape); }
  Tensor flatten() const { return reshape({-1}); }
  Tensor permute(const std::vector<int64_t>& axes) const;  // copies
  Tensor transpose(int64_t a, int64_t b) const;            // copies
  Tensor contiguous() const { return *this; }              // every tensor already is
  Tensor clone() const;                                    // deep copy, differentiable
  Tensor to(DType dtype) const;                            // differentiable for float->float

  // --- autograd ---
  bool requires_grad() const;
  Tensor& set_requires_grad(bool required = true);  // leaves only
  bool is_leaf() const;
  Tensor grad() const;  // undefined until a backward pass reaches this tensor
  void zero_grad();     // drops the gradient (the next backward starts from zero)
  // Sets the gradient of a leaf (same shape and dtype), e.g. one summed over data-parallel processes.
  void set_grad(const Tensor& grad);
  Tensor detach() const;  // same storage, no graph, no grad
  // Scalar losses may omit the seed (it is 1). The graph is freed afterwards unless retain_graph.
  void backward(const Tensor& seed = Tensor(), bool retain_graph = false) const;

  // --- in-place helpers for optimizers and initialisers (never recorded on the tape) ---
  Tensor& fill_(double value);
  Tensor& copy_(const Tensor& src);  // same shape and dtype

  // For core internals.
  explicit Tensor(std::shared_ptr<TensorImpl> impl) : impl_(std::move(impl)) {}
  TensorImpl* impl() const { return impl_.get(); }
  const std::shared_ptr<TensorImpl>& impl_ptr() const { return impl_; }

 private:
  std::shared_ptr<TensorImpl> impl_;
};

// Disables tape recording in its scope (inference): ops then keep no graph and no saved tensors.
class NoGradGuard {
 public:
  NoGradGuard();
  ~NoGradGuard();
  NoGradGuard(const NoGradGuard&) = delete;
  NoGradGuard& operator=(const NoGradGuard&) = delete;

 private:
  bool previous_;
};
// Turns tape recording back on in its scope: recompute-in-backward ops build a local graph while
// the enclosing backward pass runs without recording.
class EnableGradGuard {
 public:
  EnableGradGuard();
  ~EnableGradGuard();
  EnableGradGuard(const EnableGradGuard&) = delete;
  EnableGradGuard& operator=(const EnableGradGuard&) = delete;

 private:
  bool previous_;
};
bool grad_enabled();

}  // namespace lc2wf
