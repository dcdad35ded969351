// Cameras JSON (views/cameras.json, the cameras inside a line cloud): one camera or an array of them.
#include <nlohmann/json.hpp>

#include "dataset/formats/camera_json.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    const nlohmann::json j = nlohmann::json::parse(lc2wf::fuzz::bytes(data, size));
    if (j.is_array())
      for (const auto& c : j) (void)lc2wf::camera_from_json(c, "fuzz.json");
    else
      (void)lc2wf::camera_from_json(j, "fuzz.json");
  });
  return 0;
}
