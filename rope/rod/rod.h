// SPDX-License-Identifier: MIT
#pragma once
// The dynamic adaptive rod ([A] §3–5; docs/method.md §5–§10): a B-spline curve whose control points are the
// degrees of freedom, with mass and gravity from a continuous linear density, Green–Lagrange
// stretching ([A] eq. 11), a continuous bending energy (bending_energy.h), a linearised implicit step
// (BDF2 by default, backward Euler on request: TimeIntegrator in rod_settings.h) solved by a
// block-banded Cholesky in O(n), pins and clamps (pin + tangent direction) by
// Lagrange multipliers, knot insertion and removal after each step, and cutting. Knows nothing of
// Bullet.
//
// Units: metres, seconds, kilograms, newtons. The curve parameter s runs over
// [beginParameter(), endParameter()]; for ropes created from a segment it is the rest arclength.
//
// Step (method §8, eqs. 22a–23): (M + h alpha M + c ((h^2 + h beta) K + h eta K_m)) dv
//     = h (f_ext + M g - alpha M v) + c h (F_int - (h + beta) K v - eta K_m v) + H,   v += dv, q += h v,
// with damping D = alpha M + beta K + eta K_m (massDamping, stiffnessDamping, materialDamping; eq. 20),
// F_int the stretching and bending forces, K their stiffness (stretching with the Gauss–Newton clamp,
// plus the constant bending stiffness), K_m its material part (K without the tension term, so zero on
// rigid motion), pins and clamps imposed on the end-of-step positions. Backward Euler: c = 1, H = 0. BDF2
// (the default): c = 4/9 and H = (6 g_n - g_{n-1}) / 9 from the internal impulses g of the last two
// steps (eq. 22c); loads, springs, gravity and mass damping keep the full weight h in both, so the rod's
// momentum changes by exactly the impulse its loads deliver.
// Then adaptivity ([A] §4): knots at interaction points, insertion where the control polygon bends
// (included angle < insertAngle), removal where it is straight (> removeAngle), the removal error
// is within removalErrorBound and (by default, after a step without contact or attachment springs)
// the coarser spline carries the velocity field and the internal energy (RemovalCriterion,
// docs/method.md §10); a removal from a rope that
// nothing holds or touches keeps its linear momentum exactly.
// Counts stay within [minControlPoints, maxControlPoints].
//
// Failure: bad input throws InvalidArgument and changes nothing. A step whose factorisation fails,
// whose result is not finite, or that makes the rope longer than kMaxStepStretch times its rest
// length (a linearised step far outside its range, e.g. h = 1 s on a hanging rope) reports
// ok == false and leaves the rod exactly as it was (loads queued for that step are dropped). Deterministic: the same calls give bitwise identical results.
//
// Hooks for a physics bridge (all "next step only", cleared by step() whether it succeeds or not):
//   addForce(s, f)    point force f (N) at C(s), explicit.
//   addImpulse(s, J)  impulse J (N s) delivered over the next step (as the force J / h).
//   addSpring(s, f0, K_c, D_c)  an implicit point interaction at C(s): the force on the rope is
//       f(x, u) ~ f0 - K_c (x_new - x) - D_c (u_new - u), x = C(s), u = Cdot(s), with f0 the force at the
//       current state, K_c = -df/dx and D_c = -df/du (3x3, symmetric positive semidefinite for
//       stability). It adds b_i(s) b_j(s) (h^2 K_c + h D_c) to the system and h b_i(s) (f0 - h K_c u)
//       to the right-hand side, exactly like the rod's own stiffness: contact treated implicitly.
//   addTangentSpring(s, f0, K_c, D_c)  the same on the curve's derivative C'(s) instead of C(s): f0 is
//       a generalised force conjugate to C'(s) (N per unit of C'), K_c, D_c its Jacobians in C' and
//       Cdot'; it adds b_i'(s) b_j'(s) (h^2 K_c + h D_c) and h b_i'(s) (f0 - h K_c Cdot'). Net force
//       zero (the b_i' sum to zero), moment C'(s) x f0 on the rope: a rotational spring, e.g. the
//       tangent of a rope clamped to a rigid body (the bridge's clampToBody).
//   addSpringSample(s, f0, K_c, D_c)  the same, for one quadrature sample of a distributed load (a
//       line contact, docs/method.md): it enters the system identically but is not an interaction
//       point, so it does not ask adaptivity for a knot at s.
// Interaction points (pins, clamps, forces, impulses, springs, markInteraction) also get a knot at s
// when adaptive; a clamp also keeps the nearest knot on either side, so that no removal turns its
// tangent.

