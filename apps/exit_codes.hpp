// Exit codes (DESIGN.md): 0 success, 2 bad input or usage, 1 internal failure, and 130
// after Ctrl-C. One place turns exceptions into them, for the program and its module.
#pragma once

#include <exception>
#include <iostream>

#include "sensor/input_error.hpp"

namespace lifelong::apps {

/// Runs `command`, printing an error line and returning its exit code when it throws.
/// `interrupted` tells an interruption from other exceptions (it comes from eval, which
/// the thin program does not link).
template <typename F, typename IsInterrupted>
int Guarded(F&& command, IsInterrupted&& interrupted) {
  try {
    return command();
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    if (interrupted(e)) {
      std::cerr << "\ninterrupted: nothing was written; an earlier result is unchanged\n";
      return 130;
    }
    std::cerr << "internal error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace lifelong::apps
