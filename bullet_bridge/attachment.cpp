#include "bullet_bridge/attachment.h"

#include "rope/common/error.h"

namespace rope::bullet {

void AttachmentSettings::validate() const {
  requirePositive("attachment.stiffness", stiffness);
  requireNonNegative("attachment.damping", damping);
}

ContactSpring attachmentSpring(double stiffness, double damping, const Vec3& ropePoint, const Vec3& bodyPoint,
                               const Vec3& ropeVelocity, const Vec3& bodyVelocity, double h) {
  ContactSpring spring;
  spring.force = -stiffness * (ropePoint - bodyPoint) - damping * (ropeVelocity - bodyVelocity) +
                 stiffness * h * bodyVelocity;
  spring.stiffness = stiffness * Eigen::Matrix3d::Identity();
  spring.damping = damping * Eigen::Matrix3d::Identity();
  return spring;
}

}  // namespace rope::bullet