#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "rope/common/types.h"
#include "rope/rod/banded_matrix.h"
#include "rope/rod/pin_constraints.h"
#include "rope/rod/rod_integrals.h"
#include "rope/rod/rod_settings.h"
#include "rope/spline/knot_removal.h"
#include "rope/spline/knot_vector.h"

namespace rope {

struct StepReport {
  bool ok = true;
  const char* failure = "";   // why the step failed (static text), empty when ok
  int controlPoints = 0;      // after adaptivity
  int insertions = 0;         // knots inserted by adaptivity in this step
  int removals = 0;           // knots removed by adaptivity in this step
  double maxRemovalError = 0.0;          // m, largest curve displacement a removal caused
  double maxRemovalVelocityError = 0.0;  // m/s, same for the velocity field (removal sweep and
                                         // momentum correction)
  // An insertion keeps the curve exactly, unless the new knot's stretching points see a strain the
  // coarser rope held no energy for: then the nearby control points move by the least displacement
  // that gives that energy back (insertion_relaxation.h; docs/method.md §10). m, largest such move.
  double maxInsertionRelaxation = 0.0;
  // J: internal energy an insertion added that its relaxation could not give back (0 in the free
  // ropes of the tests; more than 0 means the total energy grew by this much).
  double unrelaxedInsertionEnergy = 0.0;
  // The knot vector after the step is Rod::knots().
};

struct RemovalReport {
  double positionError = 0.0;  // m, bound on max_s |C_new(s) - C_old(s)|
  double velocityError = 0.0;  // m/s, bound on the change of the velocity field
  double restError = 0.0;      // m, bound on the change of the rest curve
};

class Rod {
 public:
  // How a rest shape is derived from the initial geometry.
  enum class RestShape {
    kScaledToRestLength,  // the initial curve scaled so that its length is settings.restLength
    kAsGiven,             // the initial curve itself: the rope starts unstretched
  };

  // Straight rope from a to b (a != b): settings.initialControlPoints points, clamped uniform knots over
  // [0, settings.restLength] (s = rest arclength); the rest length is settings.restLength, so
  // |b - a| != restLength starts stretched or compressed.
  static Rod fromSegment(const RodSettings& settings, const Vec3& a, const Vec3& b);
  // Rope through the polyline (interpolated by a clamped spline of settings.degree, one control point
  // per polyline point): it can be created bent and slack. Like fromControlPoints, throws
  // InvalidArgument("rest", ...) for a value outside RestShape.
  static Rod fromPolyline(const RodSettings& settings, const PointList& points,
                          RestShape rest = RestShape::kScaledToRestLength);
  // Explicit control points and knots; the rest curve is derived from them ...
  static Rod fromControlPoints(const RodSettings& settings, const KnotVector& knots,
                               const PointList& points, RestShape rest = RestShape::kScaledToRestLength);
  // ... or given explicitly (same knots; settings.restLength is then not used).
  static Rod fromControlPoints(const RodSettings& settings, const KnotVector& knots,
                               const PointList& points, const PointList& restPoints);

