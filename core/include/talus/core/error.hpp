#pragma once
/// @file
/// Talus's one exception hierarchy. Contract violations and bad input throw;
/// expected outcomes of an algorithm (infeasible, no path, iteration limit) are
/// status values in that algorithm's result struct instead.
#include <stdexcept>
#include <string>

namespace talus {

/// Base of every exception Talus throws; `what()` is a message a user can act on.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input: a malformed file, a NaN, a point off the map, an invalid option.
class InputError : public Error {
 public:
  using Error::Error;
};

/// A request that is well formed but physically impossible (e.g. a vehicle
/// that cannot stand on the terrain at all).
class InfeasibleError : public Error {
 public:
  using Error::Error;
};

/// A numerical solver (factorisation, NLP, ODE) failed; the message names the
/// solver and its status.
class SolverError : public Error {
 public:
  using Error::Error;
};

}  // namespace talus
