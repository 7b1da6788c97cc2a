// SPDX-License-Identifier: MIT
#include "render/tube_mesh.h"

#include <cmath>
#include <string>
#include <vector>

#include "rope/common/error.h"
#include "rope/spline/bspline_basis.h"

namespace rope::render {

namespace {

constexpr double kPi = 3.14159265358979323846;

void requireRange(const char* parameter, int value, int minimum, int maximum) {
  if (value < minimum || value > maximum) {
    throw InvalidArgument(parameter, std::to_string(value),
                          "must be within [" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]");
  }
}

struct Sample {
  Vec3 position = Vec3::Zero();
  Vec3 tangent = Vec3::UnitX();  // unit
  Vec3 normal = Vec3::UnitY();   // unit, perpendicular to tangent; transported along the curve
  int span = 0;  // index among the non-empty spans
  bool moving = false;  // false where C'(s) = 0: the tangent is borrowed from a neighbour
};

// Some unit vector perpendicular to t, from the coordinate axis least aligned with it.
Vec3 anyPerpendicular(const Vec3& t) {
  Eigen::Index axis = 0;
  t.cwiseAbs().minCoeff(&axis);
  const Vec3 a = Vec3::Unit(axis);
  return (a - a.dot(t) * t).normalized();
}

// Double-reflection rotation-minimising frame (Wang, Jüttler, Zheng & Liu 2008): reflect the frame
// in the bisector plane of the chord, then in the plane that maps the reflected tangent onto the
// new tangent. Second-order accurate, exact for circular arcs.
Vec3 transport(const Vec3& normal, const Vec3& x0, const Vec3& t0, const Vec3& x1, const Vec3& t1) {
  Vec3 r = normal, t = t0;
  const Vec3 v1 = x1 - x0;
  const double c1 = v1.squaredNorm();
  if (c1 > 1e-30) {
    r -= (2.0 / c1) * v1.dot(r) * v1;
    t -= (2.0 / c1) * v1.dot(t) * v1;
  }
  const Vec3 v2 = t1 - t;
  const double c2 = v2.squaredNorm();
  if (c2 > 1e-30) r -= (2.0 / c2) * v2.dot(r) * v2;
  // Re-orthogonalise against round-off; fall back if the frame collapsed (a cusp).
  r -= r.dot(t1) * t1;
  const double length = r.norm();
  return length > 1e-9 ? Vec3(r / length) : anyPerpendicular(t1);
}

}  // namespace

int nonEmptySpanCount(const KnotVector& knots) {
  int count = 0;
  for (int k = knots.degree(); k < knots.controlPointCount(); ++k) {
    if (knots[k] < knots[k + 1]) ++count;
  }
  return count;
}

Mesh buildTubeMesh(const KnotVector& knots, const PointList& points, const TubeOptions& options) {
  requirePositive("options.radius", options.radius);
  requireRange("options.sides", options.sides, 3, 256);
  requireRange("options.samplesPerSpan", options.samplesPerSpan, 1, 1024);
  requireColour("options.colour", options.colour);
  requireColour("options.alternateColour", options.alternateColour);
  if (static_cast<int>(points.size()) != knots.controlPointCount()) {
    throw InvalidArgument("points.size()", std::to_string(points.size()),
                          "must equal knots.controlPointCount() = " + std::to_string(knots.controlPointCount()));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      requireFinite("points[" + std::to_string(i) + "]", points[i][c]);
    }
  }

