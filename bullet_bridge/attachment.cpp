// SPDX-License-Identifier: MIT
#include "bullet_bridge/attachment.h"

#include <Eigen/LU>
#include <Eigen/Geometry>
#include <algorithm>

#include "rope/common/error.h"

namespace rope::bullet {

void AttachmentSettings::validate() const {
  requirePositive("attachment.stiffness", stiffness);
  requireNonNegative("attachment.damping", damping);
  requirePositive("attachment.angularStiffness", angularStiffness);
  requireNonNegative("attachment.angularDamping", angularDamping);
}

void seriesWithBody(ContactSpring& spring, const Eigen::Matrix3d& inverseMass, double h) {
  // A = I + (h^2 K + h C) W; f = A^-1 (f0 - h K du - C du) keeps Rod::addSpring's form with every term
  // premultiplied by A^-1 (K and C are multiples of the identity, so A^-1 K stays symmetric).
  const Eigen::Matrix3d a = Eigen::Matrix3d::Identity() + (h * h * spring.stiffness + h * spring.damping) * inverseMass;
  const Eigen::Matrix3d inverse = a.inverse();
  spring.force = inverse * spring.force;
  spring.stiffness = inverse * spring.stiffness;
  spring.damping = inverse * spring.damping;
  // Symmetrise away round-off: the rope's system needs exactly symmetric blocks.
  spring.stiffness = 0.5 * (spring.stiffness + spring.stiffness.transpose()).eval();
  spring.damping = 0.5 * (spring.damping + spring.damping.transpose()).eval();
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
