#pragma once
/// @file
/// Reading and writing the numbers of command-line values ("X,Y",
/// "X,Y,THETA", "RHO,DTHETA") the same way in every command, and the checks
/// of file arguments every command shares.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace talus::experiments {

/// `text` split at commas into exactly `count` finite numbers (spaces around
/// each allowed, a leading '+' too), or nothing.
std::optional<std::vector<double>> parse_numbers(const std::string& text, std::size_t count);

/// InputError when `output` (the value of `option`) exists and is not a
/// regular file (a device, FIFO, socket or folder), or is the same file as one
/// of `inputs` ({option, path}): writing it would destroy that input.
void check_output_is_not_an_input(const std::string& option, const std::string& output,
                                  const std::vector<std::pair<std::string, std::string>>& inputs);

/// `value` with 15 significant digits, for messages that quote an input.
std::string format_number(double value);

}  // namespace talus::experiments