  // Samples along the whole curve; a span's last sample is the next span's first, so frames are
  // transported once through the shared points.
  const int m = options.samplesPerSpan;
  const int degree = knots.degree();
  std::vector<Sample> samples;
  samples.reserve(static_cast<std::size_t>(nonEmptySpanCount(knots) * m + 1));
  BasisValues basis;
  int spanIndex = 0;
  for (int k = degree; k < knots.controlPointCount(); ++k) {
    const double s0 = knots[k], s1 = knots[k + 1];
    if (!(s0 < s1)) continue;
    for (int j = (samples.empty() ? 0 : 1); j <= m; ++j) {
      const double s = j == m ? s1 : s0 + (s1 - s0) * j / m;
      // The span's polynomial piece is evaluated up to and including s1 (its left limit there).
      evaluateBasis(knots, k, s, 1, basis);
      Vec3 position = Vec3::Zero(), derivative = Vec3::Zero();
      for (int i = 0; i <= degree; ++i) {
        const Vec3& q = points[static_cast<std::size_t>(basis.firstIndex() + i)];
        position += basis.d[0][static_cast<std::size_t>(i)] * q;
        derivative += basis.d[1][static_cast<std::size_t>(i)] * q;
      }
      Sample sample;
      sample.position = position;
      sample.span = spanIndex;
      const double speed = derivative.norm();
      sample.moving = speed > 1e-12;
      if (sample.moving) {
        sample.tangent = derivative / speed;
      } else if (!samples.empty()) {
        sample.tangent = samples.back().tangent;  // momentary stop: keep the direction
      } else {
        sample.tangent = Vec3::UnitX();  // replaced below once a direction is known
      }
      samples.push_back(sample);
    }
    ++spanIndex;
  }
  // A curve that starts with zero speed takes its first real direction.
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i].moving) {
      for (std::size_t j = 0; j < i; ++j) samples[j].tangent = samples[i].tangent;
      break;
    }
  }
  if (samples.empty()) return Mesh{};
  samples[0].normal = anyPerpendicular(samples[0].tangent);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const Sample& p = samples[i - 1];
    samples[i].normal = transport(p.normal, p.position, p.tangent, samples[i].position, samples[i].tangent);
  }

  const int sides = options.sides;
  const int spans = spanIndex;
  Mesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(spans * (m + 1) * sides + 2 * (sides + 1)));
  mesh.indices.reserve(static_cast<std::size_t>(spans * m * sides * 6 + 6 * sides));
  std::vector<double> cosines(static_cast<std::size_t>(sides)), sines(static_cast<std::size_t>(sides));
  for (int j = 0; j < sides; ++j) {
    cosines[static_cast<std::size_t>(j)] = std::cos(2.0 * kPi * j / sides);
    sines[static_cast<std::size_t>(j)] = std::sin(2.0 * kPi * j / sides);
  }
  auto spanColour = [&](int span) {
    return options.alternateSpanColours && span % 2 == 1 ? options.alternateColour : options.colour;
  };
  auto addRing = [&](const Sample& sample, const Rgb& colour) {
    const Vec3 binormal = sample.tangent.cross(sample.normal);
    for (int j = 0; j < sides; ++j) {
      const Vec3 n = cosines[static_cast<std::size_t>(j)] * sample.normal +
                     sines[static_cast<std::size_t>(j)] * binormal;
      mesh.addVertex(sample.position + options.radius * n, n, colour);
    }
  };
  for (int span = 0; span < spans; ++span) {
    const Rgb colour = spanColour(span);
    const auto firstRing = static_cast<std::uint32_t>(mesh.vertices.size());
    for (int j = 0; j <= m; ++j) addRing(samples[static_cast<std::size_t>(span * m + j)], colour);
    for (int j = 0; j < m; ++j) {
      const std::uint32_t a = firstRing + static_cast<std::uint32_t>(j * sides);
      const std::uint32_t b = a + static_cast<std::uint32_t>(sides);
      for (int q = 0; q < sides; ++q) {
        const auto q1 = static_cast<std::uint32_t>((q + 1) % sides);
        const auto q0 = static_cast<std::uint32_t>(q);
        // Ring angle runs counter-clockwise about the tangent, so this order faces outward.
        mesh.addTriangle(a + q0, a + q1, b + q0);
        mesh.addTriangle(a + q1, b + q1, b + q0);
      }
    }
  }
  if (options.capEnds) {
    auto addCap = [&](const Sample& sample, bool atEnd, const Rgb& colour) {
      const Vec3 normal = atEnd ? sample.tangent : Vec3(-sample.tangent);
      const Vec3 binormal = sample.tangent.cross(sample.normal);
      const std::uint32_t center = mesh.addVertex(sample.position, normal, colour);
      for (int j = 0; j < sides; ++j) {
        const Vec3 n = cosines[static_cast<std::size_t>(j)] * sample.normal +
                       sines[static_cast<std::size_t>(j)] * binormal;
        mesh.addVertex(sample.position + options.radius * n, normal, colour);
      }
      for (int j = 0; j < sides; ++j) {
        const std::uint32_t p = center + 1 + static_cast<std::uint32_t>(j);
        const std::uint32_t q = center + 1 + static_cast<std::uint32_t>((j + 1) % sides);
        if (atEnd) {
          mesh.addTriangle(center, p, q);
        } else {
          mesh.addTriangle(center, q, p);
        }
      }
    };
    addCap(samples.front(), false, spanColour(0));
    addCap(samples.back(), true, spanColour(spans - 1));
  }
  return mesh;
}

}  // namespace rope::render
