// lc2wf-cloud-convert: one of our line clouds -> Line3D++ `.txt` (with supports) or a line OBJ, so other
// tools (LIMAP, Line2Surf, MeshLab) can read it and our readers can be tested on a known cloud.
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/util/cli.h"
#include "dataset/formats/line3dpp_io.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/formats/line_obj_io.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;

const char* kUsage = R"(Usage: lc2wf-cloud-convert CLOUD -o OUT [--to line3dpp|obj]

Writes our line cloud CLOUD (.lcloud / .lc2wf) as a Line3D++ .txt (default; one line per 3D segment,
"1 P Q m" then per support "camera segment p q" with camera = view + 1, as COLMAP numbers images) or as
a line OBJ ('v' per endpoint, 'l' per segment). Coordinates in metres, 9 significant digits. Ground
truth and labels are not written (neither format has them). One thread.

  -o, --out OUT       output file (written atomically)
  --to F              line3dpp (default) or obj
  -q, --quiet         no message on stderr
)";

struct Args {
  fs::path in, out;
  std::string to = "line3dpp";
  bool quiet = false;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    if (f == "-o" || f == "--out") a.out = flag_value(argc, argv, i);
    else if (f == "--to") a.to = flag_value(argc, argv, i);
    else if (f == "-q" || f == "--quiet") a.quiet = true;
    else if (!f.empty() && f[0] == '-') throw UsageError("unknown option '" + f + "'");
    else if (a.in.empty()) a.in = f;
    else throw UsageError("one input cloud only, got '" + f + "' too");
  }
  if (a.in.empty()) throw UsageError("no input cloud given");
  if (a.out.empty()) throw UsageError("-o OUT is required");
  if (a.to != "line3dpp" && a.to != "obj") throw UsageError("--to must be line3dpp or obj, got '" + a.to + "'");
  return a;
}

int run(const Args& a) {
  const LineCloud cloud = read_line_cloud(a.in);
  if (a.to == "obj") write_line_obj(a.out, cloud);
  else write_line3dpp_txt(a.out, cloud);
  if (!a.quiet) std::fprintf(stderr, "lc2wf-cloud-convert: %zu segments -> %s\n", cloud.segments.size(), a.out.string().c_str());
  return kExitDone;
}

}  // namespace

int main(int argc, char** argv) { return cli_main({"lc2wf-cloud-convert", kUsage, {}}, argc, argv, parse_args, run); }
