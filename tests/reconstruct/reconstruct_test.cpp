// lc2wf-reconstruct's pipeline on raster renders of a synthetic building with known cameras (no COLMAP):
// outputs, the metric frame from an arbitrary SfM frame, and every bad input the command must survive.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/util/version.h"
#include "dataset/formats/camera_json.h"
#include "dataset/formats/read_file.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "reconstruct/reconstruct_pipeline.h"
#include "reconstruct/stage_error.h"
#include "test_scene.h"
#include "tests/common/constant_height_model.h"
#include "tests/common/exif_gps_jpeg.h"
#include "tests/common/turned_camera.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

// Median distance of the cloud's endpoints (mapped by `to_gt`) to the nearest GT edge.
double median_edge_distance(const LineCloud& cloud, const Wireframe& gt, const Similarity& to_gt) {
  std::vector<double> d;
  for (const Segment3& s : cloud.segments)
    for (const Vec3& p : {to_gt.apply(s.a), to_gt.apply(s.b)}) {
      double best = 1e9;
      for (const auto& e : gt.edges) best = std::min(best, point_segment_distance(p, gt.junctions[e[0]], gt.junctions[e[1]]));
      d.push_back(best);
    }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

class Reconstruct : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::scratch("suite"));
    scene_ = new test::RenderedFolder(test::render_synthetic_folder(*dir_ / "scene", 12));
    test::write_tiny_weights(*dir_ / "weights");
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete scene_;
    delete dir_;
  }
  ReconstructOptions options(const std::string& out) const {
    ReconstructOptions o;
    o.images = scene_->images;
    o.weights = *dir_ / "weights";
    o.out = *dir_ / out;
    o.quiet = true;
    o.threads = 2;
    return o;
  }
  // The scene's true height (its highest junction): the user's word for the building's height.
  static double scene_height() {
    double height = 0;
    for (const Vec3& j : scene_->building.wireframe.junctions) height = std::max(height, j.z());
    return height;
  }
  static fs::path* dir_;
  static test::RenderedFolder* scene_;
};
fs::path* Reconstruct::dir_ = nullptr;

// The scene's first `count` renders, each as its stem ("view_000") and pixels (BGR), for tests that write them
// in another form.
void for_each_render(const test::RenderedFolder& scene, size_t count, const std::function<void(size_t, const std::string&, cv::Mat)>& use) {
  for (size_t i = 0; i < count; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "view_%03zu", i);
    cv::Mat image = cv::imread((scene.images / (std::string(stem) + ".png")).string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(image.empty()) << stem;
    use(i, stem, std::move(image));
  }
}

// `image` as a JPEG (quality 95) whose EXIF holds `tiff`.
std::string jpeg_with_exif(const cv::Mat& image, const std::string& tiff) {
  std::vector<uchar> encoded;
  EXPECT_TRUE(cv::imencode(".jpg", image, encoded, {cv::IMWRITE_JPEG_QUALITY, 95}));
  return testing::with_exif(std::string(encoded.begin(), encoded.end()), tiff);
}

// The run's cloud, taken back to the building frame, lies on the building's edges.
void expect_cloud_on_building(const ReconstructResult& r, const fs::path& out, const test::RenderedFolder& scene) {
  const LineCloud cloud = read_line_cloud(out / "cloud.lcloud");
  const Similarity to_gt = test::similarity_from_json(r.report["frame"]["to_metric"]).inverse();
  EXPECT_LT(median_edge_distance(cloud, scene.building.wireframe, to_gt), 0.1);
}
test::RenderedFolder* Reconstruct::scene_ = nullptr;

