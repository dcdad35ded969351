#include "tools/colmap/colmap_model.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/text_parse.h"

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

// Far above any photo; keeps width * height and pixel arithmetic inside int.
constexpr long long kMaxImageSide = 1'000'000;

// COLMAP's model ids and parameter counts for the models we accept (its camera_models.h numbering).
struct ModelSpec {
  const char* name;
  int id;
  size_t params;
};
constexpr ModelSpec kModels[] = {{"SIMPLE_PINHOLE", 0, 3}, {"PINHOLE", 1, 4}, {"SIMPLE_RADIAL", 2, 4}, {"RADIAL", 3, 5}};

// Intrinsics from one camera entry; `fail` throws naming the entry. Distortion must be zero.
template <class Fail>
ColmapIntrinsics make_intrinsics(const ModelSpec& model, long long width, long long height, const std::vector<double>& p,
                                 Fail fail) {
  if (p.size() != model.params)
    fail(std::string(model.name) + " needs " + std::to_string(model.params) + " parameters, found " + std::to_string(p.size()));
  if (width < 1 || width > kMaxImageSide || height < 1 || height > kMaxImageSide)
    fail("image size " + std::to_string(width) + " x " + std::to_string(height) + " outside 1.." + std::to_string(kMaxImageSide));
  for (double v : p)
    if (!std::isfinite(v) || std::abs(v) > kMaxCoordinate) fail("parameter " + std::to_string(v) + " is not a finite number within +-1e9");
  const bool pinhole = model.id == 1;
  const double fx = p[0], fy = pinhole ? p[1] : p[0], cx = pinhole ? p[2] : p[1], cy = pinhole ? p[3] : p[2];
  if (!(fx > 0) || !(fy > 0)) fail("focal length must be > 0");
  for (size_t k = pinhole ? 4 : 3; k < p.size(); ++k)
    if (std::abs(p[k]) > 1e-9) fail("lens distortion is not supported; undistort the images first");
  ColmapIntrinsics c;
  c.K << fx, 0, cx - 0.5, 0, fy, cy - 0.5, 0, 0, 1;  // COLMAP's pixel centres sit at +0.5
  c.width = static_cast<int>(width);
  c.height = static_cast<int>(height);
  return c;
}

// The image's camera from its pose; `fail` throws naming the image.
template <class Fail>
ColmapImage make_image(std::string name, const double q[4], const double t[3], long long camera_id, const ColmapCameras& cameras,
                       Fail fail) {
  if (name.empty()) fail("empty image name");
  if (name.find('\0') != std::string::npos) fail("image name holds a NUL byte");
  for (int k = 0; k < 4; ++k)
    if (!std::isfinite(q[k]) || std::abs(q[k]) > kMaxCoordinate) fail("quaternion is not finite");
  if (!(std::hypot(std::hypot(q[0], q[1]), std::hypot(q[2], q[3])) > 1e-12)) fail("quaternion is zero (no rotation)");
  const Vec3 tv(t[0], t[1], t[2]);
  if (!within_coordinate_limit(tv)) fail("translation is not finite or beyond +-1e9");
  const auto it = cameras.find(camera_id);
  if (it == cameras.end()) fail("unknown camera id " + std::to_string(camera_id));
  ColmapImage im;
  im.name = std::move(name);
  im.camera.K = it->second.K;
  im.camera.width = it->second.width;
  im.camera.height = it->second.height;
  im.camera.R = quaternion_to_rotation(q[0], q[1], q[2], q[3]);
  im.camera.t = tv;
  return im;
}

// ---- text ----

struct TextLine {
  int number = 0;
  std::string_view text;
};

// Lines with their 1-based numbers; comments dropped, blank lines kept (an image's point line may be empty).
std::vector<TextLine> text_lines(const std::string& text) {
  std::vector<TextLine> out;
  int n = 0;
  for (size_t pos = 0; pos < text.size();) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view line = trim(std::string_view(text).substr(pos, end - pos));
    ++n;
    pos = end + 1;
    if (!line.empty() && line.front() == '#') continue;
    out.push_back({n, line});
  }
  return out;
}

// ---- binary: little-endian fields read through a bounds-checked cursor ----

