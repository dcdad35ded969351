// Safetensors weights and their metadata: the checkpoint's network config must pass Check() before a
// network of that size would be built.
#include <nlohmann/json.hpp>

#include "fuzz_common.h"
#include "nn/config.h"
#include "nn/safetensors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    const lc2wf::SafetensorsFile file = lc2wf::parse_safetensors(lc2wf::fuzz::bytes(data, size), "fuzz.safetensors");
    const auto it = file.metadata.find("config");
    if (it == file.metadata.end()) return;
    const nlohmann::json config = nlohmann::json::parse(it->second);
    if (config.contains("net")) lc2wf::JunctionNetConfig::from_json(config.at("net"), "net").Check();
  });
  return 0;
}