TEST_F(Reconstruct, KnownCamerasGiveEveryOutputInTheirFrame) {
  ReconstructOptions o = options("known");
  o.cameras = scene_->cameras_json;
  const ReconstructResult r = reconstruct(o);
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1);  // random weights may give an empty wireframe
  for (const char* f : {"wireframe.obj", "wireframe.json", "cloud.lcloud", "cloud.obj", "cameras.json", "preview.png", "report.json"})
    EXPECT_TRUE(fs::exists(o.out / f)) << f;
  const Json report = Json::parse(read_file(o.out / "report.json"));
  EXPECT_EQ(report["cameras"]["registered"], 12);
  EXPECT_GT(report["lines_3d"].get<int>(), 50);
  EXPECT_LE(report["lines_3d_from_endpoints"].get<int>(), report["lines_3d"].get<int>());
  EXPECT_EQ(report["frame"]["up_source"], "input z");
  EXPECT_EQ(report["frame"]["scale_source"], "given");
  EXPECT_EQ(report["commit"], lc2wf_git_commit());
  // A ring of 12 views covers the building all round.
  EXPECT_EQ(report["coverage"]["cameras"], 12);
  EXPECT_GT(report["coverage"]["azimuth_span_deg"].get<double>(), 270.0);
  EXPECT_EQ(report["coverage"]["sides"].size(), 4u);
  EXPECT_FALSE(report["coverage"]["summary"].get<std::string>().empty());
  for (const char* stage : {"weights", "images", "cameras", "lsd", "triangulation", "frame", "inference", "outputs", "total"})
    EXPECT_TRUE(report["seconds"].contains(stage)) << stage;
  // The cloud, taken back to the building frame, lies on the building's edges.
  const LineCloud cloud = read_line_cloud(o.out / "cloud.lcloud");
  const Similarity to_gt = test::similarity_from_json(report["frame"]["to_metric"]).inverse();
  EXPECT_LT(median_edge_distance(cloud, scene_->building.wireframe, to_gt), 0.1);
  EXPECT_TRUE(r.workspace.empty());  // the private workspace is gone
}

// The scene's known cameras written as a COLMAP text model (images named view_XXX<ext>) in the frame `sfm`.
void write_colmap_model(const fs::path& model, const std::vector<Camera>& cameras, const Similarity& sfm, const char* ext) {
  fs::create_directories(model);
  const Camera& c0 = cameras[0];
  std::ofstream(model / "cameras.txt") << "# camera\n1 PINHOLE " << c0.width << " " << c0.height << " " << c0.K(0, 0) << " " << c0.K(1, 1)
                                       << " " << c0.K(0, 2) + 0.5 << " " << c0.K(1, 2) + 0.5 << "\n";
  std::ofstream images(model / "images.txt");
  images.precision(17);
  for (size_t v = 0; v < cameras.size(); ++v) {
    const Camera c = sfm.apply(cameras[v]);
    const Eigen::Vector4d q = rotation_to_quaternion(c.R);
    char name[32];
    std::snprintf(name, sizeof name, "view_%03zu%s", v, ext);
    images << v + 1 << " " << q(0) << " " << q(1) << " " << q(2) << " " << q(3) << " " << c.t.x() << " " << c.t.y() << " " << c.t.z()
           << " 1 " << name << "\n\n";
  }
}

// An arbitrary similarity frame of the kind structure from motion picks (scale 0.2).
Similarity arbitrary_sfm_frame() {
  Similarity sfm;
  sfm.scale = 0.2;
  sfm.R = Eigen::AngleAxisd(1.1, Vec3(0.6, 0.2, -0.7).normalized()).toRotationMatrix();
  sfm.t = Vec3(-4, 2, 9);
  return sfm;
}

// Photo clouds are judged by their lines on full orbits too and lose their small flat parts (infer/README.md,
// "Drawing only what was seen", "Flat fragments"), where lc2wf-infer leaves a full orbit's wireframe as drawn.
TEST(ReconstructDefaults, PhotoCloudsAreJudgedOnEveryCapture) {
  EXPECT_FALSE(ReconstructOptions{}.post.edge_support.partial_captures_only);
  EXPECT_TRUE(PostProcessOptions{}.edge_support.partial_captures_only);
  EXPECT_GT(ReconstructOptions{}.post.edge_support.min_support, 0.0);
  EXPECT_TRUE(ReconstructOptions{}.post.flat_parts.enabled());
  EXPECT_FALSE(PostProcessOptions{}.flat_parts.enabled());
}

// A four-storey block in the photo look (12 m to the eaves), its cameras in an SfM frame of unknown scale,
// rendered once for the tests of what scales it.
class ReconstructPhotoBlock : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::scratch("photo_block"));
    RectBuildingSpec spec;
    spec.length = 18, spec.width = 11, spec.eave_height = 12.0, spec.slope_deg = 20;
    const test::RenderedFolder scene = test::render_synthetic_folder(*dir_ / "scene", 16, make_rect_building("block", spec), "photo");
    images_ = new fs::path(scene.images);
    test::write_tiny_weights(*dir_ / "weights");
    write_colmap_model(*dir_ / "colmap_model", scene.cameras, sfm_, ".png");
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_, delete images_;
    dir_ = images_ = nullptr;
  }
  static ReconstructOptions options(const std::string& out) {
    ReconstructOptions o;
    o.images = *images_, o.weights = *dir_ / "weights", o.out = *dir_ / out, o.quiet = true, o.threads = 2;
    o.cameras = *dir_ / "colmap_model";
    return o;
  }
  static inline fs::path* dir_ = nullptr;
  static inline fs::path* images_ = nullptr;
  static inline const Similarity sfm_ = arbitrary_sfm_frame();
};