  // ---- state access ----
  const RodSettings& settings() const { return settings_; }
  int degree() const { return knots_.degree(); }
  int controlPointCount() const { return static_cast<int>(points_.size()); }
  const KnotVector& knots() const { return knots_; }
  // Cache hints (rope/common/prefetch.h) for the state and scratch a step reads; changes nothing.
  // prefetchState: the state alone, for a rod that will be lent its step scratch (swapStepScratch).
  void prefetch() const;
  void prefetchState() const;
  const PointList& controlPoints() const { return points_; }
  const PointList& velocities() const { return velocities_; }     // control-point velocities, m/s
  const PointList& restControlPoints() const { return rest_; }
  const RodIntegrals& integrals() const { return integrals_; }
  double beginParameter() const { return knots_.validBegin(); }
  double endParameter() const { return knots_.validEnd(); }
  // Throw InvalidArgument("s", ...) outside [beginParameter, endParameter] or NaN.
  Vec3 position(double s) const;
  Vec3 velocity(double s) const;
  // position / velocity at every s[i], into out (resized): the same values, without a span search for
  // sorted parameters. Throw InvalidArgument("s[i]", ...) like position, before writing anything.
  void positionsAt(const std::vector<double>& s, PointList& out) const;
  void velocitiesAt(const std::vector<double>& s, PointList& out) const;
  Vec3 tangent(double s) const;  // unit tangent (zero vector where C'(s) = 0)
  double length() const;         // current arc length, m
  double restLength() const;     // m
  double maxStrain() const;      // largest |C'|/l0' - 1 over the quadrature points
  double strain(double s) const; // |C'(s)|/l0'(s) - 1 (throws InvalidArgument("s", ...) like position)
  // Rest length per unit parameter, dl0/ds = |C0'(s)| (1 for ropes created from a segment, whose
  // parameter is the rest arclength). Throws InvalidArgument("s", ...) like position.
  double restMetric(double s) const;
  double mass() const;           // kg
  Vec3 momentum() const;         // kg m/s
  double kineticEnergy() const;  // J, (1/2) v^T M v
  double stretchingEnergy() const;
  double bendingEnergy() const;
  double gravityEnergy() const;  // -integral of mu g.C l0' ds (zero at the origin)
  double potentialEnergy() const { return stretchingEnergy() + bendingEnergy() + gravityEnergy(); }
  double totalEnergy() const { return kineticEnergy() + potentialEnergy(); }

  // Gravity from the next step on (m/s^2, finite, else InvalidArgument "gravity[i]"): replaces
  // settings().gravity. A rope in a Bullet world follows the world's gravity through this by default
  // (BulletRopeSettings::gravitySource).
  void setGravity(const Vec3& gravity);

  // Replace positions and/or velocities (same count, finite; "points"/"velocities" in errors).
  void setControlPoints(const PointList& points);
  void setVelocities(const PointList& velocities);
  // Forgets the time integrator's history (TimeIntegrator::kBdf2): the next step is a backward-Euler
  // step, after which BDF2 resumes. Replacing the state, changing knots or h, and cutting do it too. A
  // bridge calls it before a step whose loads are not smooth in time (contact comes and goes, sticks
  // and slips): BDF2 extrapolates the last two steps' internal forces, which across an impact
  // overshoots (the pile scene's self-overlap grew 9x), while backward Euler is L-stable and exact in
  // momentum either way. No effect with kBackwardEuler.
  void restartTimeIntegration() { restartHistory(); }

  // ---- pins ----
  // Holds C(s) at target (default: where it is now). Throws InvalidArgument for s outside the valid
  // range or NaN ("s"), a pin already at s or closer to another pin than settings.minKnotSpacing of
  // rest length ("s"), a pin the spline has no freedom left for around s (pin rows dependent,
  // pinRowsIndependent) ("s"), a non-finite target ("target"), or more pins than control points
  // ("pins"): each of those would make every later step fail. Returns the pin's id.
  int pin(double s, const Vec3& target);
  int pin(double s);
  // Target for the end of the next step (moving pins). Throws for an unknown id ("id") or non-finite target.
  void setPinTarget(int id, const Vec3& target);
  void releasePin(int id);  // throws for an unknown id ("id"), or a clamp's id (use releaseClamp)
  // Pins and clamps (Pin::isClamp()), in the order they were made.
  const std::vector<Pin>& pins() const { return pins_; }

