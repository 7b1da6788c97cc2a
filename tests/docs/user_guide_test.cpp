// SPDX-License-Identifier: MIT
// docs/user-guide.md against the code it documents: every settings struct a user configures has one
// table in the guide that lists exactly its fields with their true defaults and enforced ranges
// (settings_table_check.h says what is checked), and the guide's ropesim options are exactly
// ropesim's, with its defaults and ranges.
#include <BulletCollision/CollisionShapes/btBoxShape.h>

#include <sstream>

#include "bullet_bridge/attachment.h"
#include "bullet_bridge/kinematic_rope_settings.h"
#include "bullet_bridge/rope_debug_draw.h"
#include "bullet_bridge/rope_settings.h"
#include "demos/ropesim/options.h"
#include "docs/settings_table_check.h"
#include "render/polyline_mesh.h"
#include "render/renderer.h"
#include "render/rope_drawing.h"
#include "render/shape_mesh.h"
#include "render/tube_mesh.h"
#include "render/video_writer.h"
#include "render/world_extraction.h"
#include "rope/rod/rod_settings.h"
#include "rope/spline/arc_length.h"
#include "rope/spline/gauss_legendre.h"
#include "rope/tractrix/tractrix_settings.h"

namespace rope::docs {

const std::vector<GuideTable>& userGuideTables() {
  static const std::vector<GuideTable> tables =
      readGuideTables(SPLINEROPE_SOURCE_DIR "/docs/user-guide.md", "field");
  return tables;
}

Symbols commonSymbols() {
  return {{"pi", 3.14159265358979323846}, {"kMaxDegree", kMaxDegree}, {"kMaxGaussPoints", kMaxGaussPoints}};
}

namespace {

using bullet::AttachmentSettings;
using bullet::BulletRopeSettings;
using bullet::KinematicRopeSettings;
using bullet::RopeDebugColours;
using render::Camera;
using render::ExtractionOptions;
using render::PolylineOptions;
using render::RenderSettings;
using render::RopeStyle;
using render::ShapeMeshOptions;
using render::TubeOptions;
using render::VideoSettings;

// A small valid cubic curve for the validations that need one.
const KnotVector kCurveKnots = KnotVector::clampedUniform(3, 5);
const PointList kCurvePoints{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 1, 1), Vec3(4, 0, 1)};

TEST(UserGuide, EveryTableDocumentsAStructThisTestKnows) {
  const std::vector<std::string> known{
      "rope::RodSettings", "rope::ArcLengthOptions", "rope::bullet::BulletRopeSettings",
      "rope::bullet::AttachmentSettings", "rope::bullet::RopeDebugColours", "rope::TractrixSettings",
      "rope::bullet::KinematicRopeSettings", "rope::render::RenderSettings", "rope::render::Camera",
      "rope::render::RopeStyle", "rope::render::TubeOptions", "rope::render::PolylineOptions",
      "rope::render::ShapeMeshOptions", "rope::render::ExtractionOptions", "rope::render::VideoSettings"};
  ASSERT_FALSE(userGuideTables().empty());
  for (const GuideTable& table : userGuideTables()) {
    EXPECT_NE(std::find(known.begin(), known.end(), table.owner), known.end())
        << "docs/user-guide.md:" << table.line << ": a settings table under a heading naming `" << table.owner
        << "`, which this test does not check";
  }
}

TEST(UserGuide, RodSettings) {
  const Symbols derived{{"kDerived", RodSettings::kDerived}};
  using S = RodSettings;
  checkSettingsTable(StructSpec<S>{
      "rope::RodSettings",
      "settings.",
      {field("restLength", &S::restLength), field("radius", &S::radius),
       field("linearDensity", &S::linearDensity, derived), field("materialDensity", &S::materialDensity),
       field("youngsModulus", &S::youngsModulus), field("bendingStiffness", &S::bendingStiffness, derived),
       field("massDamping", &S::massDamping), field("stiffnessDamping", &S::stiffnessDamping),
       field("materialDamping", &S::materialDamping),
       field("gravity", &S::gravity),
       enumField("timeIntegrator", &S::timeIntegrator,
                 {{TimeIntegrator::kBdf2, "TimeIntegrator::kBdf2"},
                  {TimeIntegrator::kBackwardEuler, "TimeIntegrator::kBackwardEuler"}}),
       field("degree", &S::degree),
       field("initialControlPoints", &S::initialControlPoints),
       enumField("stretchingQuadrature", &S::stretchingQuadrature,
                 {{StretchingQuadrature::kExact, "StretchingQuadrature::kExact"},
                  {StretchingQuadrature::kLockingFree, "StretchingQuadrature::kLockingFree"}}),
       field("adaptive", &S::adaptive), field("minControlPoints", &S::minControlPoints),
       field("maxControlPoints", &S::maxControlPoints), field("insertAngle", &S::insertAngle),
       field("removeAngle", &S::removeAngle), field("removalErrorBound", &S::removalErrorBound),
       field("removalVelocityErrorBound", &S::removalVelocityErrorBound),
       enumField("removalCriterion", &S::removalCriterion,
                 {{RemovalCriterion::kPolygon, "RemovalCriterion::kPolygon"},
                  {RemovalCriterion::kMechanical, "RemovalCriterion::kMechanical"},
                  {RemovalCriterion::kMechanicalOutOfContact, "RemovalCriterion::kMechanicalOutOfContact"}}),
       field("removalRelativeError", &S::removalRelativeError),
       field("minKnotSpacing", &S::minKnotSpacing)},
      [](const S& settings) { settings.validate(); }});
}

TEST(UserGuide, ArcLengthOptions) {
  using S = ArcLengthOptions;
  checkSettingsTable(StructSpec<S>{
      "rope::ArcLengthOptions",
      "options.",
      {field("gaussPoints", &S::gaussPoints), field("piecesPerSpan", &S::piecesPerSpan)},
      [](const S& options) {
        arcLength(kCurveKnots, kCurvePoints, kCurveKnots.validBegin(), kCurveKnots.validEnd(), options);
      }});
}

TEST(UserGuide, BulletRopeSettings) {
  using S = BulletRopeSettings;
  checkSettingsTable(StructSpec<S>{
      "rope::bullet::BulletRopeSettings",
      "settings.",
      {field("lineContactStiffness", &S::lineContactStiffness), field("lineContactDamping", &S::lineContactDamping),
       field("lineSpeculativeDamping", &S::lineSpeculativeDamping),
       field("contactQuadraturePoints", &S::contactQuadraturePoints),
       field("concentratedContactRatio", &S::concentratedContactRatio), field("friction", &S::friction),
       field("frictionVelocity", &S::frictionVelocity),
       enumField("gravitySource", &S::gravitySource,
                 {{S::GravitySource::kWorld, "GravitySource::kWorld"}, {S::GravitySource::kRod, "GravitySource::kRod"}}),
       field("gravityScale", &S::gravityScale), field("fluidDensity", &S::fluidDensity),
       field("normalDragCoefficient", &S::normalDragCoefficient),
       field("tangentialDragCoefficient", &S::tangentialDragCoefficient),
       field("windVelocity", &S::windVelocity), field("contactStiffness", &S::contactStiffness),
       field("contactDamping", &S::contactDamping), field("speculativeDamping", &S::speculativeDamping),
       field("capsulesPerSpan", &S::capsulesPerSpan), field("speculativeMargin", &S::speculativeMargin),
       field("initialPredictionTime", &S::initialPredictionTime),
       field("bodyStabilityFactor", &S::bodyStabilityFactor), field("collisionGroup", &S::collisionGroup),
       field("collisionMask", &S::collisionMask), field("selfContact", &S::selfContact),
       field("selfContactExclusion", &S::selfContactExclusion, {{"kDerivedExclusion", S::kDerivedExclusion}})},
      [](const S& settings) { settings.validate(); }});
}

TEST(UserGuide, AttachmentSettings) {
  using S = AttachmentSettings;
  checkSettingsTable(StructSpec<S>{"rope::bullet::AttachmentSettings",
                                   "attachment.",
                                   {field("stiffness", &S::stiffness), field("damping", &S::damping),
                                    field("angularStiffness", &S::angularStiffness),
                                    field("angularDamping", &S::angularDamping)},
                                   [](const S& settings) { settings.validate(); }});
}

TEST(UserGuide, RopeDebugColours) {
  using S = RopeDebugColours;
  checkSettingsTable(StructSpec<S>{"rope::bullet::RopeDebugColours",
                                   "",
                                   {field("curve", &S::curve), field("capsules", &S::capsules),
                                    field("activeContact", &S::activeContact),
                                    field("speculativeContact", &S::speculativeContact)},
                                   {}});
}

TEST(UserGuide, TractrixSettings) {
  using S = TractrixSettings;
  checkSettingsTable(StructSpec<S>{
      "rope::TractrixSettings",
      "settings.",
      {enumField("variant", &S::variant,
                 {{TractrixVariant::kPolyline, "TractrixVariant::kPolyline"},
                  {TractrixVariant::kSplineSubdivide, "TractrixVariant::kSplineSubdivide"},
                  {TractrixVariant::kSplineSubdivideMerge, "TractrixVariant::kSplineSubdivideMerge"}}),
       field("segmentCount", &S::segmentCount), field("degree", &S::degree),
       field("subdivisionAngle", &S::subdivisionAngle), field("mergingAngle", &S::mergingAngle),
       field("minControlPoints", &S::minControlPoints), field("maxControlPoints", &S::maxControlPoints),
       field("guardMerges", &S::guardMerges), field("maxMergeShapeError", &S::maxMergeShapeError),
       enumField("lengthCorrection", &S::lengthCorrection,
                 {{TractrixLengthCorrection::kNone, "TractrixLengthCorrection::kNone"},
                  {TractrixLengthCorrection::kRestoreCurveLength, "TractrixLengthCorrection::kRestoreCurveLength"}}),
       field("lengthGaussPoints", &S::lengthGaussPoints)},
      [](const S& settings) { validateTractrixSettings(settings); }});
}

TEST(UserGuide, KinematicRopeSettings) {
  using S = KinematicRopeSettings;
  checkSettingsTable(StructSpec<S>{
      "rope::bullet::KinematicRopeSettings",
      "settings.",
      {field("radius", &S::radius), field("capsulesPerSpan", &S::capsulesPerSpan),
       field("speculativeMargin", &S::speculativeMargin), field("penetrationRecovery", &S::penetrationRecovery),
       field("friction", &S::friction), field("solverIterations", &S::solverIterations),
       field("collisionGroup", &S::collisionGroup), field("collisionMask", &S::collisionMask)},
      [](const S& settings) { settings.validate(); }});
}

TEST(UserGuide, RenderSettings) {
  using S = RenderSettings;
  checkSettingsTable(StructSpec<S>{
      "rope::render::RenderSettings",
      "settings.",
      {field("width", &S::width), field("height", &S::height), field("postAntiAliasing", &S::postAntiAliasing),
       field("samples", &S::samples), field("shadows", &S::shadows), field("shadowMapSize", &S::shadowMapSize),
       field("lightDirection", &S::lightDirection), field("autoGround", &S::autoGround),
       field("gridSpacing", &S::gridSpacing), field("horizonColour", &S::horizonColour),
       field("zenithColour", &S::zenithColour)},
      [](const S& settings) { settings.validate(); }});
}

TEST(UserGuide, Camera) {
  using S = Camera;
  checkSettingsTable(StructSpec<S>{
      "rope::render::Camera",
      "camera.",
      {field("eye", &S::eye), field("target", &S::target), field("up", &S::up),
       field("verticalFovDegrees", &S::verticalFovDegrees), field("nearPlane", &S::nearPlane),
       field("farPlane", &S::farPlane)},
      [](const S& camera) { camera.validate(); }});
}

TEST(UserGuide, RopeStyle) {
  using S = RopeStyle;
  checkSettingsTable(StructSpec<S>{"rope::render::RopeStyle",
                                   "",
                                   {nestedField("tube", &S::tube), field("showControlPolygon", &S::showControlPolygon),
                                    nestedField("controlPolygon", &S::controlPolygon)},
                                   {}});
}

TEST(UserGuide, TubeOptions) {
  using S = TubeOptions;
  checkSettingsTable(StructSpec<S>{
      "rope::render::TubeOptions",
      "options.",
      {field("radius", &S::radius), field("sides", &S::sides), field("samplesPerSpan", &S::samplesPerSpan),
       field("capEnds", &S::capEnds), field("colour", &S::colour),
       field("alternateSpanColours", &S::alternateSpanColours), field("alternateColour", &S::alternateColour)},
      [](const S& options) { render::buildTubeMesh(kCurveKnots, kCurvePoints, options); }});
}

TEST(UserGuide, PolylineOptions) {
  using S = PolylineOptions;
  checkSettingsTable(StructSpec<S>{"rope::render::PolylineOptions",
                                   "options.",
                                   {field("lineRadius", &S::lineRadius), field("pointRadius", &S::pointRadius),
                                    field("sides", &S::sides), field("colour", &S::colour)},
                                   [](const S& options) { render::buildPolylineMesh(kCurvePoints, options); }});
}

TEST(UserGuide, ShapeMeshOptions) {
  using S = ShapeMeshOptions;
  checkSettingsTable(StructSpec<S>{
      "rope::render::ShapeMeshOptions",
      "options.",
      {field("curveSegments", &S::curveSegments), field("planeHalfExtent", &S::planeHalfExtent)},
      [](const S& options) { render::buildShapeMesh(btBoxShape(btVector3(0.1, 0.2, 0.3)), options); }});
}

TEST(UserGuide, ExtractionOptions) {
  using S = ExtractionOptions;
  checkSettingsTable(StructSpec<S>{
      "rope::render::ExtractionOptions", "", {field("skip", &S::skip), field("colour", &S::colour)}, {}});
}

TEST(UserGuide, VideoSettings) {
  using S = VideoSettings;
  checkSettingsTable(StructSpec<S>{
      "rope::render::VideoSettings",
      "settings.",
      {field("width", &S::width), field("height", &S::height), field("framesPerSecond", &S::framesPerSecond),
       field("crf", &S::crf), field("preset", &S::preset), field("ffmpegExecutable", &S::ffmpegExecutable)},
      // The writer validates its settings before it looks for ffmpeg: with a name that is nowhere on
      // PATH, settings it accepts end in FfmpegNotFound, and nothing is started or written.
      [](const S& settings) {
        S checked = settings;
        checked.ffmpegExecutable = "splinerope-user-guide-test-no-such-ffmpeg";
        render::VideoWriter writer(testing::TempDir() + "user_guide_test.mp4", checked);
      }});
}

// ---- ropesim ----

// The option a row or a usage line documents: "--size WxH" -> "--size".
std::string optionName(const std::string& text) { return text.substr(0, text.find(' ')); }

// How the guide shows each option's default, given the options ropesim parses from the scene alone.
std::string shownDefault(const std::string& option, const demos::RopesimOptions& parsed) {
  const auto optional = [](const std::optional<std::string>& value) { return value ? *value : "none"; };
  const auto flag = [](bool set) { return std::string(set ? "on" : "off"); };
  if (option == "--out") return parsed.video == parsed.scene + ".mp4" ? "<scene>.mp4" : optional(parsed.video);
  if (option == "--frames") return optional(parsed.framesDirectory);
  if (option == "--seconds") return parsed.seconds ? formatValue(*parsed.seconds) : "none";
  if (option == "--fps") return std::to_string(parsed.framesPerSecond);
  if (option == "--size") return std::to_string(parsed.width) + "x" + std::to_string(parsed.height);
  if (option == "--no-render") return flag(!parsed.render);
  if (option == "--stats") return optional(parsed.statsFile);
  if (option == "--quiet") return flag(parsed.quiet);
  if (option == "--help") return flag(parsed.help);
  if (option == "--set") return parsed.overrides.empty() ? "none" : parsed.overrides.front();
  if (option == "--junit") return optional(parsed.junitFile);
  if (option == "--no-checks") return flag(!parsed.checks);
  if (option == "--snapshot-on-failure") return optional(parsed.snapshotDirectory);
  return "(no rule in user_guide_test.cpp for " + option + ")";
}

// Whether ropesim accepts the option with this numeric value (--size gets it as both dimensions).
bool ropesimAccepts(const std::string& option, double value) {
  std::ostringstream text;
  text << value;
  const std::string argument = option == "--size" ? text.str() + "x" + text.str() : text.str();
  try {
    demos::parseRopesimOptions({"hang", option, argument});
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(optionName(error.what()), option) << error.what();
    return false;
  }
  return true;
}

TEST(UserGuide, RopesimOptions) {
  std::vector<GuideTable> tables;
  for (const GuideTable& table : readGuideTables(SPLINEROPE_SOURCE_DIR "/docs/user-guide.md", "option")) {
    if (table.owner == "ropesim") tables.push_back(table);
  }
  ASSERT_EQ(tables.size(), 1u) << "docs/user-guide.md needs one options table under a heading naming `ropesim`";
  std::vector<std::string> documented, usage;
  for (const GuideRow& row : tables.front().rows) documented.push_back(optionName(leadingCode(row.field).value_or("")));
  std::istringstream help(demos::ropesimUsage());
  for (std::string line; std::getline(help, line);) {
    if (line.rfind("  --", 0) == 0) usage.push_back(optionName(line.substr(2)));
  }
  EXPECT_EQ(documented, usage) << "the guide's ropesim options, against ropesim --help";

  const demos::RopesimOptions parsed = demos::parseRopesimOptions({"hang"});
  for (const GuideRow& row : tables.front().rows) {
    const std::string option = optionName(leadingCode(row.field).value_or(""));
    SCOPED_TRACE("docs/user-guide.md:" + std::to_string(row.line) + ": " + option);
    EXPECT_EQ(leadingCode(row.defaultValue).value_or(row.defaultValue), shownDefault(option, parsed));
    const auto rangeCode = leadingCode(row.range);
    if (!rangeCode) continue;
    const Range range = parseRange(*rangeCode, commonSymbols());
    const bool integral = option != "--seconds";
    for (const auto& [bound, direction] : {std::pair{range.lower, -1.0}, std::pair{range.upper, 1.0}}) {
      if (!bound) continue;
      const double step = integral ? (option == "--size" ? 2.0 : 1.0) : 1e-6 * std::max(1.0, bound->value);
      EXPECT_EQ(ropesimAccepts(option, bound->value), bound->inclusive) << "at the bound " << bound->value;
      EXPECT_FALSE(ropesimAccepts(option, bound->value + direction * step)) << "beyond the bound " << bound->value;
      EXPECT_TRUE(ropesimAccepts(option, bound->value - direction * step)) << "inside the bound " << bound->value;
    }
  }
}

}  // namespace
}  // namespace rope::docs
