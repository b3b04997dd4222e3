// Waiting for the user to stop `rad serve`: Ctrl-C (SIGINT) or SIGTERM.
#pragma once

#include <functional>

namespace rad {

/// Installs SIGINT and SIGTERM handlers, then blocks the calling thread until one arrives or
/// `should_stop` (polled every 100 ms, may be empty) returns true. A second signal while the
/// caller is still shutting down ends the process at once (status 128 + signal). Returns the signal
/// number, or 0 when `should_stop` ended the wait. Call from one thread only.
int wait_for_shutdown(const std::function<bool()>& should_stop = {});

}  // namespace rad