  // ---- clamps ----
  // Holds C(s) at target AND the curve's tangent at s along direction (any length > 0; stored as a
  // unit vector): a weld, as for a cantilever's root, a cable leaving a connector or a hose on a
  // nozzle. Exact at the end of every step like a pin (pin_constraints.h explains the two tangent
  // rows P C'(s) = 0, P = I - d d^T). The default form clamps the rope where it is now, along its
  // current tangent. Throws InvalidArgument, changing nothing: "s" outside the valid range, NaN, a
  // pin or clamp already at s, or (default form) a zero tangent C'(s); "target[c]" / "direction[c]"
  // not finite; "direction" of zero length; "clamps" when the rod's constraints would exceed its
  // degrees of freedom (3 per pin, 5 per clamp, at most 3 per control point). Returns the clamp's id
  // (pins and clamps share one id sequence).
  int clamp(double s, const Vec3& target, const Vec3& direction);
  int clamp(double s);
  // Target point and direction for the end of the next step (a moving clamp). Throws for an unknown
  // id or a pin's id ("id"), and like clamp() for the target and direction.
  void setClampTarget(int id, const Vec3& target, const Vec3& direction);
  void releaseClamp(int id);  // throws for an unknown id or a pin's id ("id")

  // ---- point masses ----
  // A lumped mass (kg, finite and > 0, else InvalidArgument "mass") carried at C(s) for the rest of the
  // rod's life: a bob, a hook, a weight tied on. It adds m b_i(s) b_j(s) to the mass matrix and
  // m g b_i(s) to the gravity load (method eq. 11a), counts in mass(), momentum() and the energies, is
  // an interaction point for adaptivity (a knot stays there), and goes with its side when the rod is
  // cut. Throws InvalidArgument("s", ...) like position(), and changes nothing then.
  void addPointMass(double s, double mass);
  const std::vector<std::pair<double, double>>& pointMasses() const { return pointMasses_; }  // (s, kg)

  // ---- loads for the next step (see the header comment) ----
  void addForce(double s, const Vec3& force);
  void addImpulse(double s, const Vec3& impulse);
  void addSpring(double s, const Vec3& force, const Eigen::Matrix3d& stiffness,
                 const Eigen::Matrix3d& damping);
  void addSpringSample(double s, const Vec3& force, const Eigen::Matrix3d& stiffness,
                       const Eigen::Matrix3d& damping);
  void addTangentSpring(double s, const Vec3& force, const Eigen::Matrix3d& stiffness,
                        const Eigen::Matrix3d& damping);
  void clearLoads();

  // A step that makes the rope as a whole longer than this many times its rest length (and longer
  // than before the step) fails instead of being committed: a mean strain of 200 % is far past the
  // breaking strain of real ropes (nylon ~25 %, steel ~2 %) and is the linearised step's
  // extrapolation rather than mechanics (measured: h = 1 s on a rope hanging from one end gave 3.75
  // times the rest length). Not lower: a slack rope without bending stiffness flailing between
  // close pins reaches 2.7 times in one of the adaptivity tests, and a rope pulled round a capstan
  // at 1.1 e^(2 pi) over 2 times.
  static constexpr double kMaxStepStretch = 3.0;

  // One step of h seconds (finite, > 0, else InvalidArgument "h"): solveTrial(h), then commitTrial()
  // if the trial succeeded, else the loads are dropped and the rod is unchanged.
  StepReport step(double h);

