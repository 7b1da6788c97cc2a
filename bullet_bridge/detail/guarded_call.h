// SPDX-License-Identifier: MIT
#pragma once
// Nothing may leave a Bullet step (rope_warnings.h): code that runs inside stepSimulation calls
// rope code and user callbacks through guardedCall, which turns any exception into a call of
// onFailure(message) (message: what() of a std::exception, or "unknown exception").

#include <exception>

namespace rope::bullet {

template <class Call, class OnFailure>
void guardedCall(Call&& call, OnFailure&& onFailure) {
  try {
    call();
  } catch (const std::exception& error) {
    onFailure(error.what());
  } catch (...) {
    onFailure("unknown exception");
  }
}

}  // namespace rope::bullet
