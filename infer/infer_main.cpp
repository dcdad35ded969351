// lc2wf-infer: line clouds -> predicted wireframes with a model trained by lc2wf-train.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "infer/batch_inference.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-infer --weights DIR CLOUD... -o OUT [options]

Predicts a 3D wireframe for each line cloud: junction sampling -> junction model -> junction NMS and
confidence threshold -> all pairs -> edge model -> post-processing (identical-pair pruning, candidate
edges, isolated-edge removal, Hamming junction merge, line NMS, dangling-edge removal).
Writes OUT/<name>.obj ('v' + 'l', metres) and OUT/<name>.json (junction confidences, edge
probabilities and notes on degenerate inputs). A cloud with no usable junction or edge gives an empty
wireframe and a note, never a failure.

  --weights DIR       junction.safetensors + edge.safetensors written by lc2wf-train
  -o, --out OUT       output folder
  --units U           metres (default) or raw: coordinates of the written .obj (raw = the source
                      dataset's units, e.g. Roof-Image / release JSON, 20 raw = 1 m)
  --preview PNG       also draw cloud (grey), prediction (red) and GT (green, when the cloud has it);
                      with one cloud PNG is the file, with several it is a folder for <name>.png
  --release-quirks    post-process exactly as the paper's release (suppressor NMS, lower-confidence
                      edge kept by line NMS, no edge transfer on junction merge); default: sound rules
  --format F          auto (default), lc2wf or release (LineCloud JSON)
  --threads N         compute threads (default: all)
  --quiet             no progress output
  -h, --help          this text
Exit codes: 0 success, 1 some input could not be read / weights missing, 2 bad command line.
)";

}  // namespace

int main(int argc, char** argv) {
  fs::path weights, out;
  std::string preview;
  std::vector<fs::path> clouds;
  BatchInferenceOptions options;
  int threads = 0;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string f = argv[i];
      if (f == "-h" || f == "--help") {
        std::fputs(kUsage, stdout);
        return 0;
      }
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(f + " needs a value");
        return argv[++i];
      };
      if (f == "--weights") weights = value();
      else if (f == "-o" || f == "--out") out = value();
      else if (f == "--preview") preview = value();
      else if (f == "--release-quirks") options.post = PostProcessOptions::release_quirks();
      else if (f == "--quiet") options.quiet = true;
      else if (f == "--format") options.format = parse_cloud_format(value(), "--format");
      else if (f == "--threads") threads = std::stoi(value());
      else if (f == "--units") {
        const std::string u = value();
        if (u == "raw") options.raw_units = true;
        else if (u != "metres" && u != "meters") throw std::invalid_argument("--units must be 'metres' or 'raw', got '" + u + "'");
      } else if (!f.empty() && f[0] == '-') {
        throw std::invalid_argument("unknown option '" + f + "'");
      } else {
        clouds.push_back(f);
      }
    }
    if (weights.empty()) throw std::invalid_argument("--weights DIR is required");
    if (out.empty()) throw std::invalid_argument("-o OUT is required");
    if (clouds.empty()) throw std::invalid_argument("no line cloud given");
    if (threads < 0) throw std::invalid_argument("--threads must be >= 0");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-infer: %s\nRun 'lc2wf-infer --help' for usage.\n", e.what());
    return 2;
  }
  if (!preview.empty()) {
    const fs::path p = preview;
    if (clouds.size() == 1) options.preview_path = [p](const std::string&) { return p; };
    else options.preview_path = [p](const std::string& name) { return p / (name + ".png"); };
  }
  try {
    set_num_threads(threads);
    const WireframePredictor predictor(weights);
    const BatchInferenceSummary s = infer_clouds(predictor, clouds, out, options);
    if (!options.quiet && s.buildings > 0)
      std::fprintf(stderr,
                   "lc2wf-infer: %d building(s) -> %s (%d empty); %.3f s per building on average (junction %.3f, "
                   "edge %.3f, post-processing %.3f), max %.3f s\n",
                   s.buildings, out.string().c_str(), s.empty, s.total_seconds / s.buildings,
                   s.junction_seconds / s.buildings, s.edge_seconds / s.buildings, s.post_seconds / s.buildings,
                   s.max_seconds);
    return s.failed > 0 ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-infer: error: %s\n", e.what());
    return 1;
  }
}