// The window rows give the scale (one storey = 3 m) before the scale search would run.
TEST_F(ReconstructPhotoBlock, FacadeStoreysGiveTheScaleWithoutOtherEvidence) {
  const ReconstructResult r = reconstruct(options("storeys"));
  const Json& f = r.report["frame"];
  ASSERT_EQ(f["scale_source"], "storeys") << f["storeys"].dump();
  EXPECT_FALSE(f.contains("scale_search"));
  EXPECT_NEAR(f["storeys"]["storeys"].get<double>() * 3.0, f["height_m"].get<double>(), 1e-6 * f["height_m"].get<double>());
  EXPECT_EQ(f["storeys"]["relative_uncertainty"], 0.2);
  // The facade layout's storeys are 12 m / 4 = 3 m: the scale comes back to within the storeys' spread.
  EXPECT_NEAR(f["to_metric"]["scale"].get<double>() * sfm_.scale, 1.0, 0.1);
}

// The shipped height model (models/general/height.json) with the storeys not asked (--storey-height 0): the
// pipeline's own cloud comes back within a factor of 2 of its scale, and the report names the source.
TEST_F(ReconstructPhotoBlock, TheShippedHeightModelScalesIt) {
  const fs::path shipped = fs::path(LC2WF_SOURCE_DIR) / "models" / "general" / kHeightModelFile;
  if (!fs::exists(shipped)) GTEST_SKIP() << shipped << " is not in this tree";
  ReconstructOptions o = options("height_model");
  o.frame.storeys.storey_height_m = 0;
  o.height_model = shipped.string();
  const ReconstructResult r = reconstruct(o);
  const Json& f = r.report["frame"];
  ASSERT_EQ(f["scale_source"], "line statistics") << f.dump();
  const double scale_ratio = f["to_metric"]["scale"].get<double>() * sfm_.scale;  // 1 = exact
  std::printf("shipped height model on a rendered 12 m block: read %.1f m, scale ratio %.3f\n", f["line_statistics"]["height_m"].get<double>(),
              scale_ratio);
  EXPECT_GT(scale_ratio, 0.5);
  EXPECT_LT(scale_ratio, 2.0);
}

