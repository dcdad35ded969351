// JSON configs: the network, loss and optimiser sections (nn) and the whole lc2wf-train config.
#include <nlohmann/json.hpp>

#include "fuzz_common.h"
#include "nn/config.h"
#include "train/train_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    const nlohmann::json j = nlohmann::json::parse(lc2wf::fuzz::bytes(data, size));
    lc2wf::fuzz::expect_clean_rejection([&] { lc2wf::JunctionNetConfig::from_json(j, "net").Check(); });
    lc2wf::fuzz::expect_clean_rejection([&] { lc2wf::EdgeNetConfig::from_json(j, "net").Check(); });
    lc2wf::fuzz::expect_clean_rejection([&] { lc2wf::OptimConfig::from_json(j, "optim").Check(); });
    lc2wf::fuzz::expect_clean_rejection([&] { (void)lc2wf::TrainConfig::from_json(j); });
  });
  return 0;
}
