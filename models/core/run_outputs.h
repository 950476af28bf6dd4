// The files one command run writes into its output folder, removed together if the run does not complete.
#pragma once

#include <filesystem>
#include <vector>

namespace waam {

// Tracks the outputs of one run of a command (plan, check, simulate). At construction the summary file of an
// earlier run (e.g. out/simulate.json) is removed, so a summary in the folder always belongs to the files next to
// it; the command writes the summary last and then calls Complete(). If the object is destroyed before
// Complete() (Ctrl-C, a bad input found late, a write error), the summary and every file recorded with Add() are
// removed: a run leaves either its complete outputs or none of them, never a truncated set that looks complete.
// Removes the summary of an earlier run (if any) before a long computation whose outputs are written afterwards, so
// an interrupted run does not leave it looking like its own.
void RemoveEarlierSummary(const std::filesystem::path& summary);

class RunOutputs {
 public:
  explicit RunOutputs(std::filesystem::path summary);
  ~RunOutputs();
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  // Records `path` as an output of this run (before it is written) and returns it, so a call reads
  // `WriteX(data, outputs.Add(dir / "x.h5"))`.
  std::filesystem::path Add(std::filesystem::path path);
  // The run finished: its outputs stay.
  void Complete() { complete_ = true; }

 private:
  std::vector<std::filesystem::path> outputs_;
  bool complete_ = false;
};

}  // namespace waam
