#include "core/tensor.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <malloc.h>
#include <sstream>

#include "core/autograd.h"
#include "core/kernels.h"
#include "core/storage_cache.h"
#include "core/tensor_impl.h"

namespace lc2wf {

namespace {
// Blocks of 1 MB and more are mapped and recycled by core/storage_cache. The many smaller temporaries
// stay in a never-trimmed heap instead of fresh mmaps, so their pages are reused without new faults.
const bool g_malloc_tuned = [] {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  return true;
}();
}  // namespace

Storage::Storage(size_t n) : bytes(n) {
  (void)g_malloc_tuned;
  StorageBlock block = storage_allocate(n);
  data = block.data;
  capacity = block.capacity;
}

Storage::~Storage() { storage_release(StorageBlock{data, capacity}); }

const char* dtype_name(DType dtype) {
  switch (dtype) {
    case DType::F32: return "F32";
    case DType::F64: return "F64";
    case DType::Bool: return "Bool";
    case DType::I64: return "I64";
  }
  return "?";
}

size_t dtype_size(DType dtype) {
  switch (dtype) {
    case DType::F32: return 4;
    case DType::F64: return 8;
    case DType::Bool: return 1;
    case DType::I64: return 8;
  }
  return 0;
}

std::string shape_str(const Shape& shape) {
  std::string s = "[";
  for (size_t i = 0; i < shape.size(); ++i) {
    if (i) s += ", ";
    s += std::to_string(shape[i]);
  }
  return s + "]";
}

int64_t shape_numel(const Shape& shape) {
  int64_t n = 1;
  for (int64_t d : shape) {
    if (d < 0) throw_arg("invalid shape " + shape_str(shape) + ": negative dimension");
    n *= d;
  }
  return n;
}

namespace {

thread_local bool g_grad_enabled = true;

const TensorImpl& checked(const std::shared_ptr<TensorImpl>& impl) {
  if (!impl) throw_arg("operation on an undefined Tensor");
  return *impl;
}

}  // namespace

bool grad_enabled() { return g_grad_enabled; }
NoGradGuard::NoGradGuard() : previous_(g_grad_enabled) { g_grad_enabled = false; }
NoGradGuard::~NoGradGuard() { g_grad_enabled = previous_; }
EnableGradGuard::EnableGradGuard() : previous_(g_grad_enabled) { g_grad_enabled = true; }
EnableGradGuard::~EnableGradGuard() { g_grad_enabled = previous_; }

Tensor Tensor::empty(const Shape& shape, DType dtype) {
  auto impl = std::make_shared<TensorImpl>();
  impl->numel = shape_numel(shape);
  impl->shape = shape;
  impl->dtype = dtype;
  impl->storage = std::make_shared<Storage>(static_cast<size_t>(impl->numel) * dtype_size(dtype));
  return Tensor(std::move(impl));
}

Tensor Tensor::zeros(const Shape& shape, DType dtype) {
  Tensor t = empty(shape, dtype);
  std::memset(t.impl()->raw(), 0, static_cast<size_t>(t.numel()) * dtype_size(dtype));
  return t;
}

Tensor Tensor::ones(const Shape& shape, DType dtype) { return full(shape, 1.0, dtype); }

Tensor Tensor::full(const Shape& shape, double value, DType dtype) {
  Tensor t = empty(shape, dtype);
  t.fill_(value);
  return t;
}

Tensor Tensor::scalar(double value, DType dtype) { return full({}, value, dtype); }

Tensor Tensor::from_vector(const std::vector<float>& values, const Shape& shape) {
  Tensor t = empty(shape, DType::F32);
  if (static_cast<int64_t>(values.size()) != t.numel())
    throw_arg("from_vector: " + std::to_string(values.size()) + " values for shape " + shape_str(shape));
  std::memcpy(t.impl()->raw(), values.data(), values.size() * sizeof(float));
  return t;
}

Tensor Tensor::from_vector(const std::vector<double>& values, const Shape& shape) {
  Tensor t = empty(shape, DType::F64);
  if (static_cast<int64_t>(values.size()) != t.numel())
    throw_arg("from_vector: " + std::to_string(values.size()) + " values for shape " + shape_str(shape));
  std::memcpy(t.impl()->raw(), values.data(), values.size() * sizeof(double));
  return t;
}

Tensor Tensor::from_vector(const std::vector<int64_t>& values, const Shape& shape) {
  Tensor t = empty(shape, DType::I64);
  if (static_cast<int64_t>(values.size()) != t.numel())
    throw_arg("from_vector: " + std::to_string(values.size()) + " values for shape " + shape_str(shape));
  std::memcpy(t.impl()->raw(), values.data(), values.size() * sizeof(int64_t));
  return t;
}

Tensor Tensor::from_mask(const std::vector<uint8_t>& values, const Shape& shape) {
  Tensor t = empty(shape, DType::Bool);
  if (static_cast<int64_t>(values.size()) != t.numel())
    throw_arg("from_mask: " + std::to_string(values.size()) + " values for shape " + shape_str(shape));
  auto* out = static_cast<uint8_t*>(t.impl()->raw());
  for (size_t i = 0; i < values.size(); ++i) out[i] = values[i] ? 1 : 0;
  return t;
}

const Shape& Tensor::shape() const { return checked(impl_).shape; }
int64_t Tensor::dim() const { return static_cast<int64_t>(checked(impl_).shape.size()); }
int64_t Tensor::size(int64_t axis) const {
  return shape()[normalize_axis(axis, dim(), "size")];
}
int64_t Tensor::numel() const { return checked(impl_).numel; }
DType Tensor::dtype() const { return checked(impl_).dtype; }

std::string Tensor::str(int max_elements) const {
  if (!impl_) return "Tensor(undefined)";
  std::ostringstream os;
  os << "Tensor(" << dtype_name(dtype()) << " " << shape_str(shape()) << " [";
  std::vector<double> v = to_vector();
  for (size_t i = 0; i < v.size() && static_cast<int>(i) < max_elements; ++i) os << (i ? ", " : "") << v[i];
  if (static_cast<int>(v.size()) > max_elements) os << ", ...";
  os << "])";
  return os.str();
}

namespace {
template <class T> constexpr DType dtype_of();
template <> constexpr DType dtype_of<float>() { return DType::F32; }
template <> constexpr DType dtype_of<double>() { return DType::F64; }
template <> constexpr DType dtype_of<int64_t>() { return DType::I64; }
template <> constexpr DType dtype_of<uint8_t>() { return DType::Bool; }
template <> constexpr DType dtype_of<bool>() { return DType::Bool; }
}  // namespace

template <class T>
T* Tensor::data() {
  const TensorImpl& impl = checked(impl_);
  if (impl.dtype != dtype_of<T>())
    throw_arg(std::string("data<T>(): tensor has dtype ") + dtype_name(impl.dtype) + ", requested " +
              dtype_name(dtype_of<T>()));
  return static_cast<T*>(impl.raw());
}

template <class T>
const T* Tensor::data() const {
  return const_cast<Tensor*>(this)->data<T>();
}

template float* Tensor::data<float>();
template double* Tensor::data<double>();
template int64_t* Tensor::data<int64_t>();
template uint8_t* Tensor::data<uint8_t>();
template bool* Tensor::data<bool>();
template const float* Tensor::data<float>() const;
template const double* Tensor::data<double>() const;
template const int64_t* Tensor::data<int64_t>() const;
template const uint8_t* Tensor::data<uint8_t>() const;
template const bool* Tensor::data<bool>() const;

namespace {
double element_as_double(const TensorImpl& impl, int64_t i) {
  const void* p = impl.raw();
  switch (impl.dtype) {
    case DType::F32: return static_cast<const float*>(p)[i];
    case DType::F64: return static_cast<const double*>(p)[i];
    case DType::Bool: return static_cast<const uint8_t*>(p)[i];
    case DType::I64: return static_cast<double>(static_cast<const int64_t*>(p)[i]);
  }
  return 0;
}
}  // namespace

double Tensor::item() const {
  const TensorImpl& impl = checked(impl_);
  if (impl.numel != 1) throw_arg("item(): tensor of shape " + shape_str(impl.shape) + " is not a single element");
  return element_as_double(impl, 0);
}

std::vector<double> Tensor::to_vector() const {
  const TensorImpl& impl = checked(impl_);
  std::vector<double> v(static_cast<size_t>(impl.numel));
  for (int64_t i = 0; i < impl.numel; ++i) v[i] = element_as_double(impl, i);
  return v;
}

Tensor Tensor::reshape(const Shape& shape) const {
  const TensorImpl& impl = checked(impl_);
  Shape target = shape;
  int64_t known = 1, infer = -1;
  for (size_t i = 0; i < target.size(); ++i) {
    if (target[i] == -1) {
      if (infer >= 0) throw_arg("reshape: more than one -1 in " + shape_str(shape));
      infer = static_cast<int64_t>(i);
    } else if (target[i] < 0) {
      throw_arg("reshape: invalid target shape " + shape_str(shape));
    } else {
      known *= target[i];
    }
  }
  if (infer >= 0) {
    if (known == 0 || impl.numel % known != 0)
      throw_arg("reshape: cannot reshape " + shape_str(impl.shape) + " to " + shape_str(shape));
    target[infer] = impl.numel / known;
  }
  if (shape_numel(target) != impl.numel)
    throw_arg("reshape: cannot reshape " + shape_str(impl.shape) + " (" + std::to_string(impl.numel) +
              " elements) to " + shape_str(shape));
  auto out_impl = std::make_shared<TensorImpl>();
  out_impl->storage = impl.storage;
  out_impl->offset = impl.offset;
  out_impl->shape = target;
  out_impl->numel = impl.numel;
  out_impl->dtype = impl.dtype;
  Tensor out(std::move(out_impl));
  if (needs_grad({this})) {
    record(out, "reshape", {*this}, [src = impl.shape](const Tensor& g) -> std::vector<Tensor> {
      return {g.reshape(src)};
    });
  }
  return out;
}

Tensor Tensor::transpose(int64_t a, int64_t b) const {
  int64_t n = dim();
  a = normalize_axis(a, n, "transpose");
  b = normalize_axis(b, n, "transpose");
  std::vector<int64_t> axes(n);
  for (int64_t i = 0; i < n; ++i) axes[i] = i;
  std::swap(axes[a], axes[b]);
  return permute(axes);
}

Tensor Tensor::clone() const {
  const TensorImpl& impl = checked(impl_);
  Tensor out = empty(impl.shape, impl.dtype);
  std::memcpy(out.impl()->raw(), impl.raw(), static_cast<size_t>(impl.numel) * dtype_size(impl.dtype));
  if (needs_grad({this})) {
    record(out, "clone", {*this}, [](const Tensor& g) -> std::vector<Tensor> { return {g}; });
  }
  return out;
}

namespace {
template <class To>
void convert_into(const TensorImpl& src, To* dst) {
  const void* p = src.raw();
  int64_t n = src.numel;
  auto run = [&](auto* s) {
    parallel_for_work(n, kElemGrain, 1, [&](int64_t b, int64_t e) {
      for (int64_t i = b; i < e; ++i) dst[i] = static_cast<To>(s[i]);
    });
  };
  switch (src.dtype) {
    case DType::F32: run(static_cast<const float*>(p)); break;
    case DType::F64: run(static_cast<const double*>(p)); break;
    case DType::Bool: run(static_cast<const uint8_t*>(p)); break;
    case DType::I64: run(static_cast<const int64_t*>(p)); break;
  }
}
}  // namespace

Tensor Tensor::to(DType dtype) const {
  const TensorImpl& impl = checked(impl_);
  if (impl.dtype == dtype) return *this;
  Tensor out = empty(impl.shape, dtype);
  switch (dtype) {
    case DType::F32: convert_into(impl, static_cast<float*>(out.impl()->raw())); break;
    case DType::F64: convert_into(impl, static_cast<double*>(out.impl()->raw())); break;
    case DType::I64: convert_into(impl, static_cast<int64_t*>(out.impl()->raw())); break;
    case DType::Bool: {
      Tensor tmp = to(DType::F64);
      const double* s = tmp.data<double>();
      uint8_t* d = out.data<uint8_t>();
      for (int64_t i = 0; i < impl.numel; ++i) d[i] = s[i] != 0.0;
      break;
    }
  }
  bool float_to_float = (dtype == DType::F32 || dtype == DType::F64);
  if (float_to_float && needs_grad({this})) {
    record(out, "to", {*this}, [src = impl.dtype](const Tensor& g) -> std::vector<Tensor> { return {g.to(src)}; });
  }
  return out;
}

bool Tensor::requires_grad() const {
  const TensorImpl& impl = checked(impl_);
  return impl.requires_grad || impl.grad_fn != nullptr;
}

Tensor& Tensor::set_requires_grad(bool required) {
  TensorImpl& impl = const_cast<TensorImpl&>(checked(impl_));
  if (impl.grad_fn) throw_arg("set_requires_grad: only leaf tensors can change requires_grad (this one is an op output)");
  if (required && impl.dtype != DType::F32 && impl.dtype != DType::F64)
    throw_arg(std::string("set_requires_grad: only float tensors can require grad, got ") + dtype_name(impl.dtype));
  impl.requires_grad = required;
  return *this;
}

bool Tensor::is_leaf() const { return checked(impl_).grad_fn == nullptr; }
Tensor Tensor::grad() const { return checked(impl_).grad; }
void Tensor::zero_grad() { const_cast<TensorImpl&>(checked(impl_)).grad = Tensor(); }
void Tensor::set_grad(const Tensor& grad) {
  TensorImpl& impl = const_cast<TensorImpl&>(checked(impl_));
  if (impl.grad_fn) throw_arg("set_grad: only leaf tensors hold a gradient");
  if (grad.defined() && (grad.shape() != impl.shape || grad.dtype() != impl.dtype))
    throw_arg("set_grad: gradient " + shape_str(grad.shape()) + " does not match the tensor " + shape_str(impl.shape));
  impl.grad = grad;
}

Tensor Tensor::detach() const {
  const TensorImpl& impl = checked(impl_);
  auto out = std::make_shared<TensorImpl>();
  out->storage = impl.storage;
  out->offset = impl.offset;
  out->shape = impl.shape;
  out->numel = impl.numel;
  out->dtype = impl.dtype;
  return Tensor(std::move(out));
}

void Tensor::backward(const Tensor& seed, bool retain_graph) const {
  const TensorImpl& impl = checked(impl_);
  if (!requires_grad()) throw_arg("backward: tensor " + shape_str(impl.shape) + " does not require grad");
  Tensor s = seed;
  if (!s.defined()) {
    if (impl.numel != 1)
      throw_arg("backward: tensor of shape " + shape_str(impl.shape) +
                " is not a scalar; pass a seed gradient of the same shape");
    s = Tensor::ones(impl.shape, impl.dtype);
  }
  if (s.shape() != impl.shape)
    throw_arg("backward: seed shape " + shape_str(s.shape()) + " does not match tensor shape " + shape_str(impl.shape));
  if (s.dtype() != impl.dtype) s = s.to(impl.dtype);
  run_backward(*this, s, retain_graph);
}

Tensor& Tensor::fill_(double value) {
  TensorImpl& impl = const_cast<TensorImpl&>(checked(impl_));
  void* p = impl.raw();
  int64_t n = impl.numel;
  switch (impl.dtype) {
    case DType::F32: std::fill_n(static_cast<float*>(p), n, static_cast<float>(value)); break;
    case DType::F64: std::fill_n(static_cast<double*>(p), n, value); break;
    case DType::Bool: std::fill_n(static_cast<uint8_t*>(p), n, static_cast<uint8_t>(value != 0.0)); break;
    case DType::I64: std::fill_n(static_cast<int64_t*>(p), n, static_cast<int64_t>(value)); break;
  }
  return *this;
}

Tensor& Tensor::copy_(const Tensor& src) {
  TensorImpl& impl = const_cast<TensorImpl&>(checked(impl_));
  const TensorImpl& s = checked(src.impl_ptr());
  if (s.shape != impl.shape || s.dtype != impl.dtype)
    throw_arg("copy_: source " + std::string(dtype_name(s.dtype)) + " " + shape_str(s.shape) +
              " does not match destination " + dtype_name(impl.dtype) + " " + shape_str(impl.shape));
  if (impl.raw() != s.raw()) std::memmove(impl.raw(), s.raw(), static_cast<size_t>(impl.numel) * dtype_size(impl.dtype));
  return *this;
}

}  // namespace lc2wf
