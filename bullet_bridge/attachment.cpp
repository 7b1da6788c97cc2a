// SPDX-License-Identifier: MIT
#include "bullet_bridge/attachment.h"

#include <Eigen/Eigenvalues>
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

ContactSpring attachmentSpring(const Eigen::Matrix3d& stiffness, const Eigen::Matrix3d& damping, const Vec3& ropePoint,
                               const Vec3& bodyPoint, const Vec3& ropeVelocity, const Vec3& bodyVelocity, double h) {
  ContactSpring spring;
  spring.force = -stiffness * (ropePoint - bodyPoint) - damping * (ropeVelocity - bodyVelocity) +
                 h * (stiffness * bodyVelocity);
  spring.stiffness = stiffness;
  spring.damping = damping;
  return spring;
}

void capAttachmentForBody(const Eigen::Matrix3d& inverseMass, double h, double share, double stiffness,
                          double damping, Eigen::Matrix3d& stiffnessOut, Eigen::Matrix3d& dampingOut) {
  stiffnessOut = stiffness * Eigen::Matrix3d::Identity();
  dampingOut = damping * Eigen::Matrix3d::Identity();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inverseMass);
  if (solver.info() != Eigen::Success) return;
  const Vec3 lambda = solver.eigenvalues();
  Vec3 k, c;
  bool capped = false;
  for (int i = 0; i < 3; ++i) {
    // Stability of the body's explicit side along eigendirection i: k lambda h^2 <= share (capForBody).
    k[i] = lambda[i] > 0.0 ? std::min(stiffness, share / (h * h * lambda[i])) : stiffness;
    c[i] = lambda[i] > 0.0 ? std::min(damping, share / (h * lambda[i])) : damping;
    capped = capped || k[i] < stiffness || c[i] < damping;
  }
  if (!capped) return;
  const Eigen::Matrix3d& q = solver.eigenvectors();
  stiffnessOut = q * k.asDiagonal() * q.transpose();
  dampingOut = q * c.asDiagonal() * q.transpose();
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
