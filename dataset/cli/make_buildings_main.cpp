// lc2wf-make-buildings: procedural LoD2 buildings of every roof kind and size, or augmented copies of
// existing meshes, as Roof-Image .polyshape files that lc2wf-dataset --meshes reads unchanged.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/util/cli.h"
#include "core/util/fnv1a.h"
#include "core/util/version.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/mesh_io.h"
#include "dataset/geometry/building.h"
#include "dataset/geometry/mesh_augmentation.h"
#include "dataset/sampling/rng.h"
#include "dataset/synthetic/lod2_generator.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;
using nlohmann::json;

const char* kUsage = R"(Usage: lc2wf-make-buildings --count N -o OUT [--seed S] [--kinds SPEC] [--no-turn] [-q]
       lc2wf-make-buildings --augment DIR -o OUT [--copies K] [--seed S] [--height-min M] [--height-max M]
                            [--stretch-min X] [--stretch-max X] [--keep-height] [--no-turn] [-q]

Writes procedural LoD2 buildings (closed meshes labelled roof / base / wall, 20 raw units per metre) as
Roof-Image .polyshape files named gen_<kind>_<index>, plus OUT/buildings.json (per building: kind, seed,
height, footprint size, vertices, edges, faces) and a summary on stdout. lc2wf-dataset --meshes OUT turns
them into line clouds. Kinds: flat, flat_multi, gabled, hipped, pyramid, shed, mansard, gambrel, saw_tooth,
multi_part, l_shape, t_shape, u_shape, courtyard, dormers, row_houses, tower, large_block. Building i is
drawn from (seed, i) alone: the first N of a larger run are the same buildings. One thread.

  --count N            buildings to generate (1 .. 1000000)
  --seed S             seed (default 1)
  --kinds SPEC         kinds and relative weights: "all" (default, equal weights), "gabled,shed" (those
                       only), "gabled:3,flat:1"
  --no-turn            keep footprints axis-aligned (default: a random turn about the vertical)
  --augment DIR        instead: K augmented copies of every .polyshape in DIR, named <name>_aug<k>: height
                       scaled to a target, the footprint stretched along x and y, turned; ground kept at 0
  --copies K           copies per mesh with --augment (default 1)
  --height-min M, --height-max M   target height range, metres, drawn log-uniform (default 3, 60)
  --keep-height        do not scale the height
  --stretch-min X, --stretch-max X horizontal scale per axis, drawn log-uniform (default 0.8, 1.25)
  -o, --out OUT        output folder
  -q, --quiet          no summary on stdout
With --augment, a mesh that cannot be read is named on stderr and skipped (exit 1); none readable: exit 3.
)";

struct Args {
  fs::path out, augment;
  long long count = 0;
  int copies = 1;
  uint64_t seed = 1;
  Lod2Options generator;
  MeshAugmentOptions augmentation;
  bool quiet = false;
};

Args parse_args(int argc, char** argv) {
  Args a;
  bool count_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return flag_value(argc, argv, i); };
    if (f == "--count") {
      a.count = parse_count_flag(f, value());
      count_given = true;
    } else if (f == "--seed") a.seed = static_cast<uint64_t>(parse_count_flag(f, value()));
    else if (f == "--kinds") {
      try {
        a.generator.kinds = parse_lod2_kind_weights(value());
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--kinds: ") + e.what());
      }
    } else if (f == "--no-turn") {
      a.generator.turn = false;
      a.augmentation.turn = false;
    } else if (f == "--augment") a.augment = value();
    else if (f == "--copies") {
      const long long k = parse_count_flag(f, value());
      if (k < 1 || k > 1000) throw UsageError("--copies must be in 1..1000");
      a.copies = static_cast<int>(k);
    } else if (f == "--height-min") a.augmentation.height_min_m = number_flag(f, value());
    else if (f == "--height-max") a.augmentation.height_max_m = number_flag(f, value());
    else if (f == "--stretch-min") a.augmentation.stretch_min = number_flag(f, value());
    else if (f == "--stretch-max") a.augmentation.stretch_max = number_flag(f, value());
    else if (f == "--keep-height") a.augmentation.scale_height = false;
    else if (f == "-o" || f == "--out") a.out = value();
    else if (f == "-q" || f == "--quiet") a.quiet = true;
    else throw UsageError("unknown option '" + f + "'");
  }
  if (a.out.empty()) throw UsageError("-o OUT is required");
  if (a.augment.empty() == !count_given) throw UsageError("give either --count N or --augment DIR");
  if (count_given && (a.count < 1 || a.count > 1000000)) throw UsageError("--count must be in 1..1000000");
  check_options([&] { a.augmentation.Check(); },
                {{"MeshAugmentOptions.height_min_m", "--height-min"}, {"MeshAugmentOptions.height_max_m", "--height-max"},
                 {"MeshAugmentOptions.stretch_min", "--stretch-min"}, {"MeshAugmentOptions.stretch_max", "--stretch-max"}});
  a.generator.Check();
  if (!a.augment.empty() && !fs::is_directory(a.augment))
    throw std::runtime_error(a.augment.string() + ": no such folder (--augment)");
  if (!a.augment.empty() && list_polyshape_names(a.augment).empty())
    throw std::runtime_error(a.augment.string() + ": no .polyshape mesh: nothing to augment");
  return a;
}

// Nearest-rank percentile of an unsorted list.
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t k = static_cast<size_t>(std::min<double>(v.size() - 1, std::max(0.0, p / 100.0 * v.size() - 0.5)));
  return v[k];
}

