// The mapping of `ambid import`: which column or variable is t and each signal, in what unit.
#include <array>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_import.hpp"
#include "core/format/experiment_text.hpp"
#include "core/json_text.hpp"

namespace ambid {
namespace {

struct Unit {
  std::string_view name;
  double factor;  // to the SI unit
  std::string_view si;
};

// The one list of units a mapping may name; "u" stands in for the micro sign.
constexpr std::array kUnits{Unit{"m", 1.0, "m"}, Unit{"mm", 1e-3, "m"}, Unit{"um", 1e-6, "m"}, Unit{"µm", 1e-6, "m"},
                            Unit{"A", 1.0, "A"}, Unit{"mA", 1e-3, "A"}, Unit{"uA", 1e-6, "A"}, Unit{"µA", 1e-6, "A"},
                            Unit{"V", 1.0, "V"}, Unit{"mV", 1e-3, "V"}, Unit{"N", 1.0, "N"},   Unit{"rad", 1.0, "rad"},
                            Unit{"s", 1.0, "s"}, Unit{"ms", 1e-3, "s"}, Unit{"us", 1e-6, "s"}, Unit{"µs", 1e-6, "s"}};

const Unit* find_unit(std::string_view name) {
  for (const Unit& u : kUnits)
    if (u.name == name) return &u;
  return nullptr;
}

}  // namespace

std::string import_units() {
  std::string list;
  for (const Unit& u : kUnits)
    list +=
        (list.empty() ? "" : ", ") + std::string(u.name) + " (" + number_text(u.factor) + " " + std::string(u.si) + ")";
  return list;
}

double unit_factor(const std::string& unit) {
  if (unit.empty()) return 1.0;
  const Unit* u = find_unit(unit);
  if (!u) throw Error("unknown unit " + quote_excerpt(unit) + " (known: " + import_units() + ")");
  return u->factor;
}

SignalSource parse_signal_source(const std::string& name, std::string_view spec) {
  const std::string where = "mapping of '" + name + "' " + quote_excerpt(spec) + ": ";
  SignalSource s{name, "", "", 1.0};
  // Scale and unit follow the last ')' so that "A(:,2)" keeps its colon.
  const std::size_t close = spec.rfind(')');
  const std::size_t tail = close == std::string_view::npos ? 0 : close;
  if (const std::size_t star = spec.find('*', tail); star != std::string_view::npos) {
    const auto scale = parse_number(spec.substr(star + 1));
    if (!scale || !std::isfinite(*scale) || *scale == 0.0)
      throw Error(where + "the scale after '*' must be a finite non-zero number, got " +
                  quote_excerpt(spec.substr(star + 1)));
    s.scale = *scale;
    spec = spec.substr(0, star);
  }
  if (const std::size_t colon = spec.find(':', tail); colon != std::string_view::npos) {
    s.unit = std::string(spec.substr(colon + 1));
    spec = spec.substr(0, colon);
    const Unit* unit = find_unit(s.unit);
    if (!unit) throw Error(where + "unknown unit " + quote_excerpt(s.unit) + " (known: " + import_units() + ")");
    if ((unit->si == "s") != (name == "t"))
      throw Error(where + "unit " + quote_excerpt(s.unit) + (name == "t" ? " is no time unit" : " is a time unit"));
  }
  s.source = std::string(spec);
  if (s.source.empty()) throw Error(where + "names no column or variable");
  return s;
}

SignalSource parse_signal_mapping(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw Error("mapping " + quote_excerpt(text) + ": expected NAME=SOURCE[:UNIT][*SCALE], e.g. x=pos:mm");
  return parse_signal_source(std::string(text.substr(0, eq)), text.substr(eq + 1));
}

ImportMapping read_import_mapping(const std::filesystem::path& path) {
  const std::string text = read_json_file(path);
  try {
    const nlohmann::json j = parse_json_text(text);  // bounded: size and depth checked first
    if (!j.is_object()) throw Error("expected a JSON object with keys t, y, u, r, sample_time");
    ImportMapping m;
    for (const auto& [key, value] : j.items()) {
      if (key == "t") {
        if (!value.is_string()) throw Error("key `t` must be a string SOURCE[:UNIT][*SCALE]");
        m.t = parse_signal_source("t", value.get<std::string>());
      } else if (key == "sample_time") {
        if (!value.is_number() || !(value.get<double>() > 0.0))
          throw Error("key `sample_time` must be a positive number of seconds");
        m.sample_time = value.get<double>();
      } else if (key == "y" || key == "u" || key == "r") {
        auto& group = key == "y" ? m.y : key == "u" ? m.u : m.r;
        if (!value.is_array()) throw Error("key `" + key + "` must be an array of \"NAME=SOURCE[:UNIT][*SCALE]\"");
        for (const auto& entry : value) {
          if (!entry.is_string()) throw Error("key `" + key + "` holds " + entry.dump() + ", not a string");
          group.push_back(parse_signal_mapping(entry.get<std::string>()));
        }
      } else {
        throw Error("unknown key `" + key + "` (known: t, y, u, r, sample_time)");
      }
    }
    return m;
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
}

}  // namespace ambid