class ByteCursor {
 public:
  ByteCursor(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}
  size_t offset() const { return pos_; }
  size_t remaining() const { return bytes_.size() - pos_; }
  template <class T>
  T read(const std::string& field) {
    if (remaining() < sizeof(T)) fail("file ends inside " + field);
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    std::uint64_t bits = 0;
    for (size_t k = 0; k < sizeof(T); ++k) bits |= std::uint64_t{raw[k]} << (8 * k);
    T v;
    if constexpr (sizeof(T) == 8) std::memcpy(&v, &bits, 8);
    else {
      const auto narrow = static_cast<std::uint32_t>(bits);
      std::memcpy(&v, &narrow, 4);
    }
    return v;
  }
  std::string c_string(const std::string& field) {
    const size_t end = bytes_.find('\0', pos_);
    if (end == std::string_view::npos) fail("file ends inside " + field + " (no terminating NUL)");
    std::string s(bytes_.substr(pos_, end - pos_));
    pos_ = end + 1;
    return s;
  }
  void skip(std::uint64_t count, size_t each, const std::string& what) {
    if (count > remaining() / each) fail(what + " count " + std::to_string(count) + " exceeds the bytes left in the file");
    pos_ += static_cast<size_t>(count) * each;
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw DataError(source_, "byte " + std::to_string(pos_) + ": " + problem);
  }

 private:
  std::string_view bytes_;
  const std::string& source_;
  size_t pos_ = 0;
};

}  // namespace

ColmapCameras parse_colmap_cameras_txt(const std::string& text, const std::string& source) {
  ColmapCameras cameras;
  for (const TextLine& line : text_lines(text)) {
    if (line.text.empty()) continue;
    auto fail = [&](const std::string& problem) { throw DataError(source, line.number, problem); };
    const auto tok = split_tokens(line.text, " \t\r");
    if (tok.size() < 4) fail("expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS...");
    const auto id = parse_int(tok[0]), width = parse_int(tok[2]), height = parse_int(tok[3]);
    if (!id || *id < 0) fail("CAMERA_ID '" + std::string(tok[0]) + "' is not an integer >= 0");
    if (!width || !height) fail("WIDTH/HEIGHT '" + std::string(tok[2]) + " " + std::string(tok[3]) + "' are not integers");
    const ModelSpec* model = nullptr;
    for (const ModelSpec& m : kModels)
      if (tok[1] == m.name) model = &m;
    if (!model) fail("unsupported camera model '" + std::string(tok[1]) + "' (PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL or RADIAL)");
    std::vector<double> params;
    for (size_t k = 4; k < tok.size(); ++k) {
      const auto v = parse_finite_double(tok[k]);
      if (!v) fail("parameter '" + std::string(tok[k]) + "' is not a finite number");
      params.push_back(*v);
    }
    if (cameras.count(*id)) fail("camera id " + std::to_string(*id) + " is listed twice");
    cameras[*id] = make_intrinsics(*model, *width, *height, params, fail);
  }
  return cameras;
}

std::vector<ColmapImage> parse_colmap_images_txt(const std::string& text, const std::string& source, const ColmapCameras& cameras) {
  std::vector<ColmapImage> out;
  std::set<long long> ids;
  const std::vector<TextLine> lines = text_lines(text);
  // Each image takes two lines: the pose line, then its (possibly empty) 2D point line.
  for (size_t k = 0; k < lines.size(); ++k) {
    const TextLine& line = lines[k];
    if (line.text.empty()) continue;
    auto fail = [&](const std::string& problem) { throw DataError(source, line.number, problem); };
    const auto tok = split_tokens(line.text, " \t\r");
    if (tok.size() != 10) fail("expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME, found " + std::to_string(tok.size()) + " values");
    const auto id = parse_int(tok[0]), camera = parse_int(tok[8]);
    if (!id) fail("IMAGE_ID '" + std::string(tok[0]) + "' is not an integer");
    if (!camera) fail("CAMERA_ID '" + std::string(tok[8]) + "' is not an integer");
    double q[4], t[3];
    const char* fields[] = {"QW", "QX", "QY", "QZ", "TX", "TY", "TZ"};
    for (int f = 0; f < 7; ++f) {
      const auto v = parse_finite_double(tok[1 + f]);
      if (!v) fail(std::string(fields[f]) + " '" + std::string(tok[1 + f]) + "' is not a finite number");
      (f < 4 ? q[f] : t[f - 4]) = *v;
    }
    if (!ids.insert(*id).second) fail("image id " + std::to_string(*id) + " is listed twice");
    out.push_back(make_image(std::string(tok[9]), q, t, *camera, cameras, fail));
    ++k;  // skip the points line
  }
  return out;
}

