// SPDX-License-Identifier: MIT
#include "bullet_bridge/contact/contact_response.h"

#include <algorithm>
#include <cmath>

namespace rope::bullet {

ContactSpring contactSpring(const ContactLaw& law, double distance, const Vec3& normal, const Vec3& ropeVelocity,
                            const Vec3& bodyVelocity, double h, double frictionNormalForce) {
  const Vec3 w = ropeVelocity - bodyVelocity;
  const Eigen::Matrix3d nn = normal * normal.transpose();
  const Eigen::Matrix3d tangentPlane = Eigen::Matrix3d::Identity() - nn;

  ContactSpring spring;
  if (distance > 0.0) {
    // Speculative: the gap closes within the step. Drive the relative normal speed to -d/h, the
    // speed that lands the rope on the surface at the end of the step (f = c_s (-d/h - n.w_new),
    // implicit in w_new); the penalty spring takes over once it touches.
    spring.force = law.speculativeDamping * (-distance / h - normal.dot(w)) * normal;
    spring.damping = law.speculativeDamping * nn;
  } else {
    const double normalForce = -law.stiffness * distance - law.damping * normal.dot(w) +
                               law.stiffness * h * normal.dot(bodyVelocity);
    spring.force = normalForce * normal;
    spring.stiffness = law.stiffness * nn;
    spring.damping = law.damping * nn;
  }

  // Friction bound from the normal force at the current state (not its damping part, which would
  // make friction depend on the approach speed).
  const double pressing =
      frictionNormalForce >= 0.0 ? frictionNormalForce : std::max(0.0, -law.stiffness * distance);
  if (law.friction > 0.0 && pressing > 0.0) {
    const Vec3 slip = tangentPlane * w;
    const double eta = std::min(law.frictionDampingLimit,
                                law.friction * pressing / std::max(slip.norm(), law.frictionVelocity));
    spring.force -= eta * slip;
    spring.damping += eta * tangentPlane;
  }
  return spring;
}

ContactSpring sampleSpring(const ContactLaw& law, double distance, const Vec3& normal, const Vec3& ropeVelocity,
                           const Vec3& bodyVelocity, double h, const SampleFriction& friction) {
  ContactLaw normalLaw = law;
  normalLaw.friction = 0.0;
  ContactSpring spring = contactSpring(normalLaw, distance, normal, ropeVelocity, bodyVelocity, h);
  if (!(law.friction > 0.0)) return spring;
  const Eigen::Matrix3d tangentPlane = Eigen::Matrix3d::Identity() - normal * normal.transpose();
  if (!friction.sliding) {
    // f_t = -k P_t (e + h (u_new - v_b)), in addSpring's form. Undamped: backward Euler already
    // damps the spring's stiff oscillation (omega h >> 1), and a damper would turn the jitter of a
    // resting rope into tangential forces above mu f_n (measured: 0.3 mm/s gave 4 mN on 1 mN).
    const double k = law.stiffness;
    spring.force -= k * (friction.displacement - h * (tangentPlane * bodyVelocity));
    spring.stiffness += k * tangentPlane;
    return spring;
  }
  const Vec3& d = friction.direction;
  const double magnitude = law.friction * friction.normalForce;
  spring.force -= magnitude * d;
  const double eta = std::min(law.frictionDampingLimit, magnitude / friction.speed);
  spring.damping += eta * (tangentPlane - d * d.transpose());
  return spring;
}

bool contactActive(double distance, const Vec3& normal, const Vec3& ropeVelocity, const Vec3& bodyVelocity,
                   double h) {
  return distance < 0.0 || distance + h * normal.dot(ropeVelocity - bodyVelocity) < 0.0;
}

Vec3 endOfStepForce(const ContactSpring& spring, const Vec3& u, const Vec3& uNew, double h) {
  return spring.force - h * (spring.stiffness * uNew) - spring.damping * (uNew - u);
}

void capForBody(double inverseMass, double h, double share, double& stiffness, double& damping) {
  if (!(inverseMass > 0.0)) return;
  const double mass = 1.0 / inverseMass;
  stiffness = std::min(stiffness, share * mass / (h * h));
  damping = std::min(damping, share * mass / h);
}

}  // namespace rope::bullet
