// Progress reporting on stderr for long runs, and cooperative interruption (Ctrl-C).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace waam {

// Installs a SIGINT/SIGTERM handler that only sets a flag; long loops call CheckInterrupt().
void InstallInterruptHandler();
// True once SIGINT/SIGTERM was received.
bool InterruptRequested();
// Throws waam::Interrupted if an interrupt was requested.
void CheckInterrupt();

// A one-line progress bar on stderr ("plan  [#####.....]  48/100 layers  1.2 s"), redrawn at most ten times a second.
// Silent when `quiet` is true. Calls CheckInterrupt() on every Update().
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
  std::string label_;
  std::size_t total_;
  std::string unit_;
  bool quiet_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace waam
