#pragma once

#include <sstream>
#include <string>

namespace cover::config {

// A number as an error message shows it: shortest form, "20" not "20.000000".
inline std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace cover::config
