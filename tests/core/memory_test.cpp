// The tape is freed after every backward and never built under NoGradGuard.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "core/autograd.h"
#include "core/ops.h"
#include "tests/core/tiny_mlp.h"

namespace lc2wf {
namespace {

int64_t rss_bytes() {
  std::ifstream statm("/proc/self/statm");
  int64_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * sysconf(_SC_PAGESIZE);
}

TEST(Memory, ThousandTrainingStepsDoNotGrowRss) {
  auto [x, y] = test::make_regression(256, 8, 1);
  test::TinyMlp mlp(8, 64, 2);
  int64_t nodes = live_node_count();
  double first = 0, last = 0;
  int64_t rss_warm = 0;
  for (int step = 0; step < 1000; ++step) {
    double loss = mlp.step(x, y, 0.05);
    if (step == 0) first = loss;
    last = loss;
    ASSERT_EQ(live_node_count(), nodes) << "graph nodes left alive after step " << step;
    if (step == 99) rss_warm = rss_bytes();
  }
  int64_t growth = rss_bytes() - rss_warm;
  EXPECT_LT(growth, 2 << 20) << "RSS grew by " << growth << " bytes over 900 steps";
  EXPECT_LT(last, first);  // the loop really trains
}

TEST(Memory, InferenceUnderNoGradKeepsNoTape) {
  auto [x, y] = test::make_regression(128, 8, 3);
  test::TinyMlp mlp(8, 32, 4);
  int64_t nodes = live_node_count();
  NoGradGuard guard;
  Tensor out = mlp.forward(x, false);
  EXPECT_EQ(live_node_count(), nodes);
  EXPECT_FALSE(out.requires_grad());
}

TEST(Memory, OutputHandleAloneKeepsGraphThenReleasesIt) {
  int64_t nodes = live_node_count();
  {
    Tensor w = Tensor::ones({4, 4}).set_requires_grad();
    Tensor out = relu(linear(Tensor::ones({2, 4}), w));
    EXPECT_GT(live_node_count(), nodes);
  }
  // No cycle between an output and its node: dropping the handle frees the graph.
  EXPECT_EQ(live_node_count(), nodes);
}

}  // namespace
}  // namespace lc2wf
