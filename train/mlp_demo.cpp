// lc2wf-mlp-demo: the engine's smallest real job. Trains a small MLP (linear, batch norm, layer norm,
// dropout, cross-entropy) on a generated three-arm spiral and prints how far the loss drops.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/ops.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/tensor.h"

namespace {

using namespace lc2wf;

struct DemoOptions {
  int64_t steps = 400;
  int64_t points_per_class = 512;
  int64_t hidden = 64;
  double lr = 0.1;
  uint64_t seed = 1;
  int threads = 0;  // 0 = all cores

  void Check() const {
    if (steps <= 0) throw std::invalid_argument("--steps must be positive");
    if (points_per_class < 2) throw std::invalid_argument("--points must be at least 2");
    if (hidden <= 0) throw std::invalid_argument("--hidden must be positive");
    if (!(lr > 0)) throw std::invalid_argument("--lr must be positive");
    if (threads < 0) throw std::invalid_argument("--threads must be >= 0");
  }
};

void print_help() {
  std::printf(
      "usage: lc2wf-mlp-demo [--steps N] [--points N] [--hidden N] [--lr X] [--seed N] [--threads N]\n"
      "Trains a small MLP on a generated 3-class spiral with lc2wf's tensor engine and prints the loss drop.\n"
      "  --steps N    full-batch SGD steps (default 400)\n"
      "  --points N   points per class (default 512)\n"
      "  --hidden N   hidden width (default 64)\n"
      "  --lr X       learning rate, momentum 0.9 (default 0.1)\n"
      "  --seed N     data and initialisation seed (default 1)\n"
      "  --threads N  worker threads, 0 = all cores (default 0)\n"
      "Exit status: 0 when the final loss is below half the initial one, 1 otherwise, 2 on bad arguments.\n");
}

DemoOptions parse(int argc, char** argv) {
  DemoOptions o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      print_help();
      std::exit(0);
    }
    if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
    std::string v = argv[++i];
    size_t used = 0;
    try {
      if (a == "--steps") o.steps = std::stoll(v, &used);
      else if (a == "--points") o.points_per_class = std::stoll(v, &used);
      else if (a == "--hidden") o.hidden = std::stoll(v, &used);
      else if (a == "--lr") o.lr = std::stod(v, &used);
      else if (a == "--seed") o.seed = std::stoull(v, &used);
      else if (a == "--threads") o.threads = std::stoi(v, &used);
      else throw std::invalid_argument("unknown option " + a + " (see --help)");
    } catch (const std::logic_error&) {
      if (used == 0) throw std::invalid_argument("bad value '" + v + "' for " + a);
      throw;
    }
    if (used != v.size()) throw std::invalid_argument("bad value '" + v + "' for " + a);
  }
  o.Check();
  return o;
}

// Three interleaved spiral arms with a little noise: not linearly separable.
void make_spiral(int64_t per_class, Rng& rng, Tensor& x, Tensor& y) {
  const int64_t classes = 3, n = per_class * classes;
  std::vector<float> xs(static_cast<size_t>(n * 2));
  std::vector<int64_t> ys(static_cast<size_t>(n));
  for (int64_t c = 0; c < classes; ++c)
    for (int64_t i = 0; i < per_class; ++i) {
      double r = static_cast<double>(i) / static_cast<double>(per_class - 1);
      double t = c * 2.0 * M_PI / classes + 4.0 * r + 0.2 * rng.next_normal();
      int64_t k = c * per_class + i;
      xs[k * 2] = static_cast<float>(r * std::sin(t));
      xs[k * 2 + 1] = static_cast<float>(r * std::cos(t));
      ys[k] = c;
    }
  x = Tensor::from_vector(xs, {n, 2});
  y = Tensor::from_vector(ys, {n});
}

Tensor uniform_init(const Shape& shape, Rng& rng) {
  double bound = 1.0 / std::sqrt(static_cast<double>(shape.back()));
  std::vector<float> v(static_cast<size_t>(shape_numel(shape)));
  for (float& w : v) w = static_cast<float>(rng.next_uniform(-bound, bound));
  return Tensor::from_vector(v, shape).set_requires_grad();
}

struct Mlp {
  Tensor w1, b1, g1, beta1, w2, b2, w3, b3, running_mean, running_var;
  Rng dropout_rng;

