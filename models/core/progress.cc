// Progress bar on stderr and the SIGINT flag.
#include "models/core/progress.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>

#include "models/core/error.h"

namespace waam {
namespace {
volatile std::sig_atomic_t g_interrupted = 0;
// The first SIGINT/SIGTERM sets the flag that long loops check; it also puts the default action back, so a second
// one ends the process at once, even inside a loop that does not check (signal() is async-signal-safe).
extern "C" void OnSignal(int sig) {
  g_interrupted = 1;
  std::signal(sig, SIG_DFL);
}
thread_local const ProgressObserver* t_observer = nullptr;
}  // namespace

const ProgressObserver* SetProgressObserver(const ProgressObserver* observer) {
  const ProgressObserver* previous = t_observer;
  t_observer = observer;
  return previous;
}

void InstallInterruptHandler() {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
}

bool InterruptRequested() { return g_interrupted != 0; }

void CheckInterrupt() {
  if (InterruptRequested()) throw Interrupted();
}

Progress::Progress(std::string label, std::size_t total, std::string unit, bool quiet)
    : observer_(t_observer), label_(std::move(label)), total_(total), unit_(std::move(unit)), quiet_(quiet) {
  start_ = std::chrono::steady_clock::now();
  last_draw_ = start_ - std::chrono::seconds(1);
  last_notify_ = last_draw_;
}

void Progress::Notify(std::size_t done) {
  if (observer_ == nullptr) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_notify_ < std::chrono::milliseconds(50) && !finished_) return;
  last_notify_ = now;
  if (!(*observer_)(label_, done, total_)) throw Interrupted();
}

Progress::~Progress() {
  if (!finished_ && !quiet_) std::fputc('\n', stderr);
}

void Progress::Update(std::size_t done) {
  CheckInterrupt();
  Notify(done);
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100) && done < total_) return;
  last_draw_ = now;
  Draw(done);
}

void Progress::Finish() {
  if (finished_) return;
  if (!quiet_) {
    Draw(total_);
    std::fputc('\n', stderr);
  }
  finished_ = true;
  Notify(total_);
}

void Progress::Draw(std::size_t done) {
  constexpr int kWidth = 30;
  const double fraction = total_ == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total_);
  const int filled = static_cast<int>(fraction * kWidth);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
  bar[kWidth] = '\0';
  std::fprintf(stderr, "\r%-10s [%s] %zu/%zu %s  %.1f s", label_.c_str(), bar, done, total_, unit_.c_str(), seconds);
  std::fflush(stderr);
}

}  // namespace waam