TEST_F(Reconstruct, ColmapFrameIsBroughtBackToMetresWithZUp) {
  const Similarity sfm = arbitrary_sfm_frame();
  const fs::path model = *dir_ / "colmap_model";
  write_colmap_model(model, scene_->cameras, sfm, ".png");
  const double height = scene_height();

  ReconstructOptions o = options("sfm_frame");
  o.cameras = model;
  o.frame.building_height_m = height;  // the user's word for the building's height, here its true height
  const ReconstructResult r = reconstruct(o);
  const Json& f = r.report["frame"];
  EXPECT_EQ(f["scale_source"], "building height");
  EXPECT_EQ(f["gps"]["used"], false);  // PNG renders carry no EXIF
  const Similarity to_metric = test::similarity_from_json(f["to_metric"]);
  EXPECT_NEAR(to_metric.scale * sfm.scale, 1.0, 0.05);
  const Vec3 up = (to_metric.R * sfm.R).transpose() * Vec3::UnitZ();  // metric up seen in the building frame
  EXPECT_LT(std::acos(std::min(1.0, up.z())) * 180 / M_PI, 1.0);

  // A known distance between two camera centres fixes the scale exactly.
  ReconstructOptions k = options("known_distance");
  k.cameras = model;
  k.known_image_a = "view_000.png", k.known_image_b = "view_006.png";
  k.frame.known_distance_m = (scene_->cameras[0].center() - scene_->cameras[6].center()).norm();
  k.scale_given = true;
  const ReconstructResult rk = reconstruct(k);
  const Json& g = rk.report["frame"];
  EXPECT_EQ(g["scale_source"], "known distance");
  EXPECT_NEAR(g["to_metric"]["scale"].get<double>() * sfm.scale, 1.0, 1e-6);

  // No evidence at all (bare walls: no storeys either): the scale search runs the networks at 3-60 m and
  // reports its scores per height.
  ReconstructOptions n = options("scale_search");
  n.cameras = model;
  const ReconstructResult rn = reconstruct(n);
  const Json& h = rn.report["frame"];
  EXPECT_EQ(h["scale_source"], "scale search");
  EXPECT_EQ(h["storeys"]["found"], false) << h["storeys"].dump();
  ASSERT_TRUE(h.contains("scale_search"));
  EXPECT_GE(h["scale_search"]["curve"].size(), 10u);
  const double found = h["scale_search"]["height_m"].get<double>();
  EXPECT_GE(found, 3.0);
  EXPECT_LE(found, 60.0);
  EXPECT_NEAR(h["height_m"].get<double>(), found, 1e-6 * found);
  EXPECT_TRUE(rn.report["seconds"].contains("scale search"));

  // A height model (--height-model; here one that reads every cloud as the building's true height) scales the
  // cloud before the search would: the frame uses the height it reads, and the report says so.
  HeightModel height_model = test::constant_height_model(height);
  height_model.cv_median_error = 0.12;
  write_height_model(*dir_ / "height.json", height_model);
  ReconstructOptions m = options("height_model");
  m.cameras = model;
  m.height_model = (*dir_ / "height.json").string();
  const ReconstructResult rm = reconstruct(m);
  const Json& hm = rm.report["frame"];
  EXPECT_EQ(hm["scale_source"], "line statistics") << hm.dump();
  EXPECT_FALSE(hm.contains("scale_search"));
  EXPECT_NEAR(hm["line_statistics"]["height_m"].get<double>(), height, 1e-6 * height);
  EXPECT_EQ(hm["line_statistics"]["cv_median_error"], 0.12);
  EXPECT_NEAR(hm["to_metric"]["scale"].get<double>() * sfm.scale, 1.0, 0.05);  // the cloud's height is the building's, to its noise
  // A model file that is not one stops the run at the weights, naming the file.
  std::ofstream(*dir_ / "bad_height.json") << "{\"format\": \"something else\"}";
  m.height_model = (*dir_ / "bad_height.json").string();
  m.out = *dir_ / "bad_height_out";
  try {
    reconstruct(m);
    ADD_FAILURE() << "a bad height model was accepted";
  } catch (const std::exception& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("bad_height.json"));
  }
}

// A drone's photos: every camera centre written into its JPEG as a GPS fix (building x east, y north, z up,
// at 47 N 8 E), the poses in an arbitrary SfM frame, no other evidence: scale, up and north come from GPS.
// The scene's photos as JPEGs in `images` whose EXIF GPS holds camera position_of(v)'s centre (lat/lon about
// 47 N, 8 E, altitude 400 m + z).
void write_gps_photos(const fs::path& images, const test::RenderedFolder& scene, const std::function<size_t(size_t)>& position_of) {
  fs::create_directories(images);
  const double lat0 = 47.0, lon0 = 8.0, alt0 = 400.0;
  const double e2 = 6.69437999014e-3, s2 = std::pow(std::sin(lat0 * M_PI / 180), 2);
  const double north_radius = 6378137.0 * (1 - e2) / std::pow(1 - e2 * s2, 1.5);  // metres per radian of latitude
  const double east_radius = 6378137.0 / std::sqrt(1 - e2 * s2) * std::cos(lat0 * M_PI / 180);
  for_each_render(scene, scene.cameras.size(), [&](size_t v, const std::string& stem, cv::Mat image) {
    const Vec3 c = scene.cameras[position_of(v)].center();
    const std::string tiff = testing::gps_tiff(true, testing::to_dms(lat0 + c.y() / north_radius * 180 / M_PI), 'N',
                                               testing::to_dms(lon0 + c.x() / east_radius * 180 / M_PI), 'E', 0,
                                               uint32_t(std::llround((alt0 + c.z()) * 1000)), 1000);
    write_file_atomic(images / (stem + ".jpg"), jpeg_with_exif(image, tiff));
  });
}

