#pragma once
/// @file
/// Waiting for another process (a supervisor) to let go of its lock file.

#include <chrono>
#include <string>

namespace climbsim::launcher {

/// Waits until no process holds the lock on `lock_path` or `deadline` passes; true if it
/// was released. Wakes on the exit of the pid written in the file (a pidfd), so nothing
/// sleeps for a fixed time; falls back to checking every 10 ms where pidfds are missing.
bool waitForLockRelease(const std::string& lock_path, std::chrono::steady_clock::time_point deadline);

}  // namespace climbsim::launcher
