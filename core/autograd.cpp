#include "core/autograd.h"

#include <atomic>
#include <cstring>
#include <unordered_map>

#include "core/kernels.h"
#include "core/ops.h"

namespace lc2wf {

namespace {
std::atomic<int64_t> g_live_nodes{0};
thread_local const LeafGradReadyHook::Fn* g_leaf_ready = nullptr;

bool input_requires_grad(const Tensor& t) { return t.defined() && t.requires_grad(); }

// Leaf gradients accumulate in place; the first contribution is copied so the stored gradient never
// aliases a buffer that another node might still hold.
void accumulate_leaf(TensorImpl& leaf, const Tensor& g) {
  if (!leaf.grad.defined()) {
    // A gradient nobody else references can be adopted as is; anything shared is copied.
    bool unique = g.impl_ptr().use_count() == 1 && g.impl()->storage.use_count() == 1 && !g.impl()->grad_fn;
    leaf.grad = unique ? g : g.detach().clone();
    return;
  }
  Tensor& acc = leaf.grad;
  int64_t n = acc.numel();
  dispatch_float(acc.dtype(), "backward", [&](auto tag) {
    using T = decltype(tag);
    T* a = ptr<T>(acc);
    const T* b = ptr<T>(g);
    parallel_for_work(n, kElemGrain, 1, [&](int64_t s, int64_t e) {
      for (int64_t i = s; i < e; ++i) a[i] += b[i];
    });
    return 0;
  });
}

void check_grad(const Edge& edge, const Tensor& g, const char* name) {
  if (g.shape() != edge.shape)
    throw_arg(std::string("backward of ") + name + ": gradient shape " + shape_str(g.shape()) +
              " does not match input shape " + shape_str(edge.shape));
  if (g.dtype() != edge.dtype)
    throw_arg(std::string("backward of ") + name + ": gradient dtype " + dtype_name(g.dtype()) +
              " does not match input dtype " + dtype_name(edge.dtype));
}
}  // namespace

Node::Node() { g_live_nodes.fetch_add(1, std::memory_order_relaxed); }
Node::~Node() { g_live_nodes.fetch_sub(1, std::memory_order_relaxed); }

int64_t live_node_count() { return g_live_nodes.load(std::memory_order_relaxed); }

LeafGradReadyHook::LeafGradReadyHook(Fn fn) : fn_(std::move(fn)), previous_(g_leaf_ready) { g_leaf_ready = &fn_; }
LeafGradReadyHook::~LeafGradReadyHook() { g_leaf_ready = previous_; }

bool needs_grad(std::initializer_list<const Tensor*> inputs) {
  if (!grad_enabled()) return false;
  for (const Tensor* t : inputs)
    if (t && input_requires_grad(*t)) return true;
  return false;
}

bool needs_grad(const std::vector<Tensor>& inputs) {
  if (!grad_enabled()) return false;
  for (const Tensor& t : inputs)
    if (input_requires_grad(t)) return true;
  return false;
}

void record(Tensor& out, const char* name, const std::vector<Tensor>& inputs, BackwardFn backward) {
  auto node = std::make_shared<Node>();
  node->name = name;
  node->edges.resize(inputs.size());
  for (size_t i = 0; i < inputs.size(); ++i) {
    const Tensor& t = inputs[i];
    if (!input_requires_grad(t)) continue;
    Edge& e = node->edges[i];
    e.shape = t.shape();
    e.dtype = t.dtype();
    if (t.impl()->grad_fn)
      e.fn = t.impl()->grad_fn;
    else
      e.leaf = t.impl_ptr();
  }
  node->backward = std::move(backward);
  out.impl()->grad_fn = std::move(node);
}

void run_backward(const Tensor& root, const Tensor& seed, bool retain_graph) {
  NoGradGuard no_grad;
  TensorImpl* impl = root.impl();
  const LeafGradReadyHook::Fn* leaf_ready = g_leaf_ready;
  if (!impl->grad_fn) {
    accumulate_leaf(*impl, seed);
    if (leaf_ready) (*leaf_ready)(impl);
    return;
  }
  Node* start = impl->grad_fn.get();
  if (!start->backward)
    throw_arg("backward: the graph was already freed by a previous backward(); pass retain_graph=true to the first call");

  // Count, for every reachable node, how many reachable edges point at it (and, for the hook, at each leaf).
  std::unordered_map<Node*, int64_t> deps;
  std::unordered_map<const TensorImpl*, int64_t> leaf_deps;
  std::vector<Node*> stack{start};
  deps[start] = 0;
  // Owns every reachable node until the pass ends: freeing a node's edges must not destroy nodes
  // that are still queued.
  std::vector<std::shared_ptr<Node>> keep_alive{impl->grad_fn};
  while (!stack.empty()) {
    Node* n = stack.back();
    stack.pop_back();
    for (const Edge& e : n->edges) {
      if (leaf_ready && e.leaf) ++leaf_deps[e.leaf.get()];
      if (!e.fn) continue;
      auto [it, inserted] = deps.try_emplace(e.fn.get(), 0);
      ++it->second;
      if (inserted) {
        stack.push_back(e.fn.get());
        keep_alive.push_back(e.fn);
      }
    }
  }

  auto leaf_done = [&](const Edge& e) {
    if (leaf_ready && e.leaf && --leaf_deps[e.leaf.get()] == 0) (*leaf_ready)(e.leaf.get());
  };
  start->grad_buffer = seed;
  std::vector<Node*> ready{start};
  while (!ready.empty()) {
    Node* n = ready.back();
    ready.pop_back();
    Tensor g = std::move(n->grad_buffer);
    n->grad_buffer = Tensor();
    if (!g.defined()) {
      // No gradient reached this node: release its consumers' dependency counts all the same.
      for (const Edge& e : n->edges) {
        if (e.fn && --deps[e.fn.get()] == 0) ready.push_back(e.fn.get());
        leaf_done(e);
      }
      if (!retain_graph) {
        n->backward = nullptr;
        n->edges.clear();
      }
      continue;
    }
    if (!n->backward)
      throw_arg(std::string("backward: the graph through ") + n->name +
                " was already freed; pass retain_graph=true to the first backward()");
    std::vector<Tensor> grads = n->backward(g);
    if (grads.size() != n->edges.size())
      throw_arg(std::string("backward of ") + n->name + ": returned the wrong number of gradients");
    for (size_t i = 0; i < grads.size(); ++i) {
      const Edge& e = n->edges[i];
      if (!e.fn && !e.leaf) continue;
      const Tensor& gi = grads[i];
      if (e.fn) {
        Node* next = e.fn.get();
        if (gi.defined()) {
          check_grad(e, gi, n->name);
          next->grad_buffer = next->grad_buffer.defined() ? add(next->grad_buffer, gi) : gi;
        }
        if (--deps[next] == 0) ready.push_back(next);
      } else {
        if (gi.defined()) {
          check_grad(e, gi, n->name);
          accumulate_leaf(*e.leaf, gi);
        }
        leaf_done(e);
      }
    }
    if (!retain_graph) {
      n->backward = nullptr;  // frees every saved tensor of this op
      n->edges.clear();
    }
  }
}

}  // namespace lc2wf
