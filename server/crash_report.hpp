// A fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) prints the signal and the stack to
// stderr before the process dies of it as it would have: a crash on a machine without a debugger
// (the lent GPU machines, a customer's node) still says where it happened. The frames print as
// `module(+offset)`: `addr2line -f -C -e MODULE OFFSET` on the same build names the line
// (docs/TROUBLESHOOTING.md). SIGQUIT prints the stack of every thread, then has its default action
// (the process ends, with a core dump where enabled): a hung process says where it hangs.
#pragma once

namespace lgh {

// Installs the handler, once per process; call at the start of main().
void installCrashReport(const char* program);

}  // namespace lgh
