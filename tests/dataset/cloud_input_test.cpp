// Format detection of the clouds lc2wf-infer / lc2wf-eval read: ours, Line3D++ .txt, LIMAP finaltracks/
// and line OBJ, by content and extension or by name.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "dataset/formats/errors.h"
#include "dataset/formats/line3dpp_io.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/formats/line_obj_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "dataset/formats/cloud_input.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

TEST(CloudInput, DetectsEveryFormat) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_cloud_input_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "house_limap" / "finaltracks");
  SyntheticCloudOptions o;
  o.cameras.num_views = 4;
  const LineCloud ours = make_synthetic_line_cloud(make_rect_building("house", RectBuildingSpec{}), 2, o);
  write_line_cloud(dir / "house.lcloud", ours);
  write_line3dpp_txt(dir / "house_l3d.txt", ours);
  write_line_obj(dir / "house_obj.obj", ours);
  std::ofstream(dir / "house_limap" / "finaltracks" / "track_0.txt")
      << "0 0 0 1 0 0\n1 1\nimage_id_list 1\nline_id_list 0\nline2d_list\n1 2 3 4\nEND\n";

  EXPECT_EQ(load_line_cloud(dir / "house.lcloud", CloudFormat::kAuto).wireframe.edges.size(), ours.wireframe.edges.size());
  const LineCloud txt = load_line_cloud(dir / "house_l3d.txt", CloudFormat::kAuto);
  EXPECT_EQ(txt.segments.size(), ours.segments.size());
  EXPECT_EQ(txt.name, "house_l3d");
  EXPECT_TRUE(txt.wireframe.edges.empty());  // other programs' clouds carry no ground truth
  EXPECT_EQ(load_line_cloud(dir / "house_obj.obj", CloudFormat::kAuto).segments.size(), ours.segments.size());
  EXPECT_EQ(load_line_cloud(dir / "house_limap", CloudFormat::kAuto).segments.size(), 1u);
  EXPECT_EQ(find_cloud_file(dir, "house_limap"), dir / "house_limap");
  // Named formats skip detection: a Line3D++ file read as ours is an error naming it.
  EXPECT_EQ(load_line_cloud(dir / "house_l3d.txt", parse_cloud_format("line3dpp", "--format")).segments.size(), ours.segments.size());
  EXPECT_THROW(load_line_cloud(dir / "house_l3d.txt", CloudFormat::kLc2wf), DataError);
  EXPECT_THROW(parse_cloud_format("colmap", "--format"), std::invalid_argument);
  fs::remove_all(dir);
}

// Regression: a folder named like a cloud (b.lcloud/) was skipped as if nothing were there, so lc2wf-eval
// reported "no ground truth for building 'b'" without naming it (found by the adversarial corpus).
TEST(CloudInput, AFolderStandingForACloudIsNamed) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_cloud_folder_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "b.lcloud");
  fs::create_directories(dir / "c");  // a folder without an extension is not a candidate
  try {
    find_cloud_file_if_any(dir, "b");
    ADD_FAILURE() << "the folder was not reported";
  } catch (const DataError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "b.lcloud").string() + ": is a folder, not a line-cloud file (nor LIMAP tracks)");
  }
  EXPECT_FALSE(find_cloud_file_if_any(dir, "c").has_value());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf
