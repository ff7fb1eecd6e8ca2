#include "crash_report.hpp"

#include <execinfo.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <ctime>

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

void writeBacktrace() {
  void* frames[kMaxFrames];
  const int count = backtrace(frames, kMaxFrames);
  backtrace_symbols_fd(frames, count, STDERR_FILENO);
}

void onFatalSignal(int signal) {
  writeText("\n");
  writeText(gProgram);
  writeText(": fatal signal ");
  const char* name = sigabbrev_np(signal);
  writeText(name != nullptr ? name : "?");
  writeText("; stack (addr2line -f -C -e MODULE OFFSET):\n");
  writeBacktrace();
  // SA_RESETHAND put the default action back: the process dies of the signal, as before.
  std::raise(signal);
}

// ---- SIGQUIT: every thread's stack, then the default action (a hung process says where) ----

std::atomic<int> gStacksPending{0};

void writeNumber(long value) {
  char digits[24];
  int length = 0;
  do {
    digits[length++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value > 0 && length < 23);
  char text[24];
  for (int i = 0; i < length; ++i) text[i] = digits[length - 1 - i];
  text[length] = '\0';
  writeText(text);
}

void writeOwnStack() {
  writeText("thread ");
  writeNumber(static_cast<long>(syscall(SYS_gettid)));
  writeText(":\n");
  writeBacktrace();
}

int stackSignal() { return SIGRTMIN + 4; }

void onStackSignal(int /*signal*/) {
  writeOwnStack();
  gStacksPending.fetch_sub(1);
}

void waitForStack() {
  const timespec step{0, 1000000};  // 1 ms, up to a second per thread
  for (int i = 0; i < 1000 && gStacksPending.load() > 0; ++i) nanosleep(&step, nullptr);
}

struct LinuxDirent {
  unsigned long long inode;
  long long offset;
  unsigned short length;
  unsigned char type;
  char name[1];
};

void onQuit(int signal) {
  writeText("\n");
  writeText(gProgram);
  writeText(": SIGQUIT; the stack of every thread (addr2line -f -C -e MODULE OFFSET):\n");
  const long self = syscall(SYS_gettid);
  const int directory = open("/proc/self/task", O_RDONLY | O_DIRECTORY);
  if (directory >= 0) {
    alignas(8) char buffer[4096];
    long read = 0;
    while ((read = syscall(SYS_getdents64, directory, buffer, sizeof(buffer))) > 0) {
      for (long at = 0; at < read;) {
        const auto* entry = reinterpret_cast<const LinuxDirent*>(buffer + at);
        at += entry->length;
        if (entry->name[0] < '0' || entry->name[0] > '9') continue;
        long tid = 0;
        for (const char* c = entry->name; *c != '\0'; ++c) tid = tid * 10 + (*c - '0');
        if (tid == self) continue;
        gStacksPending.store(1);
        if (syscall(SYS_tgkill, getpid(), tid, stackSignal()) == 0) waitForStack();
      }
    }
    close(directory);
  }
  writeOwnStack();
  std::raise(signal);  // SA_RESETHAND: the default action (core dump where enabled)
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
  action.sa_handler = onQuit;
  sigaction(SIGQUIT, &action, nullptr);
  struct sigaction perThread {};
  perThread.sa_handler = onStackSignal;
  perThread.sa_flags = SA_RESTART;
  sigemptyset(&perThread.sa_mask);
  sigaction(stackSignal(), &perThread, nullptr);
}

}  // namespace lgh