  // ---- split step, for solvers that couple several rods (rope/rod/coupled_solve.h) ----
  // solveTrial assembles and factorises the step system with the queued loads, springs and pins and
  // solves for the end-of-step state without changing the rod: positions, velocities and knots stay
  // as they are until commitTrial(). The queued loads stay queued (clearLoads() drops them and the
  // trial). Returns report.ok == false (with report.failure) on numerical failure.
  // Where the trial holds much more stretching energy than the step's quadratic model (docs/method.md
  // §8), the step is solved again with the stretching linearised about it; not while line-contact
  // samples (addSpringSample) are queued, unless relineariseInContact: a bridge's contact active set
  // solves the trial pass by pass, and asks for it once, after its last pass (bullet_bridge/
  // rope_object.cpp, solveTrialWithContacts).
  StepReport solveTrial(double h, bool relineariseInContact = false);
  bool hasTrial() const { return trialValid_; }
  // Whether the trial (false without one, and false if its solveTrial relinearised already) holds
  // enough stretching energy beyond the step's quadratic model that solveTrial(h, true) would solve
  // it again about the trial, contact samples or not.
  bool trialNeedsRelinearisation() const {
    return trialValid_ && !trialRelinearisationTried_ && linearisationExcessive();
  }
  // End-of-step control-point velocities and the velocity field at s of the trial (throws
  // InvalidArgument("trial", ...) without one).
  const PointList& trialVelocities() const;
  Vec3 trialVelocity(double s) const;
  // The change of the trial's control-point velocities (3n doubles, x y z per point) that an extra
  // impulse of 1 N s along axis (0..2) at C(s) would cause, through the same factorised system with
  // the pins still held: the columns of P J^T in coupled_solve.h. O(n) each.
  void trialImpulseResponse(double s, int axis, double* response) const;
  // The same for an impulse of 1 N s along `direction` (any finite vector, its length included): one
  // O(n) solve instead of three.
  void trialImpulseResponse(double s, const Vec3& direction, double* response) const;
  // All three axes at once (responses: 3 columns of 3n doubles, axis 0, 1, 2), bitwise the same as
  // three calls with axis 0, 1, 2, in one pass over the factor (about half the time).
  void trialImpulseResponses(double s, double* responses) const;
  // The same on the rows of the control points from the first one with b_i(s) != 0 on (rows 3 i ..
  // 3n of each column); the rows before them are left unspecified. Enough to read the response at
  // any curve point whose first control point is not before s's (CoupledSolve), for less work.
  void trialImpulseResponsesOnward(double s, double* responses) const;
  // The same for one impulse shared out over several curve points: weights[j] times it at C(s[j]),
  // j < count (e.g. +1 and -1 at a coupling's two points on this rod: one solve where two were, from
  // the first control point of any of them on). With count 1 and weight 1 bitwise the single-point
  // call. Throws InvalidArgument "count" outside [1, kMaxResponsePoints], "s[j]" or "weights[j]".
  static constexpr int kMaxResponsePoints = 8;
  void trialImpulseResponsesOnward(const double* s, const double* weights, int count, double* responses) const;
  // In place: generalised impulses on the control points (3n doubles, N s, x y z per point; e.g. sums
  // of impulses at curve points times their basis values) -> the change of the trial's control-point
  // velocities they would cause, pins held. One O(n) solve for any number of impulses: a matrix-free
  // product for iterative solvers (contact/body_contacts.cpp's sliding bounds). Non-finite entries
  // are refused (InvalidArgument "impulses").
  void trialGeneralizedResponse(double* impulses) const;
  // Adds dv (3n doubles) to the trial velocities (and h dv to its positions): the effect of extra
  // impulses computed with trialImpulseResponse.
  void correctTrial(const double* dv);
  // A knot at s after the coming commit, as for a load (adaptivity's interaction criterion).
  void markInteraction(double s);
  // At the coming commit, adaptivity may move C(s) by at most maxChange (m, finite, >= 0): a knot
  // removal whose shape error near s is larger is not made. For a contact that holds a load by
  // friction, which a sudden move of the curve against its stiff penalty spring would kick loose
  // (docs/method.md §10). Throws InvalidArgument naming s or maxChange.
  void limitShapeChange(double s, double maxChange);
  // The coming step is in contact (the bridge: body contact candidates, or rope-rope contact in the
  // last substep): after it, RemovalCriterion::kMechanicalOutOfContact removes knots by kPolygon.
  void markContact() { contactMarked_ = true; }
  // Makes the trial the rod's state, runs adaptivity and clears the loads. Throws
  // InvalidArgument("trial", ...) without a trial.
  StepReport commitTrial();

  // ---- explicit refinement and cutting ----
  // Exact insertion ([A] §3.1): positions and velocities along the curve do not change. Explicit edits
  // are not bound by min/maxControlPoints (those limit adaptivity). Throws InvalidArgument("s", ...)
  // for s outside the open range, at a knot of multiplicity degree (one more would disconnect the
  // curve: cut() makes two ropes), or (a new knot value) closer than
  // settings.minKnotSpacing of rest length to a neighbouring knot: so short a span makes every
  // later step fail.
  void insertKnot(double s);
  // Removes one occurrence of the knot s ([A] eq. 7), momentum kept as by an adaptive removal
  // (free ropes); returns how much the fields moved.
  RemovalReport removeKnot(double s);
  // Cuts at cutPoint(s) (no pin exactly there): two independent rods that inherit positions,
  // velocities, rest state, pins and queued loads on their side. This rod is unchanged.
  std::pair<Rod, Rod> cut(double s) const;
  // Where cut(s) cuts: s itself, or the knot within settings.minKnotSpacing (rest length) of s if
  // there is one (a cut beside a knot would leave a span too short to step). Throws
  // InvalidArgument("s", ...) for s outside the rope, NaN, or leaving a piece shorter than
  // settings.minKnotSpacing.
  double cutPoint(double s) const;

