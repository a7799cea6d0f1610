#include "services/convert/frequency_response.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace ambid::convert {
namespace {

bus::IsoZone to_message(ident::IsoZone zone) {
  switch (zone) {
    case ident::IsoZone::A:
      return bus::IsoZone::a;
    case ident::IsoZone::B:
      return bus::IsoZone::b;
    case ident::IsoZone::C:
      return bus::IsoZone::c;
    case ident::IsoZone::D:
      break;
  }
  return bus::IsoZone::d;
}

}  // namespace

bus::FrequencyResponse to_message(const ident::FrfReport& report, const std::string& plant_id, std::uint64_t seq,
                                  double time) {
  const ident::Frf& g = report.plant;
  const std::size_t lines = std::size_t(g.lines()), rows = std::size_t(g.rows()), cols = std::size_t(g.cols());
  if (lines > bus::limits::max_frequencies || lines * rows * cols > bus::limits::max_response_values)
    throw Error("frequency response of " + std::to_string(lines) + " lines x " + std::to_string(rows * cols) +
                " pairs exceeds the message bounds (" + std::to_string(bus::limits::max_frequencies) + " lines, " +
                std::to_string(bus::limits::max_response_values) + " values)");
  bus::FrequencyResponse m;
  m.plant_id = plant_id;
  m.kind = "plant";
  m.seq = seq;
  m.time = time;
  m.outputs = report.output_names;
  m.inputs = report.input_names;
  m.frequencies.assign(g.frequency_hz.data(), g.frequency_hz.data() + lines);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j)
      for (std::size_t k = 0; k < lines; ++k) {
        const std::complex<double> v = g.value[k](Eigen::Index(i), Eigen::Index(j));
        m.re.push_back(v.real());
        m.im.push_back(v.imag());
      }
  for (const ident::SensitivityPeak& p : report.sensitivity_peaks) {
    if (m.peaks.size() == bus::limits::max_peaks) break;
    m.peaks.push_back({p.loop, p.frequency_hz, p.magnitude, to_message(p.zone)});
    m.zone = std::max(m.zone, m.peaks.back().zone);
  }
  return m;
}

}  // namespace ambid::convert
