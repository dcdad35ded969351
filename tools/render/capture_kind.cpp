#include "tools/render/capture_kind.h"

#include <stdexcept>

namespace lc2wf {

const char* const kCaptureKinds = "orbit, street-1, street-2 or walk";

bool is_capture_kind(const std::string& kind) { return kind == "orbit" || kind == "street-1" || kind == "street-2" || kind == "walk"; }

CameraRingOptions capture_ring(CameraRingOptions ring, const std::string& kind) {
  if (!is_capture_kind(kind)) throw std::invalid_argument("capture must be " + std::string(kCaptureKinds) + ", got '" + kind + "'");
  if (kind == "orbit") return ring;
  if (kind == "walk") {
    // Walking along the street in front of one long side, the camera at eye height.
    ring.min_camera_height_m = 1.5;
    ring.max_camera_height_m = 1.8;
    ring.azimuth_span_deg = 90.0;
    ring.straight_walk = true;
    return ring;
  }
  // A pedestrian's camera: eye height to an arm held up.
  ring.min_camera_height_m = 1.5;
  ring.max_camera_height_m = 3.0;
  ring.azimuth_span_deg = kind == "street-1" ? 90.0 : 180.0;
  ring.sector_on_corner = kind == "street-2";
  return ring;
}

}  // namespace lc2wf
