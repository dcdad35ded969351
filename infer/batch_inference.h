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
#include "infer/map_frame.h"
#include "infer/surfaces/surface_options.h"

namespace lc2wf {

struct BatchInferenceOptions {
  PostProcessOptions post;
  CloudFormat format = CloudFormat::kAuto;
  double raw_per_metre = kRawUnitsPerMetre;  // release JSON only
  bool raw_units = false;       // write raw (source) coordinates instead of metres
  // Where the preview PNG of a building goes; empty function = no previews.
  std::function<std::filesystem::path(const std::string& name)> preview_path;
  bool quiet = false;
  // fp32 gives the same numbers at any thread count (the CPU's kernel class moves the last bits); bf16
  // operands are faster where the CPU has AVX512-BF16.
  MatmulPrecision precision = MatmulPrecision::kFp32;
  // Also write the LoD2 surfaces beside each wireframe (<name>.city.json, <name>.faces.obj; infer/surfaces/).
  bool write_surfaces = false;
  SurfaceOptions surfaces;
  // Line maps made elsewhere put in the networks' frame first (up, ground, scale: infer/map_frame.h), with
  // <name>.frame.json beside the outputs; off = their coordinates are taken as metres, z up.
  MapFrameOptions map_frame;
};

// The --precision flag of the inference commands: fp32, bf16 or auto; a bad value is a usage error.
MatmulPrecision precision_flag(const std::string& value);

struct BatchInferenceSummary : InferenceTiming {
  int failed = 0;           // unreadable clouds (reported on stderr)
  int closed_solids = 0;    // with write_surfaces: buildings whose surfaces close into a valid solid
  double surface_seconds = 0;  // with write_surfaces: finding the faces, summed over buildings (file I/O excluded)
  int framed = 0;              // maps put in the networks' frame (map_frame)
  double frame_seconds = 0;    // their frame and scale search, the final inference included
  std::vector<std::string> names;  // predicted buildings, input order
};

BatchInferenceSummary infer_clouds(const WireframePredictor& predictor, const std::vector<std::filesystem::path>& clouds,
                                   const std::filesystem::path& out_dir, const BatchInferenceOptions& options);

}  // namespace lc2wf
