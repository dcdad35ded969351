// TensorImpl: the shared state behind a Tensor handle (storage, layout, autograd links).
#pragma once

#include <cstdint>
#include <memory>

#include "core/tensor.h"

namespace lc2wf {

struct Node;

// 64-byte aligned buffer so kernels get full-width vector loads on every row start. Blocks of 1 MB and
// more come from core/storage_cache (recycled, so contents start uninitialised like any fresh buffer).
struct Storage {
  explicit Storage(size_t bytes);
  ~Storage();
  Storage(const Storage&) = delete;
  Storage& operator=(const Storage&) = delete;
  void* data = nullptr;
  size_t bytes = 0;
  size_t capacity = 0;  // bytes actually reserved, handed back to core/storage_cache
};

struct TensorImpl {
  std::shared_ptr<Storage> storage;
  int64_t offset = 0;  // in elements
  Shape shape;
  int64_t numel = 0;
  DType dtype = DType::F32;
  bool requires_grad = false;  // leaf flag; non-leaves require grad through grad_fn
  Tensor grad;
  std::shared_ptr<Node> grad_fn;

  void* raw() const { return static_cast<char*>(storage->data) + offset * static_cast<int64_t>(dtype_size(dtype)); }
};

}  // namespace lc2wf