ColmapCameras parse_colmap_cameras_bin(std::string_view bytes, const std::string& source) {
  ByteCursor c(bytes, source);
  ColmapCameras cameras;
  const std::uint64_t count = c.read<std::uint64_t>("the camera count");
  // No reserve from the count: the loop ends at the file's end whatever the header claims.
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::string at = " of camera " + std::to_string(i + 1);
    const size_t start = c.offset();
    auto fail = [&](const std::string& problem) { throw DataError(source, "camera " + std::to_string(i + 1) + " at byte " + std::to_string(start) + ": " + problem); };
    const std::uint32_t id = c.read<std::uint32_t>("camera_id" + at);
    const std::int32_t model_id = c.read<std::int32_t>("model_id" + at);
    const std::uint64_t width = c.read<std::uint64_t>("width" + at), height = c.read<std::uint64_t>("height" + at);
    const ModelSpec* model = nullptr;
    for (const ModelSpec& m : kModels)
      if (model_id == m.id) model = &m;
    if (!model) fail("unsupported camera model id " + std::to_string(model_id) + " (0-3: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL)");
    std::vector<double> params;
    for (size_t k = 0; k < model->params; ++k) params.push_back(c.read<double>("parameter " + std::to_string(k + 1) + at));
    if (cameras.count(id)) fail("camera id " + std::to_string(id) + " is listed twice");
    if (width > static_cast<std::uint64_t>(kMaxImageSide) || height > static_cast<std::uint64_t>(kMaxImageSide))
      fail("image size " + std::to_string(width) + " x " + std::to_string(height) + " outside 1.." + std::to_string(kMaxImageSide));
    cameras[id] = make_intrinsics(*model, static_cast<long long>(width), static_cast<long long>(height), params, fail);
  }
  if (c.remaining() != 0) c.fail(std::to_string(c.remaining()) + " bytes after the last of " + std::to_string(count) + " cameras");
  return cameras;
}

std::vector<ColmapImage> parse_colmap_images_bin(std::string_view bytes, const std::string& source, const ColmapCameras& cameras) {
  ByteCursor c(bytes, source);
  std::vector<ColmapImage> out;
  std::set<std::uint32_t> ids;
  const std::uint64_t count = c.read<std::uint64_t>("the image count");
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::string at = " of image " + std::to_string(i + 1);
    const size_t start = c.offset();
    auto fail = [&](const std::string& problem) { throw DataError(source, "image " + std::to_string(i + 1) + " at byte " + std::to_string(start) + ": " + problem); };
    const std::uint32_t id = c.read<std::uint32_t>("image_id" + at);
    double q[4], t[3];
    for (double& v : q) v = c.read<double>("qvec" + at);
    for (double& v : t) v = c.read<double>("tvec" + at);
    const std::uint32_t camera = c.read<std::uint32_t>("camera_id" + at);
    std::string name = c.c_string("name" + at);
    // Each 2D point: x, y (double) and its 3D point id (uint64); not needed, only skipped.
    c.skip(c.read<std::uint64_t>("num_points2D" + at), 24, "num_points2D" + at);
    if (!ids.insert(id).second) fail("image id " + std::to_string(id) + " is listed twice");
    out.push_back(make_image(std::move(name), q, t, camera, cameras, fail));
  }
  if (c.remaining() != 0) c.fail(std::to_string(c.remaining()) + " bytes after the last of " + std::to_string(count) + " images");
  return out;
}

std::vector<ColmapImage> read_colmap_text_model(const fs::path& dir) {
  const fs::path cp = dir / "cameras.txt", ip = dir / "images.txt";
  return parse_colmap_images_txt(read_file(ip), ip.string(), parse_colmap_cameras_txt(read_file(cp), cp.string()));
}

std::vector<ColmapImage> read_colmap_model(const fs::path& dir) {
  if (fs::exists(dir / "cameras.txt")) return read_colmap_text_model(dir);
  const fs::path cp = dir / "cameras.bin", ip = dir / "images.bin";
  if (!fs::exists(cp) || !fs::exists(ip))
    throw DataError(dir.string(), "not a COLMAP model (no cameras.txt/images.txt or cameras.bin/images.bin)");
  return parse_colmap_images_bin(read_file(ip), ip.string(), parse_colmap_cameras_bin(read_file(cp), cp.string()));
}

}  // namespace lc2wf
