// Prediction files lc2wf-eval reads: the .obj wireframe and its scores sidecar (.json).
#include <sstream>

#include "dataset/formats/mesh_io.h"
#include "fuzz_common.h"
#include "infer/prediction_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = lc2wf::fuzz::bytes(data, size);
  lc2wf::fuzz::expect_clean_rejection([&] { (void)lc2wf::parse_scores_json(text, "fuzz.json"); });
  return 0;
}
