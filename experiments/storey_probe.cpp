// The storey estimate (dataset/photo/storey_scale.h) on metric line clouds, whose true scale is 1 metre per
// unit: per cloud whether a rhythm was found, its storeys, strength and the scale error against the truth, so
// its thresholds are chosen on validation clouds, not on a benchmark (experiments/README.md, "Storeys").
//   lc2wf_storey_probe [--storey-height M] [--min-strength S] [--min-lines N] CLOUD.lcloud...
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "core/util/cli.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/photo/metric_frame.h"

using namespace lc2wf;

int main(int argc, char** argv) {
  StoreyScaleOptions o;
  std::vector<std::string> clouds;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string f = argv[i];
      if (f.rfind("--", 0) != 0) {
        clouds.push_back(f);
        continue;
      }
      const std::string v = flag_value(argc, argv, i);
      if (f == "--storey-height") o.storey_height_m = std::stod(v);
      else if (f == "--min-strength") o.min_strength = std::stod(v);
      else if (f == "--min-lines") o.min_lines = std::stoi(v);
      else throw UsageError("unknown argument '" + f + "'");
    }
    if (clouds.empty()) throw UsageError("usage: lc2wf_storey_probe [--storey-height M] [--min-strength S] [--min-lines N] CLOUD...");
    o.Check();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf_storey_probe: %s\n", e.what());
    return 2;
  }
  try {
    std::printf("name,height_m,vertical_lines,found,storeys,strength,scale_error,why_not\n");
    for (const std::string& path : clouds) {
      const LineCloud cloud = read_line_cloud(path);
      // The metric frame with its input z kept: the same ground and height as lc2wf-reconstruct takes.
      MetricFrameOptions fo;
      fo.up = UpSource::kInputZ;
      fo.storeys = o;
      const MetricFrame f = estimate_metric_frame({}, cloud.segments, fo);
      const StoreyScale& s = f.storeys;
      std::printf("%s,%.2f,%d,%d,%.2f,%.3f,%.4f,%s\n", std::filesystem::path(path).stem().c_str(), f.height_input, s.vertical_lines,
                  s.found ? 1 : 0, s.storeys, s.strength, s.found ? s.metres_per_unit - 1.0 : 0.0, s.why_not.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf_storey_probe: %s\n", e.what());
    return 1;
  }
  return 0;
}
