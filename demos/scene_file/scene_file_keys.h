// SPDX-License-Identifier: MIT
#pragma once
// Every key a scene file may use, per kind of JSON object. The reader rejects any other key (with the
// nearest valid one suggested), and the tests compare these lists with docs/scene-files.md and
// docs/scene-file.schema.json, so the reader, the docs and the schema cannot drift apart.

#include <string>
#include <vector>

namespace rope::demos {

struct SceneFileKeyTable {
  std::string object;             // "scene", "body", "rope.settings", ... (a docs section and a schema definition)
  std::vector<std::string> keys;  // in the order the docs list them
};

const std::vector<SceneFileKeyTable>& sceneFileKeyTables();
// The table of `object`; throws std::logic_error for an unknown one (a bug, not a file error).
const SceneFileKeyTable& sceneFileKeys(const std::string& object);

// The key of `candidates` nearest to `key` by edit distance (case-insensitive), or "" if none is
// within a third of the longer length (a misspelling, not another word).
std::string nearestKey(const std::string& key, const std::vector<std::string>& candidates);

}  // namespace rope::demos
