// Progress reporting for long solver calls.
//
// A solver calls the callback with a fraction in [0, 1]; the callback returns false
// to ask the solver to stop, which then throws craterkit::Aborted. An empty callback
// means "no reporting, never abort".
#pragma once

#include "common/Error.h"

#include <functional>

namespace craterkit {

using ProgressCallback = std::function<bool(double fraction)>;

inline void reportProgress(const ProgressCallback& callback, double fraction) {
  if (callback && !callback(fraction))
    throw Aborted();
}

} // namespace craterkit
