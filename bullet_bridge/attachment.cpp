// SPDX-License-Identifier: MIT
#include "bullet_bridge/attachment.h"

#include <Eigen/Geometry>

#include "rope/common/error.h"

namespace rope::bullet {

void AttachmentSettings::validate() const {
  requirePositive("attachment.stiffness", stiffness);
  requireNonNegative("attachment.damping", damping);
  requirePositive("attachment.angularStiffness", angularStiffness);
  requireNonNegative("attachment.angularDamping", angularDamping);
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

ContactSpring clampTangentSpring(double stiffness, double damping, double restMetric, const Vec3& derivative,
                                 const Vec3& derivativeRate, const Vec3& direction, const Vec3& angularVelocity,
                                 double h) {
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - direction * direction.transpose();
  const double scale = 1.0 / (restMetric * restMetric);
  const Vec3 targetRate = across * angularVelocity.cross(derivative);  // the body-fixed target turning
  ContactSpring spring;
  spring.force = scale * (-stiffness * (across * derivative) - damping * (across * derivativeRate - targetRate) +
                          stiffness * h * targetRate);
  spring.stiffness = (scale * stiffness) * across;
  spring.damping = (scale * damping) * across;
  return spring;
}

}  // namespace rope::bullet