  // ---- paying out and reeling in (a winch; rod_winch.cpp, docs/method.md §16) ----
  enum class End { kBegin, kEnd };
  // Pays out `length` metres of rest length at one end (length > 0; < 0 reels in): the end parameter
  // moves so that the rest arc length changes by exactly `length`, and the end span's polynomial is
  // re-expressed on the moved end knots (positions, velocities and rest curve alike), so the curve,
  // its velocity field and the rest metric of the remaining rope do not change. A knot enters at the
  // middle of the end span (exact insertion) when the span grows past twice the nominal spacing
  // settings.restLength / (settings.initialControlPoints - degree); the neighbouring knot leaves
  // (Rod::removeKnot) before the end span would become shorter than half the nominal spacing (at least
  // settings.minKnotSpacing; docs/method.md §16). Pins and
  // clamps at the end move with it; other pins, queued loads and the trial keep their parameters (the
  // trial is dropped). Mass changes by linearDensity * length. Throws InvalidArgument("length", ...)
  // and changes nothing for a non-finite length, a rest length that would fall below
  // minimumRestLength(), or reeling in further than reelInLimit(end).
  void payOut(End end, double length);
  // How much rest length (m) can be reeled in at `end`: down to minimumRestLength(), and no closer
  // than settings.minKnotSpacing to a pin, clamp, point mass or queued load that is not at that end.
  // Exactly 0 within rounding (1e-12 of the rest length, what payOut accepts beyond it).
  double reelInLimit(End end) const;
  double minimumRestLength() const { return 2.0 * settings_.minKnotSpacing; }  // m

 private:
  struct PointLoad {
    double parameter;
    Vec3 force;  // N; impulses are stored as J and divided by h in step()
    bool impulse;
  };
  struct Spring {
    double parameter;
    Vec3 force;
    Eigen::Matrix3d stiffness;
    Eigen::Matrix3d damping;
    bool interaction;  // false for a quadrature sample of a distributed load (no knot)
    int derivative;    // 0: acts on C(s); 1: on C'(s) (addTangentSpring)
  };
  void queueSpring(double s, const Vec3& force, const Eigen::Matrix3d& stiffness, const Eigen::Matrix3d& damping,
                   bool interaction, int derivative = 0);


 public:
  // The queued loads as a value, for a bridge that solves one step several times with loads of its
  // own: takeLoads() moves the rod's queue into `queue` (whose old contents are dropped; each keeps
  // its buffers, so a steady state allocates nothing), addLoads() queues them again (they were
  // validated when they were first queued).
  class LoadQueue {
   public:
    bool empty() const { return loads.empty() && springs.empty() && marked.empty(); }

   private:
    friend class Rod;
    std::vector<PointLoad> loads;
    std::vector<Spring> springs;
    std::vector<double> marked;
  };
  void takeLoads(LoadQueue& queue);
  void addLoads(const LoadQueue& queue);

  // The storage a step works in (the system and its factor's band, the force lists, the trial, the
  // queued springs' buffer), which holds nothing from one step to the next: a caller stepping many
  // rods may lend one set to each rod in turn, so that a step writes where the rod before wrote, still
  // in the caches, and not into every rod's own, which a thousand rods push out of them.
  // swapStepScratch exchanges the rod's set with `scratch`; call it with no trial pending (before
  // solveTrial, after commitTrial; else InvalidArgument "trial", nothing changed). Queued springs
  // stay queued on the rod, and the results are bit for bit those of the rod's own storage.
  class StepScratch;
  void swapStepScratch(StepScratch& scratch);

