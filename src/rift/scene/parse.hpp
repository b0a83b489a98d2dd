// Reads a scene file (TOML) into a validated Scene. Every mistake throws SceneError naming
// file:line:column, the key and what is allowed. See docs/scenes.md for every key.
#pragma once
#include <string>

#include "rift/scene/scene.hpp"

namespace rift::scene {

Scene parse_file(const std::string& path);
/// Parse from text (the name is used in messages); used by tests.
Scene parse_string(const std::string& text, const std::string& name);

}  // namespace rift::scene
