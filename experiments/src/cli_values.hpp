#pragma once
/// @file
/// Reading and writing the numbers of command-line values ("X,Y",
/// "X,Y,THETA", "RHO,DTHETA") the same way in every command.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace talus::experiments {

/// `text` split at commas into exactly `count` finite numbers (spaces around
/// each allowed, a leading '+' too), or nothing.
std::optional<std::vector<double>> parse_numbers(const std::string& text, std::size_t count);

/// `value` with 15 significant digits, for messages that quote an input.
std::string format_number(double value);

}  // namespace talus::experiments