json mesh_facts(const PolyMesh& m) {
  const MeshReport r = analyse_mesh(m, 0.0);
  Eigen::AlignedBox3d box;
  for (const Vec3& v : m.vertices) box.extend(v);
  return {{"vertices", m.vertices.size()}, {"edges", build_wireframe(m).edges.size()}, {"faces", m.faces.size()},
          {"roof_faces", r.roof_faces}, {"height_m", box.max().z() - box.min().z()}};
}

// Prints the per-kind counts and the distributions of height, footprint and size.
void print_summary(const json& buildings, const fs::path& out) {
  std::map<std::string, int> kinds;
  std::vector<double> heights, longs, vertices, edges;
  for (const json& b : buildings) {
    ++kinds[b.value("kind", std::string("augmented"))];
    heights.push_back(b["height_m"].get<double>());
    longs.push_back(b["footprint_long_m"].get<double>());
    vertices.push_back(b["vertices"].get<double>());
    edges.push_back(b["edges"].get<double>());
  }
  std::printf("%zu buildings -> %s\n", buildings.size(), out.string().c_str());
  for (const auto& [kind, n] : kinds) std::printf("  %-12s %6d  %5.1f %%\n", kind.c_str(), n, 100.0 * n / buildings.size());
  auto row = [](const char* what, const std::vector<double>& v) {
    std::printf("  %-26s p10 %7.1f  p50 %7.1f  p90 %7.1f\n", what, percentile(v, 10), percentile(v, 50), percentile(v, 90));
  };
  row("height, m", heights);
  row("footprint long side, m", longs);
  row("vertices per building", vertices);
  row("edges per building", edges);
}

json generate(const Args& a) {
  json list = json::array();
  const UnitTransform raw{kRawUnitsPerMetre, Vec3::Zero()};
  for (long long i = 0; i < a.count; ++i) {
    const uint64_t seed = mix_seed(a.seed, static_cast<uint64_t>(i));
    const GeneratedBuilding b = generate_lod2_building(seed, a.generator);
    char name[96];
    std::snprintf(name, sizeof name, "gen_%s_%06lld", lod2_kind_name(b.kind), i);
    write_polyshape(a.out / (std::string(name) + ".polyshape"), b.mesh, &raw);
    json entry = {{"name", name}, {"kind", lod2_kind_name(b.kind)}, {"seed", seed}, {"footprint_long_m", b.footprint_long_m},
                  {"footprint_short_m", b.footprint_short_m}, {"attempts", b.attempts}};
    entry.update(mesh_facts(b.mesh));
    list.push_back(entry);
    if (!a.quiet && (i + 1) % 100 == 0) std::fprintf(stderr, "\r%lld / %lld buildings", i + 1, a.count);
  }
  if (!a.quiet && a.count >= 100) std::fprintf(stderr, "\n");
  return list;
}

json augment(const Args& a, int* skipped) {
  json list = json::array();
  const UnitTransform raw{kRawUnitsPerMetre, Vec3::Zero()};
  const std::vector<std::string> names = list_polyshape_names(a.augment);
  for (const std::string& name : names) {
    PolyMesh mesh;
    try {
      mesh = read_polyshape(a.augment / (name + ".polyshape"));
      for (Vec3& v : mesh.vertices) v = raw.to_metres(v);
      augment_mesh(mesh, MeshAugmentation{});  // refuses a mesh without height before anything is written
    } catch (const std::exception& e) {
      std::fprintf(stderr, "skipped %s: %s\n", name.c_str(), e.what());
      ++*skipped;
      continue;
    }
    for (int k = 0; k < a.copies; ++k) {
      const uint64_t seed = mix_seed(mix_seed(a.seed, fnv1a64(name)), static_cast<uint64_t>(k));
      const MeshAugmentation draw = draw_mesh_augmentation(seed, a.augmentation);
      const PolyMesh out = augment_mesh(mesh, draw);
      const std::string copy = name + "_aug" + std::to_string(k);
      write_polyshape(a.out / (copy + ".polyshape"), out, &raw);
      Eigen::AlignedBox3d box;
      for (const Vec3& v : mesh.vertices) box.extend(v);
      const double fx = box.sizes().x() * draw.scale_x, fy = box.sizes().y() * draw.scale_y;
      json entry = {{"name", copy}, {"source", name}, {"seed", seed}, {"scale_x", draw.scale_x}, {"scale_y", draw.scale_y},
                    {"turn_rad", draw.turn_rad}, {"footprint_long_m", std::max(fx, fy)}, {"footprint_short_m", std::min(fx, fy)}};
      entry.update(mesh_facts(out));
      list.push_back(entry);
    }
  }
  if (names.empty() || static_cast<size_t>(*skipped) == names.size())
    throw std::runtime_error(a.augment.string() + ": no readable .polyshape mesh: nothing to augment");
  return list;
}

int run(const Args& a) {
  fs::create_directories(a.out);
  int skipped = 0;
  const json buildings = a.augment.empty() ? generate(a) : augment(a, &skipped);
  json doc = {{"format", "lc2wf-generated-buildings"}, {"version", lc2wf_version()}, {"commit", lc2wf_git_commit()},
              {"seed", a.seed}, {"units", {{"raw_per_metre", kRawUnitsPerMetre}}}, {"buildings", buildings}};
  if (!a.augment.empty()) doc["augmented_from"] = a.augment.string();
  write_file_atomic(a.out / "buildings.json", doc.dump(1) + "\n");
  if (!a.quiet) print_summary(buildings, a.out);
  return skipped > 0 ? kExitPartly : kExitDone;
}

}  // namespace

int main(int argc, char** argv) { return cli_main({"lc2wf-make-buildings", kUsage, {}}, argc, argv, parse_args, run); }
