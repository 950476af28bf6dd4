// The solver's choices (SolverChoices): recorded as a run makes them, or followed from a record so that a second run
// makes the same ones (docs/THERMAL.md, "Differencing a run").
#include "models/core/error.h"
#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

int NextFollowed(ThermalState& s) {
  const std::vector<int>& values = s.followed->values;
  WAAM_THROW_UNLESS(s.followed_at < values.size(),
                    "solver choices: the record ran out after " << values.size() << " values (the run followed it "
                    "further than the recorded run went)");
  return values[s.followed_at++];
}

}  // namespace

int ChooseCount(ThermalState& s, int value) {
  switch (s.choice_mode) {
    case ThermalState::ChoiceMode::kFree:
      return value;
    case ThermalState::ChoiceMode::kRecord:
      s.recorded.values.push_back(value);
      return value;
    case ThermalState::ChoiceMode::kFollow:
      return NextFollowed(s);
  }
  return value;
}

void ChooseList(ThermalState& s, std::vector<int>& list, std::size_t limit) {
  if (s.choice_mode == ThermalState::ChoiceMode::kFree) return;
  if (s.choice_mode == ThermalState::ChoiceMode::kRecord) {
    s.recorded.values.push_back(static_cast<int>(list.size()));
    s.recorded.values.insert(s.recorded.values.end(), list.begin(), list.end());
    return;
  }
  const int size = NextFollowed(s);
  WAAM_THROW_UNLESS(size >= 0, "solver choices: a list of " << size << " values at " << s.followed_at - 1
                                                            << " (the record does not fit this run)");
  list.resize(static_cast<std::size_t>(size));
  for (int& v : list) {
    v = NextFollowed(s);
    WAAM_THROW_UNLESS(v >= 0 && static_cast<std::size_t>(v) < limit,
                      "solver choices: index " << v << " of " << limit << " at " << s.followed_at - 1
                                               << " (the record does not fit this run)");
  }
}

}  // namespace waam::twin::internal
