// SPDX-License-Identifier: MIT
#pragma once
// The error of a scene file that cannot be run: it names the JSON path and the offending value,
// "ropes[1].settings.radius: -0.01, must be > 0". ropesim exits with status 2 on it.

#include <stdexcept>
#include <string>

#include "rope/common/error.h"

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

// The value and the reason of a library error, whose message is "<parameter> = <value>: <reason>"
// (rope/common/error.h), to be told again at the file's JSON path.
struct LibraryErrorParts {
  std::string value, reason;
};
inline LibraryErrorParts splitLibraryError(const InvalidArgument& error) {
  const std::string what = error.what();
  const std::string prefix = error.parameter() + " = ";
  const std::size_t colon = what.find(": ", prefix.size());
  if (what.compare(0, prefix.size(), prefix) != 0 || colon == std::string::npos) return {"", what};
  return {what.substr(prefix.size(), colon - prefix.size()), what.substr(colon + 2)};
}

}  // namespace rope::demos
