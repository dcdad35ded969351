#include "dataset/formats/line_cloud_io.h"

#include <bit>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/util/json_number.h"
#include "core/util/json_text.h"
#include "dataset/formats/read_file.h"
#include "dataset/formats/camera_json.h"
#include "dataset/formats/errors.h"

namespace lc2wf {
namespace {

static_assert(std::endian::native == std::endian::little, "the binary line-cloud block is little-endian");

using Json = nlohmann::json;
constexpr const char* kMagic = "LC2WF-LINECLOUD";
constexpr int kVersion = 1;

template <typename T>
const char* dtype_name();
template <>
const char* dtype_name<double>() { return "f64"; }
template <>
const char* dtype_name<int32_t>() { return "i32"; }
template <>
const char* dtype_name<int64_t>() { return "i64"; }
template <>
const char* dtype_name<uint8_t>() { return "u8"; }

// Collects arrays either inline (JSON) or appended to a binary blob.
class BlockWriter {
 public:
  explicit BlockWriter(bool binary) : binary_(binary) {}
  template <typename T>
  void add(const std::string& name, const std::vector<T>& data, std::vector<int64_t> shape) {
    Json b;
    b["dtype"] = dtype_name<T>();
    b["shape"] = shape;
    if (binary_) {
      b["offset"] = blob_.size();
      b["bytes"] = data.size() * sizeof(T);
      const size_t at = blob_.size();
      blob_.resize(at + data.size() * sizeof(T));
      if (!data.empty()) std::memcpy(blob_.data() + at, data.data(), data.size() * sizeof(T));
    } else {
      b["data"] = data;
    }
    blocks_[name] = std::move(b);
  }
  Json& blocks() { return blocks_; }
  const std::string& blob() const { return blob_; }

 private:
  bool binary_;
  Json blocks_ = Json::object();
  std::string blob_;
};

class BlockReader {
 public:
  BlockReader(const Json& blocks, std::string_view blob, const std::string& src) : blocks_(blocks), blob_(blob), src_(src) {}
  bool has(const std::string& name) const { return blocks_.contains(name); }
  template <typename T>
  std::vector<T> get(const std::string& name, int64_t rows, int64_t cols) const {
    if (!blocks_.contains(name)) throw DataError(src_, "missing array '" + name + "'");
    const Json& b = blocks_.at(name);
    if (!b.is_object() || b.value("dtype", "") != dtype_name<T>()) {
      throw DataError(src_, "array '" + name + "' must have dtype " + dtype_name<T>());
    }
    const auto shape = json_exact_array<int64_t>(b.at("shape"), "arrays." + name + ".shape");
    const std::vector<int64_t> want = cols > 0 ? std::vector<int64_t>{rows, cols} : std::vector<int64_t>{rows};
    if (shape != want) throw DataError(src_, "array '" + name + "' has the wrong shape");
    // Sizes are checked against what the file holds before anything is allocated: a header may claim 10^8 rows.
    if (rows < 0 || (cols > 0 && rows > INT64_MAX / cols)) throw DataError(src_, "array '" + name + "' has an impossible size");
    const uint64_t count = static_cast<uint64_t>(rows) * static_cast<uint64_t>(cols > 0 ? cols : 1);
    if (b.contains("data")) {
      const Json& data = b.at("data");
      if (!data.is_array() || data.size() != count)
        throw DataError(src_, "array '" + name + "' has " + std::to_string(data.is_array() ? data.size() : 0) + " values, shape says " + std::to_string(count));
      return json_exact_array<T>(data, "arrays." + name + ".data");
    }
    const auto offset = json_exact<uint64_t>(b.at("offset"), "arrays." + name + ".offset");
    const auto bytes = json_exact<uint64_t>(b.at("bytes"), "arrays." + name + ".bytes");
    if (count > blob_.size() / sizeof(T) || bytes != count * sizeof(T) || offset > blob_.size() || bytes > blob_.size() - offset) {
      throw DataError(src_, "array '" + name + "' lies outside the binary block (file truncated?)");
    }
    std::vector<T> out(count);
    if (count) std::memcpy(out.data(), blob_.data() + offset, bytes);
    return out;
  }

