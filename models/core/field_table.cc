// The text of a field table's numbers (models/core/field_table.h).
#include "models/core/field_table.h"

#include <iomanip>

namespace waam::field_internal {

std::string ShowNumber(double value) {
  std::ostringstream out;
  out << std::setprecision(10) << value;
  return out.str();
}

void CheckRange(double min, double max, double step, const std::string& where) {
  WAAM_THROW_UNLESS(min <= max, where << " = [" << ShowNumber(min) << ", " << ShowNumber(max) << ", "
                                      << ShowNumber(step) << "]: min must not exceed max ([min, max, step])");
  WAAM_THROW_UNLESS(step >= 0.0, where << ": step " << ShowNumber(step) << " must not be negative");
  WAAM_THROW_UNLESS(step > 0.0 || min == max,
                    where << ": step 0 with min < max; give a step, or one number for a single value");
}

}  // namespace waam::field_internal