// Options for a run on the GPS-tagged photos of `name`, with the scene's cameras as a COLMAP model in `sfm`.
ReconstructOptions gps_run(const fs::path& dir, const std::string& name, const test::RenderedFolder& scene,
                           const std::function<size_t(size_t)>& position_of, const Similarity& sfm) {
  write_gps_photos(dir / (name + "_images"), scene, position_of);
  write_colmap_model(dir / (name + "_model"), scene.cameras, sfm, ".jpg");
  ReconstructOptions o;
  o.images = dir / (name + "_images");
  o.cameras = dir / (name + "_model");
  return o;
}

TEST_F(Reconstruct, GpsInThePhotosGivesScaleUpAndNorth) {
  const Similarity sfm = arbitrary_sfm_frame();
  const ReconstructOptions g = gps_run(*dir_, "gps", *scene_, [](size_t v) { return v; }, sfm);
  ReconstructOptions o = options("gps");
  o.images = g.images;
  o.cameras = g.cameras;
  const ReconstructResult r = reconstruct(o);
  const Json& f = r.report["frame"];
  ASSERT_EQ(f["scale_source"], "gps") << f.dump();
  EXPECT_EQ(f["gps"]["used"], true);
  const Similarity to_metric = test::similarity_from_json(f["to_metric"]);
  EXPECT_NEAR(to_metric.scale * sfm.scale, 1.0, 0.005);
  // Building frame -> metric frame is a pure turn of < 1 degree: x east, y north, z up.
  const Eigen::Matrix3d turn = to_metric.R * sfm.R;
  EXPECT_LT(Eigen::AngleAxisd(turn).angle() * 180 / M_PI, 1.0);
}

// Fixes that do not fit the cameras (each photo tagged with another photo's position, as noisy as a phone's
// fixes along a short walk) give neither scale nor up: the next evidence does, and the report says why.
TEST_F(Reconstruct, GpsThatDoesNotFitTheCamerasIsNotUsed) {
  const ReconstructOptions g = gps_run(*dir_, "gps_scrambled", *scene_, [](size_t v) { return (5 * v + 3) % 12; }, arbitrary_sfm_frame());
  ReconstructOptions o = options("gps_scrambled_out");
  o.images = g.images;
  o.cameras = g.cameras;
  o.frame.building_height_m = scene_height();
  const ReconstructResult r = reconstruct(o);
  const Json& f = r.report["frame"];
  EXPECT_EQ(f["scale_source"], "building height") << f.dump();
  EXPECT_EQ(f["gps"]["used"], false);
  EXPECT_THAT(f["gps"]["why_not"].get<std::string>(), HasSubstr("too noisy for scale and up"));
  EXPECT_GT(f["gps"]["rms_residual_m"].get<double>(), 0.25 * f["gps"]["spread_m"].get<double>());
}

void expect_stage_error(const ReconstructOptions& o, const std::string& stage, const std::string& text) {
  try {
    reconstruct(o);
    ADD_FAILURE() << "no error";
  } catch (const StageError& e) {
    EXPECT_EQ(e.stage(), stage) << e.what();
    EXPECT_THAT(std::string(e.what()), HasSubstr(text)) << e.what();
  }
  EXPECT_FALSE(fs::exists(o.out)) << "nothing may be written to OUT";
}

TEST_F(Reconstruct, TooFewImages) {
  const fs::path images = *dir_ / "two_images";
  fs::create_directories(images);
  for (const char* n : {"view_000.png", "view_001.png"}) fs::copy_file(scene_->images / n, images / n);
  std::ofstream(images / "notes.txt") << "not an image";
  ReconstructOptions o = options("too_few");
  o.images = images;
  expect_stage_error(o, "images", "2 readable image(s) in " + images.string() + ", at least 3 needed");
}

TEST_F(Reconstruct, UnreadableImagesAreNamedAndSkipped) {
  const fs::path images = *dir_ / "with_broken";
  fs::create_directories(images);
  Json cams = Json::parse(read_file(scene_->cameras_json));
  for (const auto& e : fs::directory_iterator(scene_->images)) fs::copy_file(e.path(), images / e.path().filename());
  std::ofstream(images / "view_005b.png") << "\x89PNG but not really";
  ASSERT_EQ(::mkfifo((images / "view_005c.png").c_str(), 0600), 0);  // never opened: the decoder would block
  cams.insert(cams.begin() + 6, {nullptr, nullptr});  // one entry per image file, in name order
  write_file_atomic(*dir_ / "cams_broken.json", cams.dump());
  ReconstructOptions o = options("broken");
  o.images = images;
  o.cameras = *dir_ / "cams_broken.json";
  const ReconstructResult r = reconstruct(o);
  EXPECT_EQ(r.exit_code, 1);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_EQ(r.warnings[0], "unreadable image skipped: view_005b.png (not a decodable image)");
  EXPECT_EQ(r.report["images"]["unreadable"], Json::array({"view_005b.png (not a decodable image)", "view_005c.png (not a regular file)"}));
}

