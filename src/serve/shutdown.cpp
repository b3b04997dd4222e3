#include "serve/shutdown.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>

namespace rad {
namespace {

std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "used from a signal handler");

extern "C" void on_signal(int sig) {
  if (g_signal.exchange(sig) != 0) _exit(130);  // asked twice: stop now
}

}  // namespace

int wait_for_shutdown(const std::function<bool()>& should_stop) {
  struct sigaction sa = {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  while (g_signal.load() == 0) {
    if (should_stop && should_stop()) return 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return g_signal.load();
}

}  // namespace rad
