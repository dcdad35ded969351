// Reverse-mode tape: each op output that needs a gradient owns a Node holding the backward closure and
// edges to the nodes (or leaves) of its inputs. Closures must never hold the op's own output strongly.
#pragma once

#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "core/tensor.h"
#include "core/tensor_impl.h"

namespace lc2wf {

// Returns one gradient per recorded input (undefined = no contribution), given the output gradient.
using BackwardFn = std::function<std::vector<Tensor>(const Tensor& grad_out)>;

struct Edge {
  std::shared_ptr<Node> fn;          // set when the input is an op output
  std::shared_ptr<TensorImpl> leaf;  // set when the input is a leaf that requires grad
  Shape shape;                       // expected gradient shape
  DType dtype = DType::F32;
};

struct Node {
  Node();
  ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  const char* name = "";
  std::vector<Edge> edges;  // one per recorded input, undefined edges have neither fn nor leaf
  BackwardFn backward;      // empty once the graph has been freed
  Tensor grad_buffer;       // accumulated output gradient during a backward pass
};

// Number of live tape nodes in the process (tests use it to prove graphs are freed).
int64_t live_node_count();

// True when grad mode is on and any of the inputs requires grad.
bool needs_grad(std::initializer_list<const Tensor*> inputs);
bool needs_grad(const std::vector<Tensor>& inputs);

// Attaches a node for `out` with one edge per input (inputs not requiring grad get an empty edge).
void record(Tensor& out, const char* name, const std::vector<Tensor>& inputs, BackwardFn backward);

// Runs the backward pass from `root` seeded with `seed` (same shape as root).
void run_backward(const Tensor& root, const Tensor& seed, bool retain_graph);

// While alive, backward passes on this thread call `fn(leaf)` as soon as a leaf's gradient has received
// every contribution of the pass, so data-parallel training can start summing it across processes while
// the rest of the pass runs. Guards nest; the innermost one is called.
class LeafGradReadyHook {
 public:
  using Fn = std::function<void(const TensorImpl* leaf)>;
  explicit LeafGradReadyHook(Fn fn);
  ~LeafGradReadyHook();
  LeafGradReadyHook(const LeafGradReadyHook&) = delete;
  LeafGradReadyHook& operator=(const LeafGradReadyHook&) = delete;

 private:
  Fn fn_;
  const Fn* previous_;
};

}  // namespace lc2wf
