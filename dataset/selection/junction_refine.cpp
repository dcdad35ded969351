#include "dataset/selection/junction_refine.h"

#include <stdexcept>
#include <string>

#include "dataset/geometry/line_meeting_point.h"

namespace lc2wf {

void JunctionRefineOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("JunctionRefineOptions." + what); };
  if (!(radius >= 0)) fail("radius must be >= 0");
  if (min_segments < 2) fail("min_segments must be >= 2");
  if (!(prior_weight > 0)) fail("prior_weight must be > 0");
  if (!(min_length >= 0)) fail("min_length must be >= 0");
  if (!(robust_scale >= 0)) fail("robust_scale must be >= 0");
  if (robust_iterations < 0) fail("robust_iterations must be >= 0");
}

std::vector<Vec3> refine_junctions(const std::vector<Vec3>& junctions, const std::vector<Segment3>& segments,
                                   const JunctionRefineOptions& options) {
  options.Check();
  std::vector<Vec3> out = junctions;
  if (options.radius == 0) return out;
  const double r2 = options.radius * options.radius;
  struct Line {
    Vec3 p, u;
  };
  std::vector<Line> lines;
  for (Vec3& J : out) {
    lines.clear();
    for (const Segment3& s : segments) {
      if ((s.a - J).squaredNorm() > r2 && (s.b - J).squaredNorm() > r2) continue;  // cheap test first
      const Vec3 d = s.b - s.a;
      const double len = d.norm();
      if (len < options.min_length) continue;
      lines.push_back({s.a, d / len});
    }
    if (static_cast<int>(lines.size()) < options.min_segments) continue;
    // Plain least squares first; then, with a robust scale, each line weighted by its distance from the
    // previous estimate (Cauchy), so lines that pass the junction by are outvoted by those meeting there.
    const int rounds = options.robust_scale > 0 ? 1 + options.robust_iterations : 1;
    Vec3 X = J;
    for (int round = 0; round < rounds; ++round) {
      LineMeetingPoint meeting;
      meeting.add_prior(J, options.prior_weight);
      for (const Line& l : lines) {
        double w = 1.0;
        if (round > 0) {
          const Vec3 off = (X - l.p) - l.u * l.u.dot(X - l.p);
          w = 1.0 / (1.0 + off.squaredNorm() / (options.robust_scale * options.robust_scale));
        }
        meeting.add_line(l.p, l.u, w);
      }
      const Vec3 next = meeting.A.ldlt().solve(meeting.b);
      if (!next.allFinite()) break;
      X = next;
    }
    if (X.allFinite() && (X - J).squaredNorm() <= r2) J = X;
  }
  return out;
}

}  // namespace lc2wf
