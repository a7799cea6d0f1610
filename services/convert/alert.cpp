#include "services/convert/alert.hpp"

namespace ambid::convert {

bus::Alert to_message(const diag::Alert& a) {
  bus::Alert m;
  m.plant_id = a.plant_id;
  m.fault = a.fault;
  m.channel = a.channel.value_or(0);
  m.time = a.time;
  m.level = static_cast<bus::AlertLevel>(a.level);
  m.parameter = a.parameter;
  m.value = a.value;
  m.baseline = a.baseline.value_or(0.0);
  m.message = a.message.substr(0, bus::limits::text_length);
  return m;
}

std::string_view level_name(bus::AlertLevel level) { return diag::to_string(static_cast<diag::Level>(level)); }

}  // namespace ambid::convert
