#include "tools/colmap/colmap_poses.h"

#include "dataset/photo/similarity_align.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/util/median.h"
#include "core/util/seconds_since.h"
#include "dataset/formats/errors.h"
#include "dataset/geometry/line_meeting_point.h"
#include "tools/colmap/colmap_database.h"
#include "tools/colmap/sift_matching.h"
#include "tools/process/run_process.h"

namespace lc2wf {
namespace fs = std::filesystem;

Vec3 common_aim_point(const std::vector<Camera>& cameras) {
  LineMeetingPoint meeting;
  for (const Camera& c : cameras) meeting.add_line(c.center(), c.R.transpose().col(2));  // optical axes, world frame
  return meeting.A.completeOrthogonalDecomposition().solve(meeting.b);  // minimum norm when the axes are parallel
}

void AlignOptions::Check() const {
  if (!(outlier_factor == 0 || outlier_factor >= 1)) throw std::invalid_argument("AlignOptions.outlier_factor must be 0 or >= 1");
  if (rounds < 1) throw std::invalid_argument("AlignOptions.rounds must be >= 1");
}

namespace {

// Reference poses ~ s R (estimated poses) + t over the listed views: the centres, and the points one camera
// distance along each camera's optical and image-down axes, so that cameras on one line (a walk down a
// street) still fix the turn about it. The centres alone give the scale those points need in our frame.
Similarity similarity_of_poses(const std::vector<Camera>& reference, const std::vector<std::optional<Camera>>& estimated,
                               const std::vector<int>& ids, double camera_distance) {
  std::vector<Vec3> src(estimated.size(), Vec3::Zero()), dst(reference.size(), Vec3::Zero());
  for (int k : ids) src[k] = estimated[k]->center(), dst[k] = reference[k].center();
  const Similarity by_centres = least_squares_similarity(src, dst, ids);
  if (!(by_centres.scale > 0) || !(camera_distance > 0)) return by_centres;
  std::vector<Vec3> src_poses, dst_poses;
  for (int k : ids)
    for (const Vec3& axis : {Vec3::Zero().eval(), Vec3::UnitZ().eval(), Vec3::UnitY().eval()}) {  // centre, optical, image-down
      src_poses.push_back(src[k] + camera_distance / by_centres.scale * (estimated[k]->R.transpose() * axis));
      dst_poses.push_back(dst[k] + camera_distance * (reference[k].R.transpose() * axis));
    }
  std::vector<int> all(src_poses.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return least_squares_similarity(src_poses, dst_poses, all);
}

// Via the quaternion (atan2) rather than acos of the trace, which cannot resolve angles below ~0.001 deg.
double rotation_angle_deg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return Eigen::AngleAxisd(Eigen::Quaterniond(A * B.transpose()).normalized()).angle() * 180.0 / M_PI;
}

}  // namespace

PoseComparison align_to_reference(const std::vector<Camera>& reference, std::vector<std::optional<Camera>>& estimated,
                                  const AlignOptions& options) {
  options.Check();
  if (reference.size() != estimated.size()) throw std::invalid_argument("align_to_reference: view counts differ");
  std::vector<int> ids;
  for (size_t i = 0; i < estimated.size(); ++i)
    if (estimated[i]) ids.push_back(static_cast<int>(i));
  if (ids.size() < 3) throw std::invalid_argument("align_to_reference: fewer than 3 registered views");
  const Vec3 aim = common_aim_point(reference);
  std::vector<double> distances;
  for (const Camera& c : reference) distances.push_back((c.center() - aim).norm());
  const double camera_distance = median(distances);
  std::vector<int> inliers = ids;
  Similarity sim = similarity_of_poses(reference, estimated, inliers, camera_distance);
  for (int round = 1; round < options.rounds && options.outlier_factor > 0; ++round) {
    auto error = [&](int i) { return (sim.scale * sim.R * estimated[i]->center() + sim.t - reference[i].center()).norm(); };
    std::vector<double> inlier_errors;
    for (int i : inliers) inlier_errors.push_back(error(i));
    const double threshold = std::max(options.outlier_factor * median(inlier_errors), 0.01 * camera_distance);
    std::vector<int> kept;
    for (int i : ids)
      if (error(i) <= threshold) kept.push_back(i);
    if (kept == inliers || kept.size() < 3) break;
    inliers = kept;
    sim = similarity_of_poses(reference, estimated, inliers, camera_distance);
  }
  PoseComparison pc;
  pc.reference = static_cast<int>(reference.size());
  pc.registered = static_cast<int>(ids.size());
  pc.inliers = static_cast<int>(inliers.size());
  pc.scale = sim.scale;
  pc.rotation = sim.R;
  pc.translation = sim.t;
  pc.camera_distance = camera_distance;
  pc.centre_error.assign(reference.size(), std::nan(""));
  pc.rotation_deg.assign(reference.size(), std::nan(""));
  std::vector<double> ce, re;
  for (int i : ids) {
    Camera& c = *estimated[i];
    // X_ref = s Ra X_est + ta  =>  R_ref-frame = R_est Ra^T, centre mapped by the similarity.
    const Vec3 C = sim.scale * sim.R * c.center() + sim.t;
    c.R = c.R * sim.R.transpose();
    c.t = -c.R * C;
    pc.centre_error[i] = (c.center() - reference[i].center()).norm();
    pc.rotation_deg[i] = rotation_angle_deg(c.R, reference[i].R);
    ce.push_back(pc.centre_error[i]);
    re.push_back(pc.rotation_deg[i]);
  }
  pc.median_centre_error = median(ce);
  pc.max_centre_error = *std::max_element(ce.begin(), ce.end());
  pc.median_rotation_deg = median(re);
  pc.max_rotation_deg = *std::max_element(re.begin(), re.end());
  return pc;
}

void ColmapOptions::Check() const {
  if (executable.empty()) throw std::invalid_argument("ColmapOptions.executable is empty");
  if (max_features < 100) throw std::invalid_argument("ColmapOptions.max_features must be >= 100");
  if (matcher != "exhaustive" && matcher != "sequential")
    throw std::invalid_argument("ColmapOptions.matcher must be exhaustive or sequential, not " + matcher);
  if (sequential_overlap < 1) throw std::invalid_argument("ColmapOptions.sequential_overlap must be >= 1");
  if (init_min_inliers < 8) throw std::invalid_argument("ColmapOptions.init_min_inliers must be >= 8");
  if (abs_pose_min_inliers < 6) throw std::invalid_argument("ColmapOptions.abs_pose_min_inliers must be >= 6");
  if (threads < 0) throw std::invalid_argument("ColmapOptions.threads must be >= 0");
  if (first_octave && (*first_octave < -1 || *first_octave > 2))
    throw std::invalid_argument("ColmapOptions.first_octave must be in [-1, 2]");
  if (max_image_size < 100 || max_image_size > 20000)
    throw std::invalid_argument("ColmapOptions.max_image_size must be in [100, 20000] pixels");
}

namespace {

// Runs one COLMAP command (argument vector, no shell), appending its output to the log; returns its wall time.
double run_step(const std::vector<std::string>& argv, const fs::path& log, const std::string& step) {
  const ProcessResult r = run_process(argv, log);
  if (r.exit_code != 0) {
    const std::string how = r.signal ? "killed by signal " + std::to_string(r.signal)
                            : r.exit_code < 0 ? "could not start '" + argv[0] + "'"
                                              : "exit code " + std::to_string(r.exit_code);
    throw std::runtime_error("COLMAP " + step + " failed (" + how + "); see " + log.string());
  }
  return r.seconds;
}

// What an earlier run in the same workspace left (re-runs must not mix with it): only the entries this
// file creates, never the folder or anything else in it.
void clear_colmap_outputs(const fs::path& workspace) {
  if (!fs::is_directory(workspace)) return;
  for (const char* name : {"images", "database.db", "matches.txt", "sparse", "colmap.log"}) fs::remove_all(workspace / name);
  for (const auto& e : fs::directory_iterator(workspace))
    if (const std::string n = e.path().filename().string(); n.rfind("model_txt_", 0) == 0 || n.rfind("image_list_", 0) == 0)
      fs::remove_all(e.path());
}

}  // namespace

int sift_first_octave(const ColmapOptions& options, int longer_side) {
  if (options.first_octave) return *options.first_octave;
  return longer_side > options.max_image_size ? 0 : -1;
}

ColmapRun estimate_poses_with_colmap(const std::vector<fs::path>& images, const std::vector<Eigen::Matrix3d>& K,
                                     const fs::path& workspace, const ColmapOptions& o) {
  o.Check();
  if (K.size() != images.size())
    throw std::invalid_argument("estimate_poses_with_colmap: " + std::to_string(K.size()) + " intrinsics for " +
                                std::to_string(images.size()) + " images");
  clear_colmap_outputs(workspace);
  fs::create_directories(workspace / "images");
  std::vector<std::string> names;
  for (const fs::path& p : images) {
    if (!fs::exists(p)) throw std::runtime_error("image not found: " + p.string());
    // Numbered copies: COLMAP's match list separates names by spaces, which a photo's name may hold.
    char numbered[32];
    std::snprintf(numbered, sizeof numbered, "%06zu", names.size());
    names.push_back(numbered + p.extension().string());
    fs::copy_file(p, workspace / "images" / names.back());
  }
  const fs::path db = workspace / "database.db", log = workspace / "colmap.log", image_dir = workspace / "images";
  const std::string threads = std::to_string(o.threads > 0 ? o.threads : -1);
  ColmapRun run;
  // One feature_extractor run per distinct K, on the list of its images: each run makes one shared camera.
  std::vector<char> listed(images.size(), 0);
  double extract_seconds = 0;
  for (size_t first = 0; first < images.size(); ++first) {
    if (listed[first]) continue;
    const fs::path list = workspace / ("image_list_" + std::to_string(first) + ".txt");
    {
      std::ofstream out(list);
      for (size_t i = first; i < images.size(); ++i)
        if (!listed[i] && K[i] == K[first]) out << names[i] << "\n", listed[i] = 1;
      if (!out) throw std::runtime_error("cannot write " + list.string());
    }
    const Eigen::Matrix3d& k = K[first];
    std::ostringstream params;
    params.precision(17);
    params << k(0, 0) << "," << k(1, 1) << "," << k(0, 2) + 0.5 << "," << k(1, 2) + 0.5;
    // The photos' size from the principal point of the intrinsics (cx = (width - 1) / 2 for a centred one).
    const int longer_side = static_cast<int>(std::lround(2.0 * std::max(k(0, 2), k(1, 2)) + 1.0));
    extract_seconds += run_step(
        {o.executable, "feature_extractor", "--database_path", db.string(), "--image_path", image_dir.string(), "--image_list_path",
         list.string(), "--ImageReader.camera_model", "PINHOLE", "--ImageReader.single_camera", "1", "--ImageReader.camera_params",
         params.str(), "--SiftExtraction.use_gpu", "0", "--SiftExtraction.num_threads", threads, "--SiftExtraction.max_num_features",
         std::to_string(o.max_features), "--SiftExtraction.first_octave", std::to_string(sift_first_octave(o, longer_side)),
         "--SiftExtraction.max_image_size", std::to_string(o.max_image_size)},
        log, "feature_extractor");
  }
  run.step_seconds.emplace_back("feature_extractor", extract_seconds);
  // Our exact matcher, then COLMAP's geometric verification of the matches (its RANSAC, its defaults).
  const auto t0 = SteadyClock::now();
  SiftMatchOptions match;
  match.threads = o.threads;
  const std::vector<ImageDescriptors> features = read_colmap_descriptors(db);
  const fs::path match_list = workspace / "matches.txt";
  write_match_list(features, image_pairs(static_cast<int>(features.size()), o.matcher == "sequential" ? o.sequential_overlap : 0),
                   match, match_list);
  run.step_seconds.emplace_back("matching", seconds_since(t0));
  run.step_seconds.emplace_back(
      "matches_importer",
      run_step({o.executable, "matches_importer", "--database_path", db.string(), "--match_list_path", match_list.string(),
                "--match_type", "raw", "--SiftMatching.use_gpu", "0", "--SiftMatching.num_threads", threads},
               log, "matches_importer"));
  auto mapper = [&](bool refine_focal) {
    fs::remove_all(workspace / "sparse");
    fs::create_directories(workspace / "sparse");
    const auto log_start = fs::exists(log) ? fs::file_size(log) : 0;
    try {
      run.step_seconds.emplace_back(
          "mapper",
          run_step({o.executable, "mapper", "--database_path", db.string(), "--image_path", image_dir.string(), "--output_path",
                    (workspace / "sparse").string(), "--Mapper.num_threads", threads, "--Mapper.init_min_num_inliers",
                    std::to_string(o.init_min_inliers), "--Mapper.abs_pose_min_num_inliers", std::to_string(o.abs_pose_min_inliers),
                    "--Mapper.ba_refine_focal_length", refine_focal ? "1" : "0", "--Mapper.ba_refine_principal_point", "0",
                    "--Mapper.ba_refine_extra_params", "0"},
                   log, "mapper"));
    } catch (const std::runtime_error&) {
      // COLMAP 3.8 exits non-zero when it cannot start a model; say why, not only "failed".
      std::ifstream in(log);
      in.seekg(static_cast<std::streamoff>(log_start));
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (text.find("No good initial image pair found") == std::string::npos) throw;
      throw std::runtime_error("COLMAP mapper found no initial image pair: too few verified matches between views (repetitive "
                               "textures or little overlap; a lower init_min_inliers, --init-min-inliers, may help); see " +
                               log.string());
    }
  };
  run.focal_refined = o.refine_focal_length;
  try {
    mapper(o.refine_focal_length);
  } catch (const std::runtime_error&) {
    // Free focal lengths make a pair of views' geometry looser: with few photos per camera (ten tourists' photos,
    // ten cameras) no initial pair holds. Fixed ones are the fallback.
    if (!o.refine_focal_length) throw;
    run.focal_refined = false;
    mapper(false);
  }
  // The mapper writes sparse/0, sparse/1, ... when it cannot join every view into one model.
  std::vector<ColmapImage> best;
  double convert_seconds = 0;
  for (int m = 0; fs::exists(workspace / "sparse" / std::to_string(m)); ++m) {
    const fs::path txt = workspace / ("model_txt_" + std::to_string(m));
    fs::create_directories(txt);
    convert_seconds += run_step({o.executable, "model_converter", "--input_path", (workspace / "sparse" / std::to_string(m)).string(),
                                 "--output_path", txt.string(), "--output_type", "TXT"},
                                log, "model_converter");
    auto model = read_colmap_text_model(txt);
    if (model.size() > best.size()) best = std::move(model);
  }
  if (best.empty()) throw std::runtime_error("COLMAP mapper built no model; see " + log.string());
  run.step_seconds.emplace_back("model_converter", convert_seconds);
  run.cameras.resize(images.size());
  for (const ColmapImage& im : best) {
    const auto it = std::find(names.begin(), names.end(), im.name);
    if (it == names.end()) continue;
    run.cameras[it - names.begin()] = im.camera;  // image size as COLMAP read it
  }
  return run;
}

}  // namespace lc2wf
