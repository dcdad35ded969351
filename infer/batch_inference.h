// Inference over a list of line-cloud files: predictions written with infer/prediction_io.h
// (`<out>/<name>.obj` + `<name>.json` with scores and notes), optional previews, and a timing summary.
// Shared by lc2wf-infer and lc2wf-eval --weights.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/matmul_precision.h"
#include "dataset/formats/cloud_input.h"
#include "model/inference.h"
#include "infer/inference_timing.h"

namespace lc2wf {

struct BatchInferenceOptions {
  PostProcessOptions post;
  CloudFormat format = CloudFormat::kAuto;
  double raw_per_metre = kRawUnitsPerMetre;  // release JSON only
  bool raw_units = false;       // write raw (source) coordinates instead of metres
  // Where the preview PNG of a building goes; empty function = no previews.
  std::function<std::filesystem::path(const std::string& name)> preview_path;
  bool quiet = false;
  // fp32 gives the same numbers on every CPU; bf16 operands are faster where the CPU has AVX512-BF16.
  MatmulPrecision precision = MatmulPrecision::kFp32;
};

// The --precision flag of the inference commands: fp32, bf16 or auto; a bad value is a usage error.
MatmulPrecision precision_flag(const std::string& value);

struct BatchInferenceSummary : InferenceTiming {
  int failed = 0;           // unreadable clouds (reported on stderr)
  std::vector<std::string> names;  // predicted buildings, input order
};

BatchInferenceSummary infer_clouds(const WireframePredictor& predictor, const std::vector<std::filesystem::path>& clouds,
                                   const std::filesystem::path& out_dir, const BatchInferenceOptions& options);

}  // namespace lc2wf
