#include "dataset/junction_refine.h"

#include <stdexcept>
#include <string>

#include "dataset/line_meeting_point.h"

namespace lc2wf {

void JunctionRefineOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("JunctionRefineOptions." + what); };
  if (!(radius >= 0)) fail("radius must be >= 0");
  if (min_segments < 2) fail("min_segments must be >= 2");
  if (!(prior_weight > 0)) fail("prior_weight must be > 0");
  if (!(min_length >= 0)) fail("min_length must be >= 0");
}

std::vector<Vec3> refine_junctions(const std::vector<Vec3>& junctions, const std::vector<Segment3>& segments,
                                   const JunctionRefineOptions& options) {
  options.Check();
  std::vector<Vec3> out = junctions;
  if (options.radius == 0) return out;
  const double r2 = options.radius * options.radius;
  for (Vec3& J : out) {
    LineMeetingPoint meeting;
    meeting.add_prior(J, options.prior_weight);
    int used = 0;
    for (const Segment3& s : segments) {
      if ((s.a - J).squaredNorm() > r2 && (s.b - J).squaredNorm() > r2) continue;  // cheap test first
      const Vec3 d = s.b - s.a;
      const double len = d.norm();
      if (len < options.min_length) continue;
      meeting.add_line(s.a, d / len);
      ++used;
    }
    if (used < options.min_segments) continue;
    const Vec3 X = meeting.A.ldlt().solve(meeting.b);
    if (X.allFinite() && (X - J).squaredNorm() <= r2) J = X;
  }
  return out;
}

}  // namespace lc2wf
