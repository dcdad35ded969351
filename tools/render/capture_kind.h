// The captures lc2wf-dataset --capture names, as settings of the one camera ring (camera_ring.h): a drone-like
// orbit, or a pedestrian's photos of one facade or of two facades around a corner, or from a walk along one.
#pragma once

#include <string>

#include "tools/render/camera_ring.h"

namespace lc2wf {

// "orbit, street-1, street-2 or walk", for messages.
extern const char* const kCaptureKinds;

bool is_capture_kind(const std::string& kind);

// `ring` set for the capture: orbit leaves it as it is (oblique rings all around); street-1 puts every view
// in a 90 degree sector in front of one long side of the footprint, street-2 in a 180 degree sector around
// one of its corners, both from 1.5-3 m above the ground looking at the building's centre (slightly up); walk
// puts them on a straight line along one long side at eye height (1.5-1.8 m), as a pedestrian walking down the
// street takes them (the lines along the street then lie in the views' epipolar planes).
// Throws std::invalid_argument for an unknown kind.
CameraRingOptions capture_ring(CameraRingOptions ring, const std::string& kind);

}  // namespace lc2wf