  Mlp(int64_t hidden, Rng& rng) : dropout_rng(rng.bits(rng.reserve(1))) {
    w1 = uniform_init({hidden, 2}, rng);
    b1 = Tensor::zeros({hidden}).set_requires_grad();
    g1 = Tensor::ones({hidden}).set_requires_grad();
    beta1 = Tensor::zeros({hidden}).set_requires_grad();
    w2 = uniform_init({hidden, hidden}, rng);
    b2 = Tensor::zeros({hidden}).set_requires_grad();
    w3 = uniform_init({3, hidden}, rng);
    b3 = Tensor::zeros({3}).set_requires_grad();
    running_mean = Tensor::zeros({hidden});
    running_var = Tensor::ones({hidden});
  }

  Tensor forward(const Tensor& x, bool training) {
    Tensor h = relu(batch_norm(linear(x, w1, b1), g1, beta1, running_mean, running_var, training));
    h = relu(layer_norm(linear(h, w2, b2), Tensor(), Tensor()));
    h = dropout(h, 0.1, training, dropout_rng);
    return linear(h, w3, b3);
  }

  std::vector<Tensor*> params() { return {&w1, &b1, &g1, &beta1, &w2, &b2, &w3, &b3}; }
};

double accuracy(const Tensor& logits, const Tensor& y) {
  const float* l = logits.data<float>();
  const int64_t* t = y.data<int64_t>();
  int64_t n = y.numel(), correct = 0;
  for (int64_t i = 0; i < n; ++i) {
    int64_t best = 0;
    for (int64_t c = 1; c < 3; ++c)
      if (l[i * 3 + c] > l[i * 3 + best]) best = c;
    correct += best == t[i];
  }
  return static_cast<double>(correct) / static_cast<double>(n);
}

int run(const DemoOptions& opt) {
  set_num_threads(opt.threads);
  Rng rng(opt.seed);
  Tensor x, y;
  make_spiral(opt.points_per_class, rng, x, y);
  Mlp mlp(opt.hidden, rng);
  std::vector<Tensor> velocity;
  for (Tensor* p : mlp.params()) velocity.push_back(Tensor::zeros(p->shape()));

  bool tty = isatty(STDERR_FILENO);
  auto start = std::chrono::steady_clock::now();
  double first_loss = 0, last_loss = 0;
  std::printf("lc2wf-mlp-demo: %lld points, 3 classes, MLP 2-%lld-%lld-3, %d threads\n",
              static_cast<long long>(x.size(0)), static_cast<long long>(opt.hidden),
              static_cast<long long>(opt.hidden), num_threads());
  for (int64_t step = 0; step < opt.steps; ++step) {
    Tensor loss = cross_entropy(mlp.forward(x, true), y);
    loss.backward();
    auto params = mlp.params();
    for (size_t k = 0; k < params.size(); ++k) {
      float* w = params[k]->data<float>();
      float* v = velocity[k].data<float>();
      const float* g = params[k]->grad().data<float>();
      for (int64_t i = 0; i < params[k]->numel(); ++i) {
        v[i] = 0.9f * v[i] + g[i];
        w[i] -= static_cast<float>(opt.lr) * v[i];
      }
      params[k]->zero_grad();
    }
    last_loss = loss.item();
    if (step == 0) first_loss = last_loss;
    if (step == 0 || (step + 1) % 100 == 0) std::printf("  step %5lld  loss %.4f\n", static_cast<long long>(step + 1), last_loss);
    if (tty) std::fprintf(stderr, "\r  %lld/%lld", static_cast<long long>(step + 1), static_cast<long long>(opt.steps));
  }
  if (tty) std::fprintf(stderr, "\r%*s\r", 24, "");
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Tensor logits;
  {
    NoGradGuard no_grad;
    logits = mlp.forward(x, false);
  }
  double eval_loss = cross_entropy(logits, y).item();
  std::printf("loss %.4f -> %.4f (eval %.4f), train accuracy %.1f%%, %.2f s (%.2f ms/step)\n", first_loss, last_loss,
              eval_loss, 100.0 * accuracy(logits, y), seconds, 1000.0 * seconds / static_cast<double>(opt.steps));
  return last_loss < 0.5 * first_loss ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  DemoOptions opt;
  try {
    opt = parse(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-mlp-demo: %s\n", e.what());
    return 2;
  }
  try {
    return run(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-mlp-demo: error: %s\n", e.what());
    return 1;
  }
}
