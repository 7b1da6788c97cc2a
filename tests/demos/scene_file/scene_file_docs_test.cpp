// SPDX-License-Identifier: MIT
// docs/scene-files.md and docs/scene-file.schema.json against the scene-file reader: the same keys
// for every kind of object (in the docs, in the same order), every RodSettings and
// BulletRopeSettings field a key, and the documented defaults of the rope settings equal to what the
// reader gives when the key is left out.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demos/scene_file/scene_file_keys.h"
#include "demos/scene_file/scene_file_reader.h"
#include "docs/field_count.h"

namespace rope::demos {
namespace {

std::string read(const std::string& file) {
  std::ifstream stream(file);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

struct DocRow {
  std::string key;
  std::string defaultValue;  // the default column's text
};

// "### `object`" (trailing blanks allowed): the object's name, or "" for any other line.
std::string headingName(const std::string& line) {
  const std::string prefix = "### `";
  if (line.compare(0, prefix.size(), prefix) != 0) return "";
  const std::size_t close = line.find('`', prefix.size());
  if (close == std::string::npos || line.find_first_not_of(" \t\r", close + 1) != std::string::npos) return "";
  return line.substr(prefix.size(), close - prefix.size());
}

std::string trimmed(const std::string& text) {
  const std::size_t first = text.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(' ') - first + 1);
}

// "| `key` | unit | default | ...": the key and the default column's text, or false for another line.
// (Plain string scanning: std::regex trips GCC 12's -Wmaybe-uninitialized in the sanitize build.)
bool keyRow(const std::string& line, DocRow& row) {
  const std::string prefix = "| `";
  if (line.compare(0, prefix.size(), prefix) != 0) return false;
  const std::size_t close = line.find('`', prefix.size());
  if (close == std::string::npos || line.compare(close, 3, "` |") != 0) return false;
  const std::size_t unitEnd = line.find('|', close + 3);
  if (unitEnd == std::string::npos) return false;
  const std::size_t defaultEnd = line.find('|', unitEnd + 1);
  if (defaultEnd == std::string::npos) return false;
  row.key = line.substr(prefix.size(), close - prefix.size());
  row.defaultValue = trimmed(line.substr(unitEnd + 1, defaultEnd - unitEnd - 1));
  return true;
}

// The key tables of docs/scene-files.md: "### `object`" headings, then rows "| `key` | unit |
// default | range | meaning |".
std::map<std::string, std::vector<DocRow>> docTables() {
  std::map<std::string, std::vector<DocRow>> tables;
  std::istringstream text(read(SPLINEROPE_SOURCE_DIR "/docs/scene-files.md"));
  std::string object;
  for (std::string line; std::getline(text, line);) {
    const std::string name = headingName(line);
    DocRow row;
    if (!name.empty()) {
      object = name;
      tables[object];
    } else if (!object.empty() && keyRow(line, row)) {
      tables[object].push_back(row);
    }
  }
  return tables;
}

TEST(SceneFileDocs, EveryKeyIsDocumentedInTheReadersOrder) {
  const auto tables = docTables();
  std::set<std::string> objects;
  for (const SceneFileKeyTable& table : sceneFileKeyTables()) {
    objects.insert(table.object);
    ASSERT_EQ(tables.count(table.object), 1u) << "docs/scene-files.md has no section ### `" << table.object << "`";
    std::vector<std::string> documented;
    for (const DocRow& row : tables.at(table.object)) documented.push_back(row.key);
    EXPECT_EQ(documented, table.keys) << "docs/scene-files.md, ### `" << table.object << "`";
  }
  for (const auto& [object, rows] : tables) EXPECT_EQ(objects.count(object), 1u) << "documented, not read: " << object;
}

TEST(SceneFileDocs, SchemaHasExactlyTheReadersKeys) {
  const nlohmann::json schema = nlohmann::json::parse(read(SPLINEROPE_SOURCE_DIR "/docs/scene-file.schema.json"));
  const auto tables = docTables();
  EXPECT_EQ(schema.at("$ref"), "#/$defs/scene");
  for (const SceneFileKeyTable& table : sceneFileKeyTables()) {
    SCOPED_TRACE(table.object);
    ASSERT_TRUE(schema.at("$defs").contains(table.object));
    const nlohmann::json& definition = schema.at("$defs").at(table.object);
    EXPECT_EQ(definition.at("additionalProperties"), false);
    std::set<std::string> properties, keys(table.keys.begin(), table.keys.end());
    for (auto item = definition.at("properties").begin(); item != definition.at("properties").end(); ++item) {
      properties.insert(item.key());
    }
    EXPECT_EQ(properties, keys);
    // The schema's defaults are the docs' (where the docs give one as JSON).
    for (const DocRow& row : tables.at(table.object)) {
      const nlohmann::json& property = definition.at("properties").at(row.key);
      if (row.defaultValue.size() > 2 && row.defaultValue.front() == '`' && row.defaultValue.back() == '`') {
        const auto value = nlohmann::json::parse(row.defaultValue.substr(1, row.defaultValue.size() - 2), nullptr, false);
        if (!value.is_discarded()) {
          EXPECT_EQ(property.at("default"), value) << row.key;
        }
      }
      if (row.defaultValue == "required") {
        const nlohmann::json& required = definition.at("required");
        EXPECT_NE(std::find(required.begin(), required.end(), row.key), required.end()) << row.key;
      }
    }
  }
}

TEST(SceneFileDocs, EverySettingsFieldIsAKey) {
  // One key per field of the two settings structs (a new field must get a key, a row and a default).
  EXPECT_EQ(sceneFileKeys("rope.settings").keys.size(),
            docs::fieldCount<RodSettings>() + docs::fieldCount<bullet::BulletRopeSettings>());
}

bool sameSettings(const RopeDescription& a, const RopeDescription& b) {
  const RodSettings &r = a.rod, &s = b.rod;
  const bullet::BulletRopeSettings &p = a.bridge, &q = b.bridge;
  static_assert(docs::fieldCount<RodSettings>() == 24 && docs::fieldCount<bullet::BulletRopeSettings>() == 24,
                "compare the new field here");
  return r.restLength == s.restLength && r.radius == s.radius && r.linearDensity == s.linearDensity &&
         r.materialDensity == s.materialDensity && r.youngsModulus == s.youngsModulus &&
         r.bendingStiffness == s.bendingStiffness && r.massDamping == s.massDamping &&
         r.stiffnessDamping == s.stiffnessDamping && r.materialDamping == s.materialDamping && r.gravity == s.gravity && r.timeIntegrator == s.timeIntegrator && r.degree == s.degree &&
         r.initialControlPoints == s.initialControlPoints && r.stretchingQuadrature == s.stretchingQuadrature &&
         r.adaptive == s.adaptive && r.minControlPoints == s.minControlPoints && r.maxControlPoints == s.maxControlPoints &&
         r.insertAngle == s.insertAngle && r.removeAngle == s.removeAngle && r.removalErrorBound == s.removalErrorBound &&
         r.removalVelocityErrorBound == s.removalVelocityErrorBound && r.removalCriterion == s.removalCriterion &&
         r.removalRelativeError == s.removalRelativeError && r.minKnotSpacing == s.minKnotSpacing &&
         p.lineContactStiffness == q.lineContactStiffness && p.lineContactDamping == q.lineContactDamping &&
         p.lineSpeculativeDamping == q.lineSpeculativeDamping && p.contactQuadraturePoints == q.contactQuadraturePoints &&
         p.concentratedContactRatio == q.concentratedContactRatio && p.friction == q.friction &&
         p.frictionVelocity == q.frictionVelocity && p.gravitySource == q.gravitySource && p.gravityScale == q.gravityScale &&
         p.fluidDensity == q.fluidDensity && p.normalDragCoefficient == q.normalDragCoefficient &&
         p.tangentialDragCoefficient == q.tangentialDragCoefficient && p.windVelocity == q.windVelocity &&
         p.contactStiffness == q.contactStiffness && p.contactDamping == q.contactDamping &&
         p.speculativeDamping == q.speculativeDamping && p.capsulesPerSpan == q.capsulesPerSpan &&
         p.speculativeMargin == q.speculativeMargin && p.initialPredictionTime == q.initialPredictionTime &&
         p.bodyStabilityFactor == q.bodyStabilityFactor && p.collisionGroup == q.collisionGroup &&
         p.collisionMask == q.collisionMask && p.selfContact == q.selfContact &&
         p.selfContactExclusion == q.selfContactExclusion;
}

RopeDescription ropeWith(const nlohmann::json& settings) {
  const std::string text = R"({"ropes": [{"name": "r", "settings": )" + settings.dump() +
                           R"(, "shape": {"type": "segment", "from": [0, 0, 0], "to": [1, 0, 0]}}]})";
  return readSceneText(text).ropes.at(0);
}

TEST(SceneFileDocs, DocumentedRopeSettingsDefaultsAreTheLibrarys) {
  const RopeDescription defaults = ropeWith(nlohmann::json::object());
  EXPECT_TRUE(sameSettings(defaults, RopeDescription{})) << "an empty settings object is the library's defaults";
  const auto tables = docTables();
  for (const DocRow& row : tables.at("rope.settings")) {
    SCOPED_TRACE(row.key + " = " + row.defaultValue);
    ASSERT_GT(row.defaultValue.size(), 2u);
    const nlohmann::json value = nlohmann::json::parse(row.defaultValue.substr(1, row.defaultValue.size() - 2));
    nlohmann::json settings = nlohmann::json::object();
    settings[row.key] = value;
    EXPECT_TRUE(sameSettings(ropeWith(settings), defaults));
  }
}

TEST(SceneFileDocs, DocumentedSceneDefaultsAreTheReaders) {
  const SceneDescription empty = readSceneText("{}");
  const auto tables = docTables();
  for (const DocRow& row : tables.at("scene")) {
    if (row.key != "gravity" && row.key != "timeStep" && row.key != "duration") continue;
    SCOPED_TRACE(row.key);
    const nlohmann::json value = nlohmann::json::parse(row.defaultValue.substr(1, row.defaultValue.size() - 2));
    const SceneDescription set = readSceneText("{\"" + row.key + "\": " + value.dump() + "}");
    EXPECT_EQ(set.gravity, empty.gravity);
    EXPECT_EQ(set.timeStep, empty.timeStep);
    EXPECT_EQ(set.duration, empty.duration);
  }
}

TEST(SceneFileKeys, NearestKeySuggestsMisspellingsOnly) {
  EXPECT_EQ(nearestKey("youngModulus", sceneFileKeys("rope.settings").keys), "youngsModulus");
  EXPECT_EQ(nearestKey("Radius", sceneFileKeys("rope.settings").keys), "radius");
  EXPECT_EQ(nearestKey("colour", sceneFileKeys("body").keys), "");
}

TEST(SceneFileOverrides, SetReplacesAndAddsKeys) {
  nlohmann::json document = nlohmann::json::parse(
      R"({"ropes": [{"name": "r", "shape": {"type": "segment", "from": [0, 0, 0], "to": [1, 0, 0]}}]})");
  applySceneOverrides(document, {parseSceneOverride("ropes[0].settings.youngsModulus=1e8"),
                                 parseSceneOverride("ropes[0].settings.stretchingQuadrature=exact"),
                                 parseSceneOverride("gravity=[0,-1.62,0]")});
  const SceneDescription scene = readSceneJson(document);
  EXPECT_EQ(scene.ropes.at(0).rod.youngsModulus, 1e8);
  EXPECT_EQ(scene.ropes.at(0).rod.stretchingQuadrature, StretchingQuadrature::kExact);
  EXPECT_EQ(scene.gravity, Vec3(0, -1.62, 0));
  EXPECT_THROW(parseSceneOverride("novalue"), SceneFileError);
  EXPECT_THROW(applySceneOverrides(document, {parseSceneOverride("ropes[1].name=x")}), SceneFileError);
  EXPECT_THROW(applySceneOverrides(document, {parseSceneOverride("gravity.x=1")}), SceneFileError);
}

}  // namespace
}  // namespace rope::demos
