// SPDX-License-Identifier: MIT
#pragma once
// The error of a scene file that cannot be run: it names the JSON path and the offending value,
// "ropes[1].settings.radius: -0.01, must be > 0". ropesim exits with status 2 on it.

#include <stdexcept>
#include <string>

namespace rope::demos {

class SceneFileError : public std::runtime_error {
 public:
  // path: "ropes[1].settings.radius" ("" for the file as a whole); value: the offending value as the
  // file writes it ("" if there is none, e.g. a missing key); reason: what was expected.
  SceneFileError(const std::string& path, const std::string& value, const std::string& reason)
      : std::runtime_error((path.empty() ? std::string("scene file") : path) + ": " +
                           (value.empty() ? reason : value + ", " + reason)),
        path_(path) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace rope::demos
