#include "services/report/figure.hpp"

#include <utility>

namespace ambid::report {

Series line(std::string label, std::vector<double> x, std::vector<double> y) {
  Series series;
  series.label = std::move(label);
  series.x = std::move(x);
  series.y = std::move(y);
  return series;
}

Series markers(std::string label, std::vector<double> x, std::vector<double> y, Marker marker) {
  Series series = line(std::move(label), std::move(x), std::move(y));
  series.style.line = false;
  series.style.marker = marker;
  return series;
}

}  // namespace ambid::report
