// A rigid blade: the half-space behind a plane face that ends at a straight tip line along
// y (the doctor blade of creping). Particles touch the face, or the tip line when they pass
// below it, through the same mirror-image van Wyk contact as the walls (walls.h). The blade
// moves with a prescribed velocity; an optional hard core stops centres at the face (below).
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "engine/core/types.h"

namespace fibrenet {

struct Blade {
  Vec3 tip = Vec3::Zero();        // a point of the tip line (the line runs along y) [m]
  Vec3 face_normal = Vec3::UnitX();  // unit, in the x-z plane, pointing out of the blade
  Vec3 face_up = Vec3::UnitZ();      // unit, along the face away from the tip
  Vec3 velocity = Vec3::Zero();      // prescribed [m/s]
  bool friction = true;              // Coulomb friction
  // Its coefficient against the steel; unset, the fibre-fibre contacts' mu.
  std::optional<double> mu;
  // Hard core: once a particle's centre comes closer to the blade than hard_gap (a fraction
  // of its radius: the fibre wall has collapsed), a linear spring of hard_stiffness [N/m]
  // adds to the van Wyk force, so that no centre is driven through the steel at impact
  // speeds. 0 = off.
  double hard_stiffness = 0.0;
  double hard_gap = 0.5;
  // Reaction of the particles on the blade during the last step [N], the work the blade has
  // done on them since the start [J], and each particle's tangential history against it.
  Vec3 reaction = Vec3::Zero();
  double work = 0.0;
  std::vector<Vec3> history;

  // A blade whose face makes `angle` [rad] with the surface it scrapes (the plane z = tip.z
  // on the side x < tip.x): 90 degrees is a vertical face, less leans over the oncoming sheet.
  static Blade AtAngle(const Vec3& tip, double angle) {
    Blade b;
    b.tip = tip;
    b.face_up = Vec3(-std::cos(angle), 0.0, std::sin(angle));
    b.face_normal = Vec3(-std::sin(angle), 0.0, -std::cos(angle));
    return b;
  }

  // The blade is the quarter space behind the face and above the plane through the tip
  // normal to the face (its bottom: a 90 degree wedge, whose bottom rises behind the tip at
  // 90 degrees minus the face angle, like a bevelled blade). For a particle centre at x it
  // returns the unit normal from the blade towards the centre and the centre's distance from
  // the blade surface: face, tip line or bottom, whichever is nearest; negative inside.
  struct Touch {
    Vec3 normal;
    double gap;
  };
  Touch Nearest(const Vec3& x) const {
    const Vec3 rel(x.x() - tip.x(), 0.0, x.z() - tip.z());
    const double along = rel.dot(face_up), out = rel.dot(face_normal);
    if (along >= 0.0) return {face_normal, out};  // over the face, or inside through it
    if (out < 0.0) return {-face_up, -along};      // under the bottom
    const double r = rel.norm();                   // beside the tip line
    return r > 0.0 ? Touch{rel / r, r} : Touch{face_normal, 0.0};
  }
};

}  // namespace fibrenet
