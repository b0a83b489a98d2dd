// Errors: user mistakes in a scene (exit status 2) and physics failures during a run.
#pragma once
#include <sstream>
#include <stdexcept>
#include <string>

namespace rift {

/// Where something was written in a scene file.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

/// A mistake in the user's input. The message names file:line:column, the key and what is
/// allowed; the command line turns it into exit status 2 before any output is written.
class SceneError : public std::runtime_error {
 public:
  SceneError(SourceLocation where, std::string key, const std::string& what_is_wrong)
      : std::runtime_error(format(where, key, what_is_wrong)),
        where_(std::move(where)),
        key_(std::move(key)) {}
  const SourceLocation& where() const { return where_; }
  const std::string& key() const { return key_; }

 private:
  static std::string format(const SourceLocation& w, const std::string& key, const std::string& msg) {
    std::ostringstream s;  // (not string concatenation: GCC 12 raises a false -Wrestrict on it)
    s << w.file;
    if (w.line > 0) s << ':' << w.line << ':' << w.column;
    s << ": error: ";
    if (!key.empty()) s << '\'' << key << "': ";
    s << msg;
    return s.str();
  }
  SourceLocation where_;
  std::string key_;
};

/// A run that cannot go on: NaN, energy blow-up, time step above the stable limit.
class PhysicsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rift
