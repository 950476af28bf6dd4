// The text of a field table's numbers (models/core/field_table.h).
#include "models/core/field_table.h"

#include <iomanip>

namespace waam::field_internal {

std::string ShowNumber(double value) {
  std::ostringstream out;
  out << std::setprecision(10) << value;
  return out.str();
}

}  // namespace waam::field_internal
