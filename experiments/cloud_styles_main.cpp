// lc2wf-cloud-styles: the same held-out buildings as clouds of several kinds, to measure how a model
// trained on one extractor's clouds serves others (experiments/robustness.sh scores a model on each).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/util/cli.h"
#include "dataset/formats/line3dpp_io.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/long_fragment_cloud.h"
#include "dataset/formats/mesh_io.h"
#include "dataset/sampling/rng.h"
#include "dataset/geometry/segment_split.h"
#include "dataset/splits/splits.h"
#include "dataset/synthetic/surface_clutter.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-cloud-styles --data DIR --split FILE -o OUT [--seed S] [-q]

For every building of FILE, reads DIR/<name>.lcloud (a labelled cloud of lc2wf-dataset) and writes
  OUT/own/<name>.lcloud       the cloud as it is
  OUT/line3dpp/<name>.txt     the same segments through the Line3D++ .txt writer and reader path
  OUT/long/<name>.lcloud      every GT edge as 2-5 long fragments with 2 cm noise, plus half of the
                              cloud's non-edge lines (dataset/synthetic/long_fragment_cloud.h)
  OUT/long-line3dpp/<name>.txt  the same as a Line3D++ .txt, as such a map would come
  OUT/edges/<name>.lcloud     only the cloud's lines on a GT edge (f = 1): what the other lines cost
  OUT/photo/<name>.lcloud     the cloud plus texture lines as a textured-photo reconstruction has them:
                              2.5 per segment on the faces, 3.5 on the ground around the building
                              (dataset/synthetic/surface_clutter.h)
  OUT/gt/<name>.obj           the ground truth in metres, for lc2wf-eval --gt
Prints on stdout, per kind, the share of long segments another segment overlaps and how many clouds the
rule of --max-segment-length auto (dataset/geometry/segment_split.h) would cut were they read from a line map.
Deterministic for a seed and the split's order.

  --data DIR     labelled line clouds
  --split FILE   building names, one per line
  -o, --out DIR  output folder
  --seed S       seed of the long fragments and the texture lines (default 1555)
  -q, --quiet    no summary line
)";

struct Args {
  fs::path data, split, out;
  uint64_t seed = 1555;
  bool quiet = false;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    if (f == "--data") a.data = flag_value(argc, argv, i);
    else if (f == "--split") a.split = flag_value(argc, argv, i);
    else if (f == "-o" || f == "--out") a.out = flag_value(argc, argv, i);
    else if (f == "-q" || f == "--quiet") a.quiet = true;
    else if (f == "--seed") a.seed = static_cast<uint64_t>(parse_count_flag(f, flag_value(argc, argv, i)));
    else throw UsageError("unknown option '" + f + "'");
  }
  if (a.data.empty() || a.split.empty() || a.out.empty()) throw UsageError("--data, --split and -o are required");
  return a;
}

constexpr uint64_t kPhotoStream = 0x9407u;

LineCloud edge_lines_only(const LineCloud& cloud) {
  std::vector<bool> keep(cloud.segments.size(), false);
  for (size_t i = 0; i < cloud.labels.size(); ++i) keep[i] = cloud.labels[i].f;
  return keep_segments(cloud, keep);
}

// The proportions of the SfM-texture renders of 11 test buildings (reconstruct/README.md): ≈ 5,000 lines,
// of them ≈ 1,700 on the building's surfaces off its edges and ≈ 2,500 on the ground around it.
SurfaceClutterOptions photo_clutter(const LineCloud& cloud) {
  SurfaceClutterOptions o;
  o.face_lines = static_cast<int>(2.5 * static_cast<double>(cloud.segments.size()));
  o.ground_lines = static_cast<int>(3.5 * static_cast<double>(cloud.segments.size()));
  return o;
}

// How far each style is from a merged line map (the --max-segment-length auto rule), over the split.
struct OverlapRange {
  double low = 1.0, high = 0.0, sum = 0.0;
  int clouds = 0, merged = 0;
  void add(const LineCloud& cloud) {
    const double f = overlapped_long_fraction(cloud, kMergedMapPieceLength);
    low = std::min(low, f), high = std::max(high, f), sum += f, ++clouds, merged += f < kMergedMapOverlap;
  }
};

int run(const Args& a) {
  const auto names = read_name_list(a.split);  // before OUT is made: a bad split writes nothing
  if (names.empty()) throw std::runtime_error(a.split.string() + ": names no building (nothing to do)");
  for (const char* kind : {"own", "line3dpp", "long", "long-line3dpp", "edges", "photo", "gt"}) fs::create_directories(a.out / kind);
  std::map<std::string, OverlapRange> overlap;
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    const LineCloud cloud = read_line_cloud(a.data / (name + ".lcloud"));
    const LineCloud styles[] = {
        cloud, make_long_fragment_cloud(cloud, LongFragmentOptions{}, mix_seed(a.seed, i)), edge_lines_only(cloud),
        with_surface_clutter(cloud, photo_clutter(cloud), mix_seed(a.seed ^ kPhotoStream, i))};
    const char* kinds[] = {"own", "long", "edges", "photo"};
    for (int k = 0; k < 4; ++k) {
      write_line_cloud(a.out / kinds[k] / (name + ".lcloud"), styles[k]);
      overlap[kinds[k]].add(styles[k]);
    }
    write_line3dpp_txt(a.out / "line3dpp" / (name + ".txt"), cloud);
    write_line3dpp_txt(a.out / "long-line3dpp" / (name + ".txt"), styles[1]);
    write_obj_wireframe(a.out / "gt" / (name + ".obj"), cloud.wireframe);
  }
  std::printf("| clouds | long segments overlapped (min / mean / max) | cut if read from a line map |\n|---|---|---|\n");
  for (const auto& [kind, r] : overlap)
    std::printf("| %s | %.2f / %.2f / %.2f | %d of %d |\n", kind.c_str(), r.low, r.sum / std::max(1, r.clouds), r.high,
                r.merged, r.clouds);
  if (!a.quiet) std::fprintf(stderr, "lc2wf-cloud-styles: %zu buildings -> %s\n", names.size(), a.out.string().c_str());
  return kExitDone;
}

}  // namespace

int main(int argc, char** argv) { return lc2wf::cli_main({"lc2wf-cloud-styles", kUsage, {}}, argc, argv, parse_args, run); }