 private:
  const Json& blocks_;
  std::string_view blob_;
  const std::string& src_;
};

}  // namespace

std::string line_cloud_to_bytes(const LineCloud& c, const LineCloudWriteOptions& options) {
  validate_line_cloud(c, c.name.empty() ? "line cloud" : c.name);
  const int64_t n = static_cast<int64_t>(c.segments.size());
  Json h;
  h["format"] = "lc2wf-linecloud";
  h["version"] = kVersion;
  h["name"] = c.name;
  h["units"] = {{"raw_per_metre", c.units.raw_per_metre},
                {"origin_raw", {c.units.origin_raw.x(), c.units.origin_raw.y(), c.units.origin_raw.z()}}};
  h["cameras"] = Json::array();
  for (const auto& cam : c.cameras) h["cameras"].push_back(camera_to_json(cam));
  Json junctions = Json::array();
  for (const auto& j : c.wireframe.junctions) junctions.push_back({j.x(), j.y(), j.z()});
  h["wireframe"] = {{"junctions", junctions}, {"edges", c.wireframe.edges}};
  h["num_segments"] = n;
  h["has_support"] = !c.support.empty();
  h["has_labels"] = !c.labels.empty();

  BlockWriter w(options.binary);
  std::vector<double> seg(6 * n);
  for (int64_t i = 0; i < n; ++i) {
    const auto& s = c.segments[i];
    for (int k = 0; k < 3; ++k) {
      seg[6 * i + k] = s.a[k];
      seg[6 * i + 3 + k] = s.b[k];
    }
  }
  w.add("segments", seg, {n, 6});
  if (!c.support.empty()) {
    std::vector<int64_t> offsets{0};
    std::vector<int32_t> views;
    std::vector<double> xy;
    for (const auto& list : c.support) {
      for (const auto& o : list) {
        views.push_back(o.view);
        xy.insert(xy.end(), {o.seg.a.x(), o.seg.a.y(), o.seg.b.x(), o.seg.b.y()});
      }
      offsets.push_back(static_cast<int64_t>(views.size()));
    }
    const auto m = static_cast<int64_t>(views.size());
    w.add("support_offsets", offsets, {n + 1});
    w.add("support_view", views, {m});
    w.add("support_xy", xy, {m, 4});
  }
  if (!c.labels.empty()) {
    std::vector<uint8_t> f(n);
    std::vector<int32_t> ids(2 * n);
    std::vector<double> d(2 * n);
    for (int64_t i = 0; i < n; ++i) {
      const auto& l = c.labels[i];
      f[i] = l.f ? 1 : 0;
      ids[2 * i] = l.i1;
      ids[2 * i + 1] = l.i2;
      d[2 * i] = l.d1;
      d[2 * i + 1] = l.d2;
    }
    w.add("label_f", f, {n});
    w.add("label_junctions", ids, {n, 2});
    w.add("label_distances", d, {n, 2});
  }
  h["arrays"] = std::move(w.blocks());
  if (!options.binary) return json_text(h, 1) + "\n";
  const std::string header = json_text(h);
  return std::string(kMagic) + " " + std::to_string(kVersion) + " " + std::to_string(header.size()) + "\n" + header + w.blob();
}

LineCloud line_cloud_from_bytes(const std::string& bytes, const std::string& src) {
  if (bytes.empty()) throw DataError(src, "file is empty");
  Json h;
  std::string_view blob;
  try {
    if (bytes.front() == '{') {
      h = Json::parse(bytes);
    } else {
      const size_t eol = bytes.find('\n');
      const std::string magic = std::string(kMagic) + " ";
      if (eol == std::string::npos || bytes.compare(0, magic.size(), magic) != 0) {
        throw DataError(src, 1, "not a line-cloud file (expected '{' or '" + std::string(kMagic) + " <version> <header bytes>')");
      }
      int version = 0;
      size_t header_len = 0;
      if (std::sscanf(bytes.c_str() + magic.size(), "%d %zu", &version, &header_len) != 2) {
        throw DataError(src, 1, "malformed first line");
      }
      if (version != kVersion) throw DataError(src, 1, "unsupported version " + std::to_string(version));
      if (header_len > bytes.size() - eol - 1) throw DataError(src, "header runs past the end of the file (truncated?)");
      h = Json::parse(bytes.substr(eol + 1, header_len));
      blob = std::string_view(bytes).substr(eol + 1 + header_len);
    }
  } catch (const Json::exception& e) {
    throw DataError(src, std::string("malformed JSON: ") + e.what());
  }

  LineCloud c;
  try {
    if (h.value("format", "") != "lc2wf-linecloud") throw DataError(src, "'format' is not lc2wf-linecloud");
    if (!h.contains("version") || json_exact<int64_t>(h.at("version"), "version") != kVersion) throw DataError(src, "unsupported version");
    c.name = h.value("name", "");
    const auto& u = h.at("units");
    c.units.raw_per_metre = u.at("raw_per_metre").get<double>();
    const auto o = u.at("origin_raw").get<std::vector<double>>();
    if (o.size() != 3) throw DataError(src, "units.origin_raw needs 3 values");
    c.units.origin_raw = Vec3(o[0], o[1], o[2]);
    if (!(c.units.raw_per_metre > 0)) throw DataError(src, "units.raw_per_metre must be > 0");
    for (const auto& cj : h.at("cameras")) c.cameras.push_back(camera_from_json(cj, src));
    for (const auto& j : h.at("wireframe").at("junctions")) {
      const auto v = j.get<std::vector<double>>();
      if (v.size() != 3) throw DataError(src, "wireframe junction needs 3 values");
      c.wireframe.junctions.emplace_back(v[0], v[1], v[2]);
    }
    for (const auto& e : h.at("wireframe").at("edges")) {
      const auto ids = json_exact_array<int>(e, "wireframe.edges");
      if (ids.size() != 2) throw DataError(src, "wireframe edge needs 2 ids");
      c.wireframe.edges.push_back({ids[0], ids[1]});
    }
    const auto n = json_exact<int64_t>(h.at("num_segments"), "num_segments");
    // Every segment takes at least 6 numbers of the file: bounds the count before anything is allocated.
    if (n < 0 || static_cast<uint64_t>(n) > bytes.size() / 6) throw DataError(src, "num_segments " + std::to_string(n) + " does not fit the file's size");
    const BlockReader r(h.at("arrays"), blob, src);
    const auto seg = r.get<double>("segments", n, 6);
    c.segments.resize(n);
    for (int64_t i = 0; i < n; ++i) {
      c.segments[i].a = Vec3(seg[6 * i], seg[6 * i + 1], seg[6 * i + 2]);
      c.segments[i].b = Vec3(seg[6 * i + 3], seg[6 * i + 4], seg[6 * i + 5]);
    }
    if (h.value("has_support", false)) {
      const auto offsets = r.get<int64_t>("support_offsets", n + 1, 0);
      const int64_t m = offsets.back();
      if (offsets.front() != 0 || m < 0) throw DataError(src, "support_offsets must start at 0");
      const auto views = r.get<int32_t>("support_view", m, 0);
      const auto xy = r.get<double>("support_xy", m, 4);
      c.support.resize(n);
      for (int64_t i = 0; i < n; ++i) {
        if (offsets[i + 1] < offsets[i] || offsets[i + 1] > m) throw DataError(src, "support_offsets are not increasing");
        for (int64_t k = offsets[i]; k < offsets[i + 1]; ++k) {
          c.support[i].push_back({views[k], {Vec2(xy[4 * k], xy[4 * k + 1]), Vec2(xy[4 * k + 2], xy[4 * k + 3])}});
        }
      }
    }
    if (h.value("has_labels", false)) {
      const auto f = r.get<uint8_t>("label_f", n, 0);
      const auto ids = r.get<int32_t>("label_junctions", n, 2);
      const auto d = r.get<double>("label_distances", n, 2);
      c.labels.resize(n);
      for (int64_t i = 0; i < n; ++i) c.labels[i] = {f[i] != 0, ids[2 * i], d[2 * i], ids[2 * i + 1], d[2 * i + 1]};
    }
  } catch (const Json::exception& e) {
    throw DataError(src, std::string("bad field: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw DataError(src, e.what());
  }
  validate_line_cloud(c, src);
  return c;
}

void write_line_cloud(const std::filesystem::path& path, const LineCloud& cloud, const LineCloudWriteOptions& options) {
  std::string bytes;
  try {
    bytes = line_cloud_to_bytes(cloud, options);
  } catch (const DataError& e) {
    throw DataError(path.string(), e.what());
  }
  write_file_atomic(path, bytes);
}

LineCloud read_line_cloud(const std::filesystem::path& path) {
  return line_cloud_from_bytes(read_file(path), path.string());
}

}  // namespace lc2wf
