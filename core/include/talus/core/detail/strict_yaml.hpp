#pragma once
/// @file
/// Internal to Talus (its layers' configuration readers; yaml-cpp needed to
/// include it). Strict YAML for Talus's configuration files (vehicles, robots): one
// document, no key twice in any mapping. yaml-cpp alone resolves a duplicate
// key silently to its first value and ignores documents after the first, so
// `friction: 0.7 ... friction: 0.1` would run with 0.7.
#include <yaml-cpp/yaml.h>

#include <string>

namespace talus::detail {

/// Parses `text` (from `source`, for messages); InputError for invalid
/// YAML, a second document or a duplicate key, naming the key and its lines.
YAML::Node load_strict_yaml(const std::string& text, const std::string& source);

}  // namespace talus::detail
