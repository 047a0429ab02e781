// The affine velocity field a test rig imposes along one axis (0 = x, 2 = z):
//   u_axis(x) = u_half * clamp((x_axis - centre) / half_span, -1, 1),
// the other components zero. Beyond the span it is uniform (the grips move rigidly there).
// A uniform-rate affine deformation has no acceleration and so no inertial force. The default
// (u_half = 0) is rest.
#pragma once

#include <algorithm>

#include "engine/core/types.h"

namespace fibrenet {

struct AffineField {
  int axis = 0;
  double centre = 0.0, half_span = 1.0, u_half = 0.0;  // [m], [m], [m/s]

  bool IsRest() const { return u_half == 0.0; }
  // Built from scalars: a vector whose one component was stored at a run-time index and then
  // read whole stalls on the store forwarding (the integrator calls this for every particle).
  Vec3 At(const Vec3& x) const {
    const double u = u_half * std::clamp((x[axis] - centre) / half_span, -1.0, 1.0);
    return Vec3(axis == 0 ? u : 0.0, axis == 1 ? u : 0.0, axis == 2 ? u : 0.0);
  }
};

}  // namespace fibrenet
