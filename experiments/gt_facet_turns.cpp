// How much of a GT wireframe lies between faces that barely turn: for every mesh edge of the named buildings,
// the angle between the normals of the faces that share it, and the share of the edges (by count and by
// length) under 10 / 20 / 30 degrees, split into edges between two walls (the facets of a polygonised round
// tower, bay or chimney) and the rest. A polygonised curve's facet edges draw no line in any render; this sizes
// a GT rule that would drop them (experiments/README.md, "Where the real score is lost").
//   lc2wf_gt_facet_turns --meshes FOLDER --split FILE
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/util/cli.h"
#include "dataset/formats/building_sources.h"
#include "dataset/splits/splits.h"

namespace fs = std::filesystem;
using namespace lc2wf;

namespace {

constexpr std::array<double, 3> kTurns = {10.0, 20.0, 30.0};

Vec3 newell_normal(const std::vector<Vec3>& v, const std::vector<int>& face) {
  Vec3 n = Vec3::Zero();
  for (size_t k = 0; k < face.size(); ++k) {
    const Vec3& a = v[face[k]];
    const Vec3& b = v[face[(k + 1) % face.size()]];
    n += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()), (a.x() - b.x()) * (a.y() + b.y()));
  }
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : n;
}

struct Tally {
  double edges = 0, length = 0;
  std::array<double, 3> under{}, under_length{};
};

}  // namespace

int main(int argc, char** argv) {
  fs::path meshes, split;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string f = argv[i];
      const std::string v = flag_value(argc, argv, i);
      if (f == "--meshes") meshes = v;
      else if (f == "--split") split = v;
      else throw UsageError("unknown argument '" + f + "'");
    }
    if (meshes.empty() || split.empty()) throw UsageError("usage: lc2wf_gt_facet_turns --meshes FOLDER --split FILE");
  } catch (const UsageError& e) {
    std::fprintf(stderr, "lc2wf_gt_facet_turns: %s\n", e.what());
    return 2;
  }
  try {
    const BuildingCatalog catalog(meshes);
    Tally walls, others;
    int skipped = 0;
    for (const std::string& name : read_name_list(split)) {
      Building b;
      try {
        b = catalog.load(name);
      } catch (const BuildingSkipped&) {
        ++skipped;
        continue;
      }
      const PolyMesh& m = b.mesh;
      std::vector<Vec3> normal;
      for (const auto& face : m.faces) normal.push_back(newell_normal(m.vertices, face));
      std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
      for (size_t f = 0; f < m.faces.size(); ++f)
        for (size_t k = 0; k < m.faces[f].size(); ++k) {
          const int a = m.faces[f][k], c = m.faces[f][(k + 1) % m.faces[f].size()];
          faces_of_edge[{std::min(a, c), std::max(a, c)}].push_back(static_cast<int>(f));
        }
      for (const auto& [edge, faces] : faces_of_edge) {
        if (faces.size() < 2) continue;  // a border: no turn to measure
        double turn = 0;                 // the largest turn between any two of its faces, degrees in [0, 90]
        bool all_walls = true;
        for (size_t i = 0; i < faces.size(); ++i) {
          const Vec3& ni = normal[faces[i]];
          all_walls = all_walls && std::abs(ni.z()) < 0.1;
          for (size_t j = i + 1; j < faces.size(); ++j) {
            const double c = std::abs(ni.dot(normal[faces[j]]));
            turn = std::max(turn, std::acos(std::min(1.0, c)) * 180.0 / M_PI);
          }
        }
        Tally& t = all_walls ? walls : others;
        const double length = (m.vertices[edge.first] - m.vertices[edge.second]).norm();
        t.edges += 1, t.length += length;
        for (size_t k = 0; k < kTurns.size(); ++k)
          if (turn < kTurns[k]) t.under[k] += 1, t.under_length[k] += length;
      }
    }
    const double all_edges = walls.edges + others.edges, all_length = walls.length + others.length;
    std::printf("| edges between | edges | share of all GT edges / length |");
    for (double d : kTurns) std::printf(" turning < %.0f°: share of all edges / length |", d);
    std::printf("\n|---|---|---|---|---|---|\n");
    for (const auto& [label, t] : {std::pair<const char*, const Tally&>{"two walls", walls}, {"a roof or ground face", others}}) {
      std::printf("| %s | %.0f | %.1f %% / %.1f %% |", label, t.edges, 100 * t.edges / all_edges, 100 * t.length / all_length);
      for (size_t k = 0; k < kTurns.size(); ++k)
        std::printf(" %.1f %% / %.1f %% |", 100 * t.under[k] / all_edges, 100 * t.under_length[k] / all_length);
      std::printf("\n");
    }
    std::printf("\n%d building(s) skipped by the clean-up.\n", skipped);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lc2wf_gt_facet_turns: %s\n", e.what());
    return 3;
  }
  return 0;
}
