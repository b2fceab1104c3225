#include "abbe/io/temp_cleanup.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>

namespace abbe::io {
namespace {

constexpr int kSlots = 16;
constexpr std::size_t kPathMax = 4096;
// A slot is written while its flag is 0, then published with flag 1; the
// handler reads only published slots (lock-free atomics: signal-safe).
struct Slot {
  std::atomic<int> used{0};
  char path[kPathMax];
};
Slot g_slots[kSlots];
std::once_flag g_installed;
constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void remove_temp_files(int sig) {
  for (auto& s : g_slots)
    if (s.used.load() == 1) ::unlink(s.path);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install() {
  for (int sig : kSignals) {
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) != 0) continue;
    if (old.sa_handler == SIG_IGN) continue;  // e.g. nohup: keep ignoring
    struct sigaction sa {};
    sa.sa_handler = remove_temp_files;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, nullptr);
  }
}

}  // namespace

int register_temp_file(const char* path) noexcept {
  if (std::strlen(path) >= kPathMax) return -1;
  try {
    std::call_once(g_installed, install);
  } catch (...) {
    return -1;
  }
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_slots[i].used.compare_exchange_strong(expected, 2)) continue;  // 2: being written
    std::strcpy(g_slots[i].path, path);
    g_slots[i].used.store(1);
    return i;
  }
  return -1;
}

void unregister_temp_file(int slot) noexcept {
  if (slot >= 0 && slot < kSlots) g_slots[slot].used.store(0);
}

}  // namespace abbe::io