// Photos taken upright and sideways in one set (a phone turned for a tall facade): each keeps its own size
// and camera, and the cloud lies on the building as from upright photos alone.
TEST_F(Reconstruct, SidewaysPhotosKeepTheirOwnSizeAndCamera) {
  const fs::path images = *dir_ / "sideways";
  fs::create_directories(images);
  Json cams = Json::array();
  for_each_render(*scene_, scene_->cameras.size(), [&](size_t i, const std::string& stem, cv::Mat image) {
    Camera camera = scene_->cameras[i];
    if (i % 3 == 1) cv::rotate(image, image, cv::ROTATE_90_CLOCKWISE), camera = test::turned_clockwise(camera);
    ASSERT_TRUE(cv::imwrite((images / (stem + ".png")).string(), image));
    cams.push_back(camera_to_json(camera));
  });
  write_file_atomic(*dir_ / "cams_sideways.json", cams.dump());
  ReconstructOptions o = options("sideways_out");
  o.images = images;
  o.cameras = *dir_ / "cams_sideways.json";
  const ReconstructResult r = reconstruct(o);
  const Json& sizes = r.report["images"]["sizes"];
  ASSERT_EQ(sizes.size(), scene_->cameras.size());
  EXPECT_EQ(sizes[0], Json::array({640, 480}));
  EXPECT_EQ(sizes[1], Json::array({480, 640}));
  EXPECT_EQ(r.report["cameras"]["registered"], 12);
  EXPECT_GT(r.report["lines_3d"].get<int>(), 50);
  expect_cloud_on_building(r, o.out, *scene_);

  // One --intrinsics cannot describe both sizes: said before COLMAP runs, naming the flag and the sizes.
  ReconstructOptions one_k = options("sideways_one_k");
  one_k.images = images;
  one_k.intrinsics = Eigen::Vector4d(622.2, 622.2, 319.5, 239.5);
  expect_stage_error(one_k, "cameras", "--intrinsics gives one camera, but the photos have several sizes (8 of 640x480, 4 of 480x640)");
}

// A phone's JPEGs stored 640x480 with EXIF orientation 6 (shown turned clockwise) are read as stored, the pixels
// the cameras were estimated for (COLMAP ignores the tag), not turned as an image viewer shows them.
TEST_F(Reconstruct, ExifOrientationIsNotApplied) {
  const fs::path images = *dir_ / "exif_turned";
  fs::create_directories(images);
  for_each_render(*scene_, scene_->cameras.size(), [&](size_t, const std::string& stem, cv::Mat image) {
    write_file_atomic(images / (stem + ".jpg"), jpeg_with_exif(image, testing::orientation_tiff(6)));
  });
  // The test can fail: OpenCV's default reading turns these files.
  ASSERT_EQ(cv::imread((images / "view_000.jpg").string(), cv::IMREAD_GRAYSCALE).size(), cv::Size(480, 640));
  ReconstructOptions o = options("exif_turned_out");
  o.images = images;
  o.cameras = scene_->cameras_json;
  const ReconstructResult r = reconstruct(o);
  for (const Json& size : r.report["images"]["sizes"]) EXPECT_EQ(size, Json::array({640, 480}));
  expect_cloud_on_building(r, o.out, *scene_);
}

