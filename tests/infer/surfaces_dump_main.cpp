// Runs the face finder on stored predictions (NAME.obj + NAME.json, as lc2wf-infer writes them) and prints,
// per building, the graph size, the time, the status, the reasons and the faces (vertex coordinates in mm, in
// ring order), so two builds can be compared face for face: `lc2wf_surfaces_dump OUT.txt PRED.obj...` writes
// the faces to OUT.txt and one line per building with its time to stdout (the time stays out of OUT.txt).
// `--repeat N` (first argument) runs each building N times and reports the least time (a loaded machine).
#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "infer/prediction_io.h"
#include "infer/surfaces/wireframe_surfaces.h"

int main(int argc, char** argv) {
  using namespace lc2wf;
  int first = 1, repeat = 1;
  if (argc > 2 && std::string(argv[1]) == "--repeat") repeat = std::max(1, std::atoi(argv[2])), first = 3;
  if (argc < first + 2) {
    std::fprintf(stderr, "usage: %s [--repeat N] OUT.txt PREDICTION.obj...\n", argv[0]);
    return 2;
  }
  std::ofstream out(argv[first]);
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", argv[first]);
    return 1;
  }
  try {
    for (int a = first + 1; a < argc; ++a) {
      const std::filesystem::path obj = argv[a];
      const ScoredWireframe p = read_prediction(obj);
      SurfaceModel m;
      double ms = INFINITY;
      for (int r = 0; r < repeat; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        m = surfaces_from_wireframe(p.wireframe, p.edge_scores);
        ms = std::min(ms, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      }
      const std::string name = obj.stem().string();
      std::printf("%-80s junctions %4zu edges %4zu  %10.2f ms  %10ld steps  %s, %zu faces\n", name.c_str(),
                  p.wireframe.junctions.size(), p.wireframe.edges.size(), ms, m.work_steps, to_string(m.status), m.faces.size());
      out << name << " " << to_string(m.status) << " " << m.faces.size() << " faces\n";
      for (const std::string& r : m.reasons) out << "  reason: " << r << "\n";
      for (const SurfaceFace& f : m.faces) {
        out << "  " << to_string(f.label) << ":";
        for (int v : f.ring)
          out << " (" << std::lround(m.vertices[v].x() * 1000) << "," << std::lround(m.vertices[v].y() * 1000) << ","
              << std::lround(m.vertices[v].z() * 1000) << ")";
        out << "\n";
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
