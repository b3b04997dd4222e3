#include "serve/shutdown.h"

#include <chrono>
#include <thread>

#include "core/interrupt.h"

namespace rad {

int wait_for_shutdown(const std::function<bool()>& should_stop) {
  install_interrupt_handlers();
  while (interrupt_signal() == 0) {
    if (should_stop && should_stop()) return 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return interrupt_signal();
}

}  // namespace rad