// A phone's photos carry their 35 mm-equivalent focal length (here 28 mm); COLMAP gets it as fx = 28 / 36 x the
// longer side, unless --focal-35mm says otherwise. A stand-in colmap records its arguments and fails.
TEST_F(Reconstruct, ExifFocalLengthSetsTheCamerasIntrinsics) {
  const fs::path images = *dir_ / "exif_focal";
  fs::create_directories(images);
  const std::string tiff = testing::exif_ifd_tiff(true, {{0xA405, 3, 1, testing::tiff_short(true, 28)}});
  for_each_render(*scene_, 4, [&](size_t, const std::string& stem, cv::Mat image) {
    write_file_atomic(images / (stem + ".jpg"), jpeg_with_exif(image, tiff));
  });
  const fs::path fake = *dir_ / "recording_colmap.sh", args = *dir_ / "colmap_args.txt";
  std::ofstream(fake) << "#!/bin/sh\necho \"$@\" >> '" << args.string() << "'\nexit 1\n";
  fs::permissions(fake, fs::perms::owner_all);
  for (const bool given : {false, true}) {
    fs::remove(args);
    ReconstructOptions o = options(given ? "exif_focal_given" : "exif_focal_out");
    o.images = images;
    o.colmap.executable = fake.string();
    if (given) o.focal_35mm = 35.0;
    EXPECT_THROW(reconstruct(o), StageError);
    const std::string recorded = read_file(args);
    const std::string expected = given ? "622.22222222222217,622.22222222222217,320,240" : "497.77777777777777,497.77777777777777,320,240";
    EXPECT_THAT(recorded, HasSubstr("--ImageReader.camera_params " + expected)) << recorded;
  }
}

// TIFF photos are read (COLMAP reads them too); a phone's HEIC and a camera's raw files are named as not read,
// with what to do, instead of vanishing from the count.
TEST_F(Reconstruct, TiffIsReadAndHeicIsNamed) {
  const fs::path images = *dir_ / "tiff_heic";
  fs::create_directories(images);
  for_each_render(*scene_, scene_->cameras.size(), [&](size_t, const std::string& stem, cv::Mat image) {
    ASSERT_TRUE(cv::imwrite((images / (stem + ".tif")).string(), image));
  });
  std::ofstream(images / "IMG_0001.HEIC") << "ftypheic";
  std::ofstream(images / "DSC_0002.NEF") << "raw";
  ReconstructOptions o = options("tiff_heic_out");
  o.images = images;
  o.cameras = scene_->cameras_json;  // one entry per photo it reads: the HEIC and raw files are not among them
  const ReconstructResult r = reconstruct(o);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.report["images"]["read"], 12);
  EXPECT_EQ(r.report["images"]["not_read"], Json::array({"DSC_0002.NEF", "IMG_0001.HEIC"}));
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_THAT(r.warnings[0], HasSubstr("convert them to JPEG first): DSC_0002.NEF, IMG_0001.HEIC"));
  expect_cloud_on_building(r, o.out, *scene_);

  const fs::path heic_only = *dir_ / "heic_only";
  fs::create_directories(heic_only);
  for (const char* n : {"a.heic", "b.heic", "c.heic"}) std::ofstream(heic_only / n) << "ftypheic";
  ReconstructOptions h = options("heic_only_out");
  h.images = heic_only;
  expect_stage_error(h, "images", "0 readable image(s) in " + heic_only.string() +
                                      ", at least 3 needed; not read (HEIC/HEIF or camera raw: convert them to JPEG first): a.heic, b.heic, c.heic");
}

TEST_F(Reconstruct, AScaleThatLeavesTheCoordinateLimitIsAFrameError) {
  // --scale 1e20 failed only when the cloud was written, as an I/O error naming a workspace file.
  ReconstructOptions o = options("huge_scale");
  o.cameras = scene_->cameras_json;
  o.frame.scale = 1e20;
  o.scale_given = true;
  // The message names the flag the user typed (it said "given").
  expect_stage_error(o, "frame", "m/unit (--scale) puts the cloud beyond +-1e9 m");
}

