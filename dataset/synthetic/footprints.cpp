#include "dataset/synthetic/footprints.h"

namespace lc2wf {

std::vector<Wing> l_wings(double a, double b, double w, bool gabled) {
  return {{{0, 0, a, w}, true}, {{0, gabled ? 0.5 * w : 0.0, w, b}, false}};
}

std::vector<Wing> t_wings(double a, double b, double w, double stem, double at, bool gabled) {
  return {{{0, 0, a, w}, true}, {{at, gabled ? 0.5 * w : 0.0, at + stem, b}, false}};
}

std::vector<Wing> u_wings(double a, double b, double w, bool gabled) {
  const double y0 = gabled ? 0.5 * w : 0.0;
  return {{{0, 0, a, w}, true}, {{0, y0, w, b}, false}, {{a - w, y0, a, b}, false}};
}

std::vector<Wing> courtyard_wings(double a, double b, double w, bool gabled) {
  const double y0 = gabled ? 0.5 * w : 0.0, y1 = gabled ? b - 0.5 * w : b;
  return {{{0, 0, a, w}, true}, {{0, b - w, a, b}, true}, {{0, y0, w, y1}, false}, {{a - w, y0, a, y1}, false}};
}

}  // namespace lc2wf
