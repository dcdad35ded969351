#include "core/kernels.h"

namespace lc2wf {

void throw_arg(const std::string& message) { throw std::invalid_argument(message); }

void check_defined(const Tensor& t, const char* op, const char* arg) {
  if (!t.defined()) throw_arg(std::string(op) + ": argument '" + arg + "' is undefined");
}

void check_float(const Tensor& t, const char* op, const char* arg) {
  check_defined(t, op, arg);
  if (t.dtype() != DType::F32 && t.dtype() != DType::F64)
    throw_arg(std::string(op) + ": argument '" + arg + "' must be F32 or F64, got " + dtype_name(t.dtype()) + " " +
              shape_str(t.shape()));
}

void check_dtype(const Tensor& t, DType dtype, const char* op, const char* arg) {
  check_defined(t, op, arg);
  if (t.dtype() != dtype)
    throw_arg(std::string(op) + ": argument '" + arg + "' must be " + dtype_name(dtype) + ", got " +
              dtype_name(t.dtype()) + " " + shape_str(t.shape()));
}

void check_same_dtype(const Tensor& a, const Tensor& b, const char* op) {
  if (a.dtype() != b.dtype())
    throw_arg(std::string(op) + ": dtype mismatch " + dtype_name(a.dtype()) + " " + shape_str(a.shape()) + " vs " +
              dtype_name(b.dtype()) + " " + shape_str(b.shape()));
}

void check_same_shape(const Tensor& a, const Tensor& b, const char* op) {
  if (a.shape() != b.shape())
    throw_arg(std::string(op) + ": shape mismatch " + shape_str(a.shape()) + " vs " + shape_str(b.shape()));
}

int64_t normalize_axis(int64_t axis, int64_t ndim, const char* op) {
  int64_t a = axis < 0 ? axis + ndim : axis;
  if (a < 0 || a >= ndim)
    throw_arg(std::string(op) + ": axis " + std::to_string(axis) + " out of range for a " + std::to_string(ndim) +
              "-d tensor");
  return a;
}

BroadcastPlan plan_broadcast(const Shape& out, const Shape& a, const Shape& b) {
  size_t nd = out.size();
  std::vector<int64_t> sizes;
  std::vector<uint8_t> fa, fb;
  for (size_t d = 0; d < nd; ++d) {
    if (out[d] == 1) continue;
    bool af = (d >= nd - a.size()) && a[d - (nd - a.size())] != 1;
    bool bf = (d >= nd - b.size()) && b[d - (nd - b.size())] != 1;
    if (!sizes.empty() && fa.back() == af && fb.back() == bf) {
      sizes.back() *= out[d];
    } else {
      sizes.push_back(out[d]);
      fa.push_back(af);
      fb.push_back(bf);
    }
  }
  BroadcastPlan p;
  p.size = sizes;
  p.sa.resize(sizes.size());
  p.sb.resize(sizes.size());
  int64_t ra = 1, rb = 1;
  for (size_t i = sizes.size(); i-- > 0;) {
    p.sa[i] = fa[i] ? ra : 0;
    p.sb[i] = fb[i] ? rb : 0;
    if (fa[i]) ra *= sizes[i];
    if (fb[i]) rb *= sizes[i];
  }
  return p;
}

}  // namespace lc2wf
