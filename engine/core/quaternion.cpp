#include "engine/core/quaternion.h"

namespace fibrenet {

Quat FrameAlongAxis(const Vec3& axis) { return Quat::FromTwoVectors(Vec3::UnitX(), axis); }

}  // namespace fibrenet
