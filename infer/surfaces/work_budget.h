// The work budget of one face search (SurfaceOptions::max_work_steps): the steps whose number can grow faster
// than the graph (pairs of edges at a junction, junctions tested against a candidate plane, edges and rings of
// a plane's graph, pairs of faces checked against each other) are charged before they are done; once a charge
// does not fit, the budget is exhausted, the step stops and the search returns what it had finished, with
// reason() among the model's reasons. The steps done never exceed the limit.
#pragma once

#include <string>

namespace lc2wf {

class WorkBudget {
 public:
  explicit WorkBudget(long limit) : limit_(limit) {}

  // Takes `steps` from the budget for the step named `step` ("candidate planes"); false, and nothing taken,
  // when they do not fit (then and on every later call: a stopped search does not resume).
  bool charge(long steps, const char* step) {
    if (exhausted_) return false;
    if (steps > limit_ - used_) {
      exhausted_ = true;
      step_ = step;
      return false;
    }
    used_ += steps;
    return true;
  }
  bool exhausted() const { return exhausted_; }
  long used() const { return used_; }
  long limit() const { return limit_; }
  // "surfaces: work budget reached after 1234 steps (surfaces.max_work_steps = 2000) in candidate planes".
  std::string reason() const {
    return "surfaces: work budget reached after " + std::to_string(used_) + " steps (surfaces.max_work_steps = " +
           std::to_string(limit_) + ") in " + step_;
  }

 private:
  long limit_;
  long used_ = 0;
  bool exhausted_ = false;
  std::string step_;
};

}  // namespace lc2wf
