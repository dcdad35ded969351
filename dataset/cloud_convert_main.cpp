// lc2wf-cloud-convert: one of our line clouds -> Line3D++ `.txt` (with supports) or a line OBJ, so other
// tools (LIMAP, Line2Surf, MeshLab) can read it and our readers can be tested on a known cloud.
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/util/cli.h"
#include "dataset/line3dpp_io.h"
#include "dataset/line_cloud_io.h"
#include "dataset/line_obj_io.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-cloud-convert CLOUD -o FILE [--to line3dpp|obj]

Writes our line cloud CLOUD (.lcloud / .lc2wf) as a Line3D++ .txt (default; one line per 3D segment,
"1 P Q m" then per support "camera segment p q" with camera = view + 1, as COLMAP numbers images) or as
a line OBJ ('v' per endpoint, 'l' per segment). Coordinates in metres, 9 significant digits. Ground
truth and labels are not written (neither format has them).

  -o, --out FILE     output file (written atomically)
  --to F             line3dpp (default) or obj
  -h, --help         this text
Exit codes: 0 success, 2 bad command line, 3 unreadable cloud or write error.
)";

struct Args {
  fs::path in, out;
  std::string to = "line3dpp";
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    if (f == "-o" || f == "--out") a.out = flag_value(argc, argv, i);
    else if (f == "--to") a.to = flag_value(argc, argv, i);
    else if (!f.empty() && f[0] == '-') throw UsageError("unknown option '" + f + "'");
    else if (a.in.empty()) a.in = f;
    else throw UsageError("one input cloud only, got '" + f + "' too");
  }
  if (a.in.empty()) throw UsageError("no input cloud given");
  if (a.out.empty()) throw UsageError("-o FILE is required");
  if (a.to != "line3dpp" && a.to != "obj") throw UsageError("--to must be line3dpp or obj, got '" + a.to + "'");
  return a;
}

int run(const Args& a) {
  try {
    const LineCloud cloud = read_line_cloud(a.in);
    if (a.to == "obj") write_line_obj(a.out, cloud);
    else write_line3dpp_txt(a.out, cloud);
    std::fprintf(stderr, "lc2wf-cloud-convert: %zu segments -> %s\n", cloud.segments.size(), a.out.string().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf-cloud-convert: error: %s\n", e.what());
    return 3;
  }
}

}  // namespace

int main(int argc, char** argv) { return cli_main("lc2wf-cloud-convert", kUsage, argc, argv, parse_args, run); }
