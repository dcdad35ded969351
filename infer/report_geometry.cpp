#include "infer/report_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace lc2wf {
namespace {

template <typename T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // x86/ARM hosts are little endian, as the layout requires
  out.append(b, sizeof(T));
}

uint8_t byte_score(double s) { return static_cast<uint8_t>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0)); }

}  // namespace

std::string base64_encode(std::string_view bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8) | uint8_t(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const uint32_t v = (uint8_t(bytes[i]) << 16) | (two ? uint8_t(bytes[i + 1]) << 8 : 0);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += two ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string encode_report_geometry(const ReportGeometryInput& in, int max_cloud_segments) {
  const Wireframe& pw = in.pred->wireframe;
  const Wireframe& gt = *in.gt;
  if (pw.junctions.size() > 65535 || gt.junctions.size() > 65535)
    throw std::invalid_argument("report geometry: more than 65535 junctions in one wireframe");
  if (in.junctions.pred.size() != pw.junctions.size() || in.junctions.gt.size() != gt.junctions.size() ||
      in.edges.pred.size() != pw.edges.size() || in.edges.gt.size() != gt.edges.size())
    throw std::invalid_argument("report geometry: match status sizes differ from the wireframes");
  std::vector<const Segment3*> cloud;
  const size_t total = in.cloud ? in.cloud->size() : 0;
  const size_t keep = std::min<size_t>(total, static_cast<size_t>(std::max(0, max_cloud_segments)));
  for (size_t k = 0; k < keep; ++k) cloud.push_back(&(*in.cloud)[k * total / keep]);

  // Quantisation box: every point of the three layers.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  auto grow = [&](const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); };
  for (const Segment3* s : cloud) grow(s->a), grow(s->b);
  for (const Vec3& p : pw.junctions) grow(p);
  for (const Vec3& p : gt.junctions) grow(p);
  if (!std::isfinite(lo.x())) lo = hi = Vec3::Zero();
  const Vec3 origin = (lo + hi) / 2;
  const double step = std::max((hi - lo).maxCoeff() / 2 / 32000.0, 1e-6);  // |q| <= 32000 fits int16

  std::string b;
  for (int k = 0; k < 3; ++k) put<float>(b, static_cast<float>(origin[k]));
  put<float>(b, static_cast<float>(step));
  for (size_t n : {cloud.size(), pw.junctions.size(), pw.edges.size(), gt.junctions.size(), gt.edges.size()})
    put<uint32_t>(b, static_cast<uint32_t>(n));
  put<uint32_t>(b, static_cast<uint32_t>(in.vertex_thresholds));
  put<uint32_t>(b, static_cast<uint32_t>(in.edge_thresholds));
  auto point = [&](const Vec3& p) {
    for (int k = 0; k < 3; ++k) put<int16_t>(b, static_cast<int16_t>(std::lround((p[k] - origin[k]) / step)));
  };
  for (const Segment3* s : cloud) point(s->a), point(s->b);
  for (const Vec3& p : pw.junctions) point(p);
  for (const Vec3& p : gt.junctions) point(p);
  for (const auto& e : pw.edges) put<uint16_t>(b, uint16_t(e[0])), put<uint16_t>(b, uint16_t(e[1]));
  for (const auto& e : gt.edges) put<uint16_t>(b, uint16_t(e[0])), put<uint16_t>(b, uint16_t(e[1]));
  for (double s : in.pred->junction_scores) put<uint8_t>(b, byte_score(s));
  for (double s : in.pred->edge_scores) put<uint8_t>(b, byte_score(s));
  for (const auto* bits : {&in.junctions.pred, &in.junctions.gt, &in.edges.pred, &in.edges.gt})
    b.append(reinterpret_cast<const char*>(bits->data()), bits->size());
  return base64_encode(b);
}

}  // namespace lc2wf
