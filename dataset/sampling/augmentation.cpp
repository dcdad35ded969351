#include "dataset/sampling/augmentation.h"

#include <cmath>
#include <stdexcept>

#include "dataset/sampling/rng.h"

namespace lc2wf {

void NetworkFrame::Check() const {
  if (!centre_m.allFinite()) throw std::invalid_argument("NetworkFrame.centre_m must be finite");
  if (!(scale_m > 0) || !std::isfinite(scale_m)) throw std::invalid_argument("NetworkFrame.scale_m must be > 0");
}

void AugmentOptions::Check() const {
  if (!(scale_min > 0 && scale_min <= scale_max)) throw std::invalid_argument("AugmentOptions.scale_min must be in (0, scale_max]");
  if (!std::isfinite(scale_max)) throw std::invalid_argument("AugmentOptions.scale_max must be finite");
  if (!(shift_max_m >= 0) || !std::isfinite(shift_max_m)) throw std::invalid_argument("AugmentOptions.shift_max_m must be >= 0");
}

Vec3 Augmentation::apply(const Vec3& p) const {
  Vec3 d = p - centre_m;
  if (angle_rad != 0.0) {
    const double c = std::cos(angle_rad), s = std::sin(angle_rad);
    d = Vec3(c * d.x() - s * d.y(), s * d.x() + c * d.y(), d.z());
  }
  return centre_m + scale * d + shift_m;
}

void Augmentation::apply(std::vector<Vec3>& points) const {
  for (auto& p : points) p = apply(p);
}

void Augmentation::apply(std::vector<Segment3>& segments) const {
  for (auto& s : segments) {
    s.a = apply(s.a);
    s.b = apply(s.b);
  }
}

Augmentation draw_augmentation(DataRng& rng, const AugmentOptions& o, const NetworkFrame& frame) {
  o.Check();
  Augmentation a;
  a.centre_m = frame.centre_m;
  a.scale = rng.uniform(o.scale_min, o.scale_max);
  for (int k = 0; k < 3; ++k) a.shift_m[k] = rng.uniform(-o.shift_max_m, o.shift_max_m);
  if (o.rotate_z) a.angle_rad = rng.uniform(-M_PI, M_PI);
  return a;
}

}  // namespace lc2wf
