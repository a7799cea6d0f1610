#include "services/report/format.hpp"

#include <cstdio>

namespace ambid::report {

std::string format_number(double value, int significant) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", significant, value);
  return text;
}

}  // namespace ambid::report
