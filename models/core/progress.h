// Progress reporting on stderr for long runs, and cooperative interruption (Ctrl-C).
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>

namespace waam {

// Installs a SIGINT/SIGTERM handler that only sets a flag; long loops call CheckInterrupt(). A second signal of
// the same kind ends the process at once (the default action).
void InstallInterruptHandler();
// True once SIGINT/SIGTERM was received.
bool InterruptRequested();
// Throws waam::Interrupted if an interrupt was requested.
void CheckInterrupt();

// Told of progress (e.g. a Python callback): the Progress's label, the units done and the total (0 when not known
// yet). Returns false to stop the run: the Update that called it then throws Interrupted.
using ProgressObserver = std::function<bool(const std::string& label, std::size_t done, std::size_t total)>;

// Sets the observer of the Progress objects this thread constructs from now on (nullptr: none; not owned, it must
// outlive them) and returns the previous one. Updates of one Progress may come from pool threads, one at a time.
const ProgressObserver* SetProgressObserver(const ProgressObserver* observer);

// A one-line progress bar on stderr ("plan  [#####.....]  48/100 layers  1.2 s"), redrawn at most ten times a second.
// Silent when `quiet` is true. Calls CheckInterrupt() on every Update(), and this thread's observer (if any) at most
// every 50 ms and at Finish().
class Progress {
 public:
  Progress(std::string label, std::size_t total, std::string unit, bool quiet);
  ~Progress();
  // Sets the total when it becomes known after construction.
  void SetTotal(std::size_t total) { total_ = total; }
  void Update(std::size_t done);
  void Finish();

 private:
  void Draw(std::size_t done);
  void Notify(std::size_t done);
  const ProgressObserver* observer_;  // this thread's observer when constructed (may be null)
  std::string label_;
  std::size_t total_;
  std::string unit_;
  bool quiet_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::chrono::steady_clock::time_point last_notify_;
};

}  // namespace waam
