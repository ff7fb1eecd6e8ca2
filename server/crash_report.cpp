#include "crash_report.hpp"

#include <execinfo.h>
#include <unistd.h>

#include <csignal>
#include <cstring>

namespace lgh {
namespace {

constexpr int kMaxFrames = 64;
constexpr int kFatalSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
const char* gProgram = "lgh";

// Only async-signal-safe calls from here on: write(2) and backtrace_symbols_fd (backtrace itself
// is safe once libgcc is loaded, which installCrashReport makes sure of).
void writeText(const char* text) {
  const std::size_t length = std::strlen(text);
  const ssize_t written = ::write(STDERR_FILENO, text, length);
  (void)written;
}

void onFatalSignal(int signal) {
  writeText("\n");
  writeText(gProgram);
  writeText(": fatal signal ");
  const char* name = sigabbrev_np(signal);
  writeText(name != nullptr ? name : "?");
  writeText("; stack (addr2line -f -C -e MODULE OFFSET):\n");
  void* frames[kMaxFrames];
  const int count = backtrace(frames, kMaxFrames);
  backtrace_symbols_fd(frames, count, STDERR_FILENO);
  // SA_RESETHAND put the default action back: the process dies of the signal, as before.
  std::raise(signal);
}

}  // namespace

void installCrashReport(const char* program) {
  static bool installed = false;
  if (installed) return;
  installed = true;
  gProgram = program;
  void* warmUp[1];
  backtrace(warmUp, 1);  // loads libgcc's unwinder now, not inside the handler
  struct sigaction action {};
  action.sa_handler = onFatalSignal;
  action.sa_flags = SA_RESETHAND | SA_ONSTACK;
  sigemptyset(&action.sa_mask);
  // The main thread's stack overflowing (deep recursion) still gets its report.
  static char alternateStack[64 * 1024];
  stack_t stack{};
  stack.ss_sp = alternateStack;
  stack.ss_size = sizeof(alternateStack);
  sigaltstack(&stack, nullptr);
  for (const int signal : kFatalSignals) sigaction(signal, &action, nullptr);
}

}  // namespace lgh
