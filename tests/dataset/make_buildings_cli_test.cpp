// lc2wf-make-buildings run as a user runs it: the files, their names and facts, determinism, --kinds,
// --augment, and bad command lines.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dataset/formats/mesh_io.h"
#include "dataset/geometry/building.h"
#include "tests/common/run_cli.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::run_argv;

const std::string kBin = LC2WF_MAKE_BUILDINGS_BIN;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

fs::path fresh_dir(const std::string& tag) {
  const fs::path d = fs::path(::testing::TempDir()) / ("lc2wf_make_buildings_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

TEST(MakeBuildingsCli, WritesPolyshapesAndTheirFacts) {
  const fs::path dir = fresh_dir("gen");
  auto r = run_argv({kBin, "--count", "24", "--seed", "3", "-o", (dir / "a").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("24 buildings"));
  EXPECT_THAT(r.out, HasSubstr("height, m"));
  const auto doc = nlohmann::json::parse(read(dir / "a" / "buildings.json"));
  ASSERT_EQ(doc["buildings"].size(), 24u);
  for (const auto& b : doc["buildings"]) {
    const std::string name = b["name"];
    EXPECT_EQ(name.rfind("gen_" + b["kind"].get<std::string>() + "_", 0), 0u) << name;
    const Building building = load_roof_image_building(dir / "a" / (name + ".polyshape"));
    EXPECT_EQ(building.wireframe.junctions.size(), b["vertices"].get<size_t>()) << name;
    EXPECT_EQ(building.wireframe.edges.size(), b["edges"].get<size_t>()) << name;
    EXPECT_EQ(building.issues.non_manifold_edges, 0) << name;
    EXPECT_EQ(building.issues.merged_vertices, 0) << name;
    Eigen::AlignedBox3d box;
    for (const Vec3& v : building.mesh.vertices) box.extend(v);
    EXPECT_NEAR(box.max().z(), b["height_m"].get<double>(), 1e-4) << name;
  }
  // Same seed, same bytes; the first buildings of a larger run are the same buildings.
  r = run_argv({kBin, "--count", "30", "--seed", "3", "-q", "-o", (dir / "b").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  const std::string first = doc["buildings"][0]["name"];
  EXPECT_EQ(read(dir / "a" / (first + ".polyshape")), read(dir / "b" / (first + ".polyshape")));
  fs::remove_all(dir);
}

TEST(MakeBuildingsCli, KindsChooseWhatIsDrawn) {
  const fs::path dir = fresh_dir("kinds");
  const auto r = run_argv({kBin, "--count", "6", "--kinds", "shed", "-q", "-o", dir.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const auto& b : nlohmann::json::parse(read(dir / "buildings.json"))["buildings"]) EXPECT_EQ(b["kind"], "shed");
  fs::remove_all(dir);
}

TEST(MakeBuildingsCli, AugmentWritesCopiesAndNamesBadMeshes) {
  const fs::path dir = fresh_dir("augment");
  ASSERT_EQ(run_argv({kBin, "--count", "3", "--kinds", "gabled", "-q", "-o", (dir / "in").string()}).code, 0);
  std::ofstream(dir / "in" / "broken.polyshape") << "# Number of verts: 3\nnot a vertex\n";
  const auto r = run_argv({kBin, "--augment", (dir / "in").string(), "--copies", "2", "--height-min", "20", "--height-max", "30",
                           "-o", (dir / "out").string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("broken.polyshape"));
  const auto doc = nlohmann::json::parse(read(dir / "out" / "buildings.json"));
  ASSERT_EQ(doc["buildings"].size(), 6u);
  for (const auto& b : doc["buildings"]) {
    EXPECT_GE(b["height_m"].get<double>(), 20 - 1e-6);
    EXPECT_LE(b["height_m"].get<double>(), 30 + 1e-6);
    EXPECT_TRUE(fs::exists(dir / "out" / (b["name"].get<std::string>() + ".polyshape")));
  }
  fs::remove_all(dir);
}

TEST(MakeBuildingsCli, BadCommandLinesWriteNothing) {
  const fs::path dir = fresh_dir("bad");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--count", "3", "--kinds", "castle"}, {"--count", "0"}, {}, {"--count", "2", "--augment", "x"},
        {"--augment", "x", "--stretch-min", "2", "--stretch-max", "1"}}) {
    std::vector<std::string> argv = {kBin};
    argv.insert(argv.end(), args.begin(), args.end());
    argv.insert(argv.end(), {"-o", dir.string()});
    const auto r = run_argv(argv);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_FALSE(fs::exists(dir));
  }
  EXPECT_THAT(run_argv({kBin, "--count", "3", "--kinds", "castle", "-o", dir.string()}).err, HasSubstr("castle"));
  EXPECT_THAT(run_argv({kBin, "--augment", "x", "--stretch-min", "2", "--stretch-max", "1", "-o", dir.string()}).err,
              HasSubstr("--stretch-min"));
}

}  // namespace
}  // namespace lc2wf