 private:
  Rod(const RodSettings& settings, KnotVector knots, PointList points, PointList velocities,
      PointList rest, int gaussCount);
  static Rod fromCurve(const RodSettings& settings, const KnotVector& knots, const PointList& points,
                       RestShape rest);
  void validateParameter(double s) const;
  // Index of the pin (clamp = false) or clamp with this id; "id" for an unknown id or the other kind.
  int findPin(int id, bool clamp) const;
  int constraintRowCount() const;  // 3 per pin, 5 per clamp
  // Adds a pin (direction zero) or clamp (unit direction) after the checks both share ("s" taken,
  // too many constraint rows); s and target are already validated.
  int addPin(double s, const Vec3& target, const Vec3& direction);
  // Appends the knots next to each clamp, so that adaptivity keeps the tangent there exact.
  void addClampNeighbours(std::vector<double>& interactions) const;
  // rod_edit_checks.cpp
  void requireIndependentPin(double s) const;
  void requireResolvableKnot(double s) const;
  double restDistance(double a, double b) const;  // rest arc length between two parameters, m
  // One linearised step. `about` (end-of-step control points of an earlier pass, or null for the
  // start of the step) is where the stretching force is linearised (rod.cpp: relinearise).
  bool assembleAndSolve(double h, StepReport& report, const PointList* about = nullptr);
  // assembleAndSolve's part that depends on the rod's state alone: step_.system and step_.force from
  // the spans (stretching linearised about `about` or the start, bending, mass, damping, gravity) and
  // the point masses, with the products and blocks the step's bookkeeping reads (step_.internalForce
  // and the rest).
  void assembleState(double h, const PointList* about);
  // trialImpulseResponses (onward: trialImpulseResponsesOnward), for weights[j] at s[j], j < count.
  void impulseResponses(const double* s, const double* weights, int count, double* responses, bool onward) const;
  // The stretching energy the last pass's trial holds beyond the quadratic model it was solved with,
  // J (rod.cpp); and whether it is large enough to solve the step again about the trial.
  double linearisationExcess() const;
  bool needsRelinearisation(bool inContact) const;
  bool linearisationExcessive() const;  // needsRelinearisation's energy test alone
  // Kinetic, stretching, bending and gravitational energy of the trial (newPoints_, newVelocities_), J.
  double trialEnergy() const;
  // The weight c of the internal forces in this step (method eq. 22a): 4/9 for a BDF2 step with
  // history of the same h, 1 for backward Euler and for BDF2's restart step.
  double internalWeight(double h) const;
  // BDF2's history (method eq. 22c): records this step's internal impulse, or forgets it.
  void recordInternalImpulse();
  void restartHistory() { historySteps_ = 0; }
  // Whether `next` (end-of-step control points) breaks kMaxStepStretch (rod.cpp).
  bool overstretchedBy(const PointList& next) const;
  void adapt(StepReport& report);
  // Inserts s exactly ([A] eq. 6). Adaptivity's insertions (report given: counted there) in a rope that
  // was free in the step (freeLastStep_) also give back the stretching energy the new knot reveals
  // (insertion_relaxation.h), which moves the curve a little; an explicit insertKnot, the winch's
  // insertions and insertions in a held or touched rope keep the curve exactly.
  void insertKnotUnchecked(double s, StepReport* report = nullptr);
  // Applies a planned removal to knots, points, velocities, rest state and integrals together, and
  // for a rope without pins and interactions restores the momentum the velocity sweep changed by the
  // least-kinetic-energy correction, a uniform velocity (docs/method.md §10); returns its size, m/s.
  // O(n).
  double applyRemoval(const KnotRemoval& plan);
  // The momentum carried by the spans [first, last] (clamped to the rod), kg m/s.
  Vec3 spanMomentum(int first, int last) const;
  bool isNearInteraction(double s) const;
  // rod_winch.cpp: moves the end by a rest length that keeps it inside the end span (reel-in) or
  // extends the end span (pay-out), no knot change.
  void moveEnd(End end, double length);
  double endSpanRestLength(End end) const;

  RodSettings settings_;
  KnotVector knots_;
  PointList points_;
  PointList velocities_;
  PointList rest_;
  RodIntegrals integrals_;
  std::vector<Pin> pins_;
  int nextPinId_ = 1;
  std::vector<std::pair<double, double>> pointMasses_;  // (s, kg)
  std::vector<PointLoad> loads_;
  std::vector<Spring> springs_;

