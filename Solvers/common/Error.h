// CraterKit solver errors.
//
// Solvers report bad input by throwing InputError with a message that names the
// offending parameter and value; the VTK filters turn it into vtkErrorMacro in one
// place. Aborted is thrown when a progress callback asks the solver to stop.
#pragma once

#include <stdexcept>
#include <string>

namespace craterkit {

class InputError : public std::invalid_argument {
public:
  using std::invalid_argument::invalid_argument;
};

class Aborted : public std::runtime_error {
public:
  Aborted() : std::runtime_error("aborted by the user") {}
};

} // namespace craterkit
