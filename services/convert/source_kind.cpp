#include "services/convert/source_kind.hpp"

#include "core/error.hpp"

namespace ambid::convert {

bus::SourceKind parse_source_kind(const std::string& text) {
  if (text == "sim") return bus::SourceKind::sim;
  if (text == "replay") return bus::SourceKind::replay;
  if (text == "rig") return bus::SourceKind::rig;
  throw Error("source kind '" + text + "' unknown (known: sim, replay, rig)");
}

std::string_view source_kind_name(bus::SourceKind kind) {
  switch (kind) {
    case bus::SourceKind::replay:
      return "replay";
    case bus::SourceKind::rig:
      return "rig";
    case bus::SourceKind::sim:
      break;
  }
  return "sim";
}

diag::Source to_source(bus::SourceKind kind) {
  switch (kind) {
    case bus::SourceKind::replay:
      return diag::Source::replay;
    case bus::SourceKind::rig:
      return diag::Source::rig;
    case bus::SourceKind::sim:
      break;
  }
  return diag::Source::sim;
}

}  // namespace ambid::convert
