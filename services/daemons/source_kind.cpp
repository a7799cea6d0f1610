#include "services/daemons/source_kind.hpp"

#include "core/error.hpp"

namespace ambid::daemons {

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

}  // namespace ambid::daemons
