#pragma once
// Detects a plant id served twice: an identifier also reads the IdentifiedModel topic and
// sees its own models come back (local delivery) exactly once each. A model for one of its
// plants that it did not write, or a second copy of one it wrote (another identifier cutting
// the same windows the same way), comes from another identifier serving the same plant id.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <utility>

#include "services/bus/messages.hpp"

namespace ambid::daemons {

class ForeignModels {
 public:
  // `remembered`: own models kept per plant to recognise their echoes (a few seconds' worth).
  explicit ForeignModels(std::size_t remembered = 256) : remembered_(remembered) {}

  void published(const bus::IdentifiedModel& model);
  // True when `model` (of a plant this daemon serves) was written by another identifier.
  bool foreign(const bus::IdentifiedModel& model);

 private:
  struct Own {
    std::uint64_t seq;
    double time;
    bool echoed = false;
  };
  std::size_t remembered_;
  std::map<std::string, std::deque<Own>> own_;  // by plant id, newest last
};

}  // namespace ambid::daemons
