// Ctrl-C (SIGINT) and SIGTERM as a request to stop cleanly: the first one sets a flag that long
// loops poll between steps (the solver between shots, rad serve's wait), so the run can write
// what it has; a second one ends the process at once.
#pragma once

namespace rad {

/// Installs the SIGINT and SIGTERM handlers (once; later calls do nothing).
void install_interrupt_handlers();

/// The signal that asked to stop (SIGINT or SIGTERM), or 0 while none has.
int interrupt_signal();

/// The conventional exit status of a process stopped by `signal`: 128 + signal (130, 143).
inline int interrupted_exit_status(int signal) { return 128 + signal; }

}  // namespace rad