TEST_F(Reconstruct, HostileCameraFilesAreNamed) {
  ReconstructOptions o = options("hostile_reference");
  o.cameras = scene_->cameras_json;
  write_file_atomic(*dir_ / "reference.json", "[{\"K\": [1,");
  o.reference_cameras = *dir_ / "reference.json";
  expect_stage_error(o, "outputs", (*dir_ / "reference.json").string() + ": not JSON: ");
  write_file_atomic(*dir_ / "reference.json", "{\"K\": 1}");
  expect_stage_error(o, "outputs", (*dir_ / "reference.json").string() + ": expected an array of cameras, one per image");
  // A COLMAP model whose image names match none of the photos: every image looked unregistered.
  const fs::path model = *dir_ / "foreign_model";
  fs::create_directories(model);
  write_file_atomic(model / "cameras.txt", "1 PINHOLE 640 480 500 500 320 240\n");
  write_file_atomic(model / "images.txt", "1 1 0 0 0 0 0 5 1 IMG_0001.JPG\n\n2 1 0 0 0 1 0 5 1 IMG_0002.JPG\n\n");
  ReconstructOptions m = options("foreign_model_out");
  m.cameras = model;
  expect_stage_error(m, "cameras", model.string() + ": none of the model's 2 image names matches an image of the folder");
  // Regression: all-zero K and R passed the reader and failed in triangulation as an I/O error, "view 0
  // has an invalid camera", naming no file (found by the adversarial corpus).
  Json cams = Json::parse(read_file(scene_->cameras_json));
  const fs::path zeros = *dir_ / "zero_cameras.json";
  for (auto& c : cams)
    if (!c.is_null()) c["K"] = std::vector<double>(9, 0.0);
  write_file_atomic(zeros, cams.dump());
  ReconstructOptions z = options("zero_cameras_out");
  z.cameras = zeros;
  expect_stage_error(z, "cameras", zeros.string() + " entry 0: camera: the focal lengths K[0] and K[4] must be > 0");
  for (auto& c : cams)
    if (!c.is_null()) c["K"] = {500, 0, 320, 0, 500, 240, 0, 0, 1}, c["R"] = std::vector<double>(9, 0.0);
  write_file_atomic(zeros, cams.dump());
  expect_stage_error(z, "cameras", zeros.string() + " entry 0: camera: R is not a rotation");
}

TEST_F(Reconstruct, ImagesWithoutLines) {
  const fs::path images = *dir_ / "blank";
  fs::create_directories(images);
  for (int v = 0; v < 12; ++v) cv::imwrite((images / ("view_" + std::string(v < 10 ? "00" : "0") + std::to_string(v) + ".png")).string(), cv::Mat(480, 640, CV_8UC1, cv::Scalar(128)));
  ReconstructOptions o = options("blank_out");
  o.images = images;
  o.cameras = scene_->cameras_json;
  expect_stage_error(o, "lsd", "no 2D line segment in any of the 12 registered images");
}

TEST_F(Reconstruct, TooFewRegisteredImages) {
  Json cams = Json::parse(read_file(scene_->cameras_json));
  for (size_t i = 2; i < cams.size(); ++i) cams[i] = nullptr;
  write_file_atomic(*dir_ / "cams_two.json", cams.dump());
  ReconstructOptions o = options("unregistered");
  o.cameras = *dir_ / "cams_two.json";
  expect_stage_error(o, "cameras", "2 of 12 images registered (cameras json " + o.cameras.string() +
                                       "), at least 3 needed; unregistered: [\"view_002.png\"");
}

TEST_F(Reconstruct, CamerasFileOfTheWrongSize) {
  write_file_atomic(*dir_ / "cams_short.json", "[null]");
  ReconstructOptions o = options("short");
  o.cameras = *dir_ / "cams_short.json";
  expect_stage_error(o, "cameras", "cams_short.json has 1 cameras for 12 images");
}

TEST_F(Reconstruct, NamedWorkspaceIsNeverCleared) {
  const fs::path ws = *dir_ / "my_workspace";
  fs::create_directories(ws);
  std::ofstream(ws / "precious.txt") << "mine";
  ReconstructOptions o = options("ws_out");
  o.cameras = scene_->cameras_json;
  o.workspace = ws;
  EXPECT_THROW(reconstruct(o), std::runtime_error);
  EXPECT_TRUE(fs::exists(ws / "precious.txt"));
  EXPECT_FALSE(fs::exists(o.out));

  o.workspace = *dir_ / "new_workspace";
  const ReconstructResult r = reconstruct(o);
  EXPECT_EQ(r.workspace, o.workspace.string());
  EXPECT_TRUE(fs::exists(o.workspace / "out" / "report.json"));  // kept: the user named it
}

TEST_F(Reconstruct, KeepKeepsThePrivateWorkspace) {
  ReconstructOptions o = options("keep_out");
  o.cameras = scene_->cameras_json;
  o.keep = true;
  const ReconstructResult r = reconstruct(o);
  ASSERT_FALSE(r.workspace.empty());
  EXPECT_TRUE(fs::exists(fs::path(r.workspace) / "out" / "cloud.lcloud"));
  fs::remove_all(r.workspace);
}

}  // namespace
}  // namespace lc2wf
