#include "tools/colmap/colmap_poses.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "dataset/errors.h"

namespace lc2wf {
namespace fs = std::filesystem;

Eigen::Matrix3d quaternion_to_rotation(double qw, double qx, double qy, double qz) {
  return Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
}

Eigen::Vector4d rotation_to_quaternion(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
}

namespace {

// Non-comment, non-empty lines with their 1-based numbers.
std::vector<std::pair<int, std::string>> data_lines(const fs::path& p, bool keep_empty) {
  std::ifstream in(p);
  if (!in) throw DataError(p.string(), "cannot open");
  std::vector<std::pair<int, std::string>> out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line[0] == '#') continue;
    if (line.empty() && !keep_empty) continue;
    out.emplace_back(n, line);
  }
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

std::vector<ColmapImage> read_colmap_text_model(const fs::path& dir) {
  struct Intr {
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
    int w = 0, h = 0;
  };
  std::map<int, Intr> cams;
  const fs::path cp = dir / "cameras.txt", ip = dir / "images.txt";
  for (const auto& [n, line] : data_lines(cp, false)) {
    std::istringstream ss(line);
    int id = 0;
    std::string model;
    Intr c;
    std::vector<double> p;
    if (!(ss >> id >> model >> c.w >> c.h)) throw DataError(cp.string(), n, "expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS...");
    for (double x; ss >> x;) p.push_back(x);
    double fx, fy, cx, cy;
    if (model == "PINHOLE" && p.size() == 4) {
      fx = p[0], fy = p[1], cx = p[2], cy = p[3];
    } else if ((model == "SIMPLE_PINHOLE" && p.size() == 3) || (model == "SIMPLE_RADIAL" && p.size() == 4) ||
               (model == "RADIAL" && p.size() == 5)) {
      fx = fy = p[0], cx = p[1], cy = p[2];
      for (size_t k = 3; k < p.size(); ++k)
        if (std::abs(p[k]) > 1e-9) throw DataError(cp.string(), n, "lens distortion is not supported; undistort the images first");
    } else {
      throw DataError(cp.string(), n, "unsupported camera model or parameter count: " + model);
    }
    c.K << fx, 0, cx - 0.5, 0, fy, cy - 0.5, 0, 0, 1;  // COLMAP's pixel centres sit at +0.5
    cams[id] = c;
  }
  std::vector<ColmapImage> out;
  const auto lines = data_lines(ip, true);
  // Each image takes two lines: the pose line, then its (possibly empty) 2D point line.
  for (size_t k = 0; k < lines.size(); ++k) {
    const auto& [n, line] = lines[k];
    if (line.empty()) continue;
    std::istringstream ss(line);
    int id = 0, cam = 0;
    double qw, qx, qy, qz, tx, ty, tz;
    std::string name;
    if (!(ss >> id >> qw >> qx >> qy >> qz >> tx >> ty >> tz >> cam >> name))
      throw DataError(ip.string(), n, "expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
    const auto it = cams.find(cam);
    if (it == cams.end()) throw DataError(ip.string(), n, "unknown camera id " + std::to_string(cam));
    ColmapImage im;
    im.name = name;
    im.camera.K = it->second.K;
    im.camera.width = it->second.w;
    im.camera.height = it->second.h;
    im.camera.R = quaternion_to_rotation(qw, qx, qy, qz);
    im.camera.t = Vec3(tx, ty, tz);
    out.push_back(im);
    ++k;  // skip the points line
  }
  return out;
}

PoseComparison align_to_reference(const std::vector<Camera>& reference, std::vector<std::optional<Camera>>& estimated) {
  if (reference.size() != estimated.size()) throw std::invalid_argument("align_to_reference: view counts differ");
  std::vector<int> ids;
  for (size_t i = 0; i < estimated.size(); ++i)
    if (estimated[i]) ids.push_back(static_cast<int>(i));
  if (ids.size() < 3) throw std::invalid_argument("align_to_reference: fewer than 3 registered views");
  Eigen::Matrix3Xd src(3, ids.size()), dst(3, ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    src.col(k) = estimated[ids[k]]->center();
    dst.col(k) = reference[ids[k]].center();
  }
  const Eigen::Matrix4d T = Eigen::umeyama(src, dst, true);  // dst = s R src + t
  const Eigen::Matrix3d sR = T.topLeftCorner<3, 3>();
  const double s = std::cbrt(sR.determinant());
  const Eigen::Matrix3d Ra = sR / s;
  const Vec3 ta = T.topRightCorner<3, 1>();
  PoseComparison pc;
  pc.reference = static_cast<int>(reference.size());
  pc.registered = static_cast<int>(ids.size());
  pc.scale = s;
  std::vector<double> ce, re;
  for (int i : ids) {
    Camera& c = *estimated[i];
    // X_est = (Ra^T (X_ref - ta)) / s  =>  x_cam = R_est X_est + t_est = (R_est Ra^T / s) X_ref + ...
    const Vec3 C = s * Ra * c.center() + ta;
    c.R = c.R * Ra.transpose();
    c.t = -c.R * C;
    ce.push_back((c.center() - reference[i].center()).norm());
    const double cosang = std::clamp(((c.R * reference[i].R.transpose()).trace() - 1.0) / 2.0, -1.0, 1.0);
    re.push_back(std::acos(cosang) * 180.0 / M_PI);
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
}

namespace {

void run_step(const std::string& cmd, const fs::path& log, const std::string& step) {
  const int status = std::system((cmd + " >> '" + log.string() + "' 2>&1").c_str());
  if (status != 0) throw std::runtime_error("COLMAP " + step + " failed (status " + std::to_string(status) + "); see " + log.string());
}

}  // namespace

std::vector<std::optional<Camera>> estimate_poses_with_colmap(const std::vector<fs::path>& images, const Eigen::Matrix3d& K,
                                                              int width, int height, const fs::path& workspace,
                                                              const ColmapOptions& o) {
  o.Check();
  fs::remove_all(workspace);
  fs::create_directories(workspace / "images");
  std::vector<std::string> names;
  for (const fs::path& p : images) {
    if (!fs::exists(p)) throw std::runtime_error("image not found: " + p.string());
    fs::copy_file(p, workspace / "images" / p.filename());
    names.push_back(p.filename().string());
  }
  const fs::path db = workspace / "database.db", log = workspace / "colmap.log";
  const std::string exe = "'" + o.executable + "'";
  std::ostringstream params;
  params.precision(17);
  params << K(0, 0) << "," << K(1, 1) << "," << K(0, 2) + 0.5 << "," << K(1, 2) + 0.5;
  run_step(exe + " feature_extractor --database_path '" + db.string() + "' --image_path '" + (workspace / "images").string() +
               "' --ImageReader.camera_model PINHOLE --ImageReader.single_camera 1 --ImageReader.camera_params " + params.str() +
               " --SiftExtraction.use_gpu 0 --SiftExtraction.max_num_features " + std::to_string(o.max_features),
           log, "feature_extractor");
  run_step(exe + " exhaustive_matcher --database_path '" + db.string() + "' --SiftMatching.use_gpu 0", log, "exhaustive_matcher");
  fs::create_directories(workspace / "sparse");
  run_step(exe + " mapper --database_path '" + db.string() + "' --image_path '" + (workspace / "images").string() + "' --output_path '" +
               (workspace / "sparse").string() +
               "' --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0 --Mapper.ba_refine_extra_params 0",
           log, "mapper");
  if (!fs::exists(workspace / "sparse" / "0")) throw std::runtime_error("COLMAP mapper built no model; see " + log.string());
  fs::create_directories(workspace / "model_txt");
  run_step(exe + " model_converter --input_path '" + (workspace / "sparse" / "0").string() + "' --output_path '" +
               (workspace / "model_txt").string() + "' --output_type TXT",
           log, "model_converter");
  const auto model = read_colmap_text_model(workspace / "model_txt");
  std::vector<std::optional<Camera>> out(images.size());
  for (const ColmapImage& im : model) {
    const auto it = std::find(names.begin(), names.end(), im.name);
    if (it == names.end()) continue;
    Camera c = im.camera;
    c.width = width;
    c.height = height;
    out[it - names.begin()] = c;
  }
  return out;
}

}  // namespace lc2wf