  // Step scratch (kept to avoid allocation per step).
  ConstrainedSolver solver_;
  std::vector<ConstraintRows> rows_;
  std::vector<ConstraintRows> relaxationRows_;  // insertKnotUnchecked's scratch
  double trialInternalWeight_ = 1.0;
  // BDF2's history (method eq. 22c): the internal impulses g (N s per control point) of the last two
  // steps, how many of them are valid (0 after a restart) and the h they were taken with (s).
  PointList internalImpulse_, previousInternalImpulse_;
  int historySteps_ = 0;
  double historyStep_ = 0.0;
  double stretchingEnergy_ = 0.0;  // J, at the last pass's linearisation point
  // assembleState's system and force from its last run about the start of the step, and every input
  // they were computed from (compared bit for bit): a pass with the same state reuses them.
  struct AssemblyCache {
    // Scratch like the solver: a copy of the rod starts without it (and assembles afresh).
    AssemblyCache() = default;
    AssemblyCache(const AssemblyCache&) {}
    AssemblyCache& operator=(const AssemblyCache&) {
      valid = false;
      return *this;
    }
    AssemblyCache(AssemblyCache&&) = default;
    AssemblyCache& operator=(AssemblyCache&&) = default;
    bool valid = false;
    std::uint64_t integralsRevision = 0;
    double step = 0.0, internalWeight = 0.0, axial = 0.0;
    double massDamping = 0.0, stiffnessDamping = 0.0, materialDamping = 0.0;
    Vec3 gravity = Vec3::Zero();
    std::vector<std::pair<double, double>> pointMasses;
    PointList points, velocities;
    SymmetricBandedMatrix system;
    PointList force;
    bool matches(const Rod& rod, double h, double c) const;
    void store(const Rod& rod, double h, double c);
  };
  // What a step works in and nothing carries to the next step (swapStepScratch lends it).
  struct StepBuffers {
    SymmetricBandedMatrix system;
    std::vector<double> rhs;
    PointList force, stiffnessTimesV, materialTimesV, massTimesV;
    // The internal forces (stretching, bending; N per control point) at the start of the trial,
    // their stiffness blocks and, with materialDamping, material stiffness blocks K_m (lower
    // triangle per span), and the trial's history term (N s): what recordInternalImpulse() needs
    // once the trial's end velocities are final.
    PointList internalForce, historyTerm;
    std::vector<Eigen::Matrix3d> stiffnessBlocks;
    std::vector<Eigen::Matrix3d> materialBlocks;
    PointList newPoints, newVelocities;  // the trial
    PointList relinearisationPoints;
    AssemblyCache assemblyCache;
  };
  StepBuffers step_;
  std::vector<double> bend_;
  std::vector<int> spans_;
  std::vector<double> interactions_;
  // Caps on how far adaptivity may move the curve (limitShapeChange): queued for the coming commit,
  // and the committed step's, by parameter, which adapt() reads.
  struct ShapeLimit {
    double parameter;
    double change;  // m
  };
  std::vector<ShapeLimit> pendingShapeLimits_;
  std::vector<ShapeLimit> shapeLimits_;
  // The largest curve change (m) a removal that changes the curve on (from, to) may make.
  double shapeChangeLimit(double from, double to, double bound) const;
  bool contactMarked_ = false;    // markContact() since the last commit (clearLoads keeps it)
  bool contactLastStep_ = false;  // the last committed step was in contact (kMechanicalOutOfContact)
  bool freeLastStep_ = false;     // it had no contact, and nothing but pins, clamps and point masses
                                  // acted on it (adaptivity's insertions then relax)
  std::vector<double> markedInteractions_;
  bool trialValid_ = false;
  bool trialRelinearisationTried_ = false;  // the last solveTrial solved again about its first trial
  bool relinearisingInContact_ = false;     // the last solveTrial's relineariseInContact
  double trialStep_ = 0.0;
};

class Rod::StepScratch {
  friend class Rod;
  StepBuffers buffers;
  std::vector<Spring> springs;
};

}  // namespace rope
