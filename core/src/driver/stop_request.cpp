#include "pbms/driver/stop_request.hpp"

#include <csignal>

namespace pbms {
namespace {

volatile std::sig_atomic_t g_window_open = 0;
volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_stop_signal(int sig) {
  if (g_window_open) {
    g_stop = 1;
    return;
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void install_stop_handlers() {
  std::signal(SIGTERM, on_stop_signal);
  std::signal(SIGUSR1, on_stop_signal);
}

bool stop_requested() {
  return g_stop != 0;
}

StopWindow::StopWindow() {
  g_window_open = 1;
}

StopWindow::~StopWindow() {
  g_window_open = 0;
}

}  // namespace pbms
