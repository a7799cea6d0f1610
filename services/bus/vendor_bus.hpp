#pragma once
// The Bus of one vendor: a participant shared by every endpoint, and the writer and reader
// factories of every message type of BusMessages. The backends differ only in their Participant
// and endpoint templates, so both instantiate this.
#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "services/bus/bus.hpp"

namespace ambid::bus {
namespace detail {

template <class Participant, template <class> class VendorWriter, template <class> class VendorReader>
class VendorBase : public Bus {
 protected:
  VendorBase(std::string vendor, int domain, std::string_view profile)
      : Bus(std::move(vendor), domain), participant_(std::make_shared<Participant>(domain, profile)) {}

  template <class M>
  std::unique_ptr<Writer<M>> make_writer() {
    return std::make_unique<VendorWriter<M>>(participant_, activity());
  }
  template <class M>
  std::unique_ptr<Reader<M>> make_reader() {
    return std::make_unique<VendorReader<M>>(participant_, activity());
  }

 private:
  std::shared_ptr<Participant> participant_;
};

// Overrides the factory pair of each message of List, one class per message stacked on Base.
template <class Base, class List>
class VendorFactories;

template <class Base>
class VendorFactories<Base, TypeList<>> : public Base {
 protected:
  using Base::Base;
};

template <class Base, class Message, class... Rest>
class VendorFactories<Base, TypeList<Message, Rest...>> : public VendorFactories<Base, TypeList<Rest...>> {
  using Next = VendorFactories<Base, TypeList<Rest...>>;

 protected:
  using Next::Next;

 private:
  std::unique_ptr<Writer<Message>> create_writer(std::type_identity<Message>) override {
    return this->template make_writer<Message>();
  }
  std::unique_ptr<Reader<Message>> create_reader(std::type_identity<Message>) override {
    return this->template make_reader<Message>();
  }
};

template <class Participant, template <class> class VendorWriter, template <class> class VendorReader>
using VendorBusBase = VendorFactories<VendorBase<Participant, VendorWriter, VendorReader>, BusMessages>;

}  // namespace detail

template <class Participant, template <class> class VendorWriter, template <class> class VendorReader>
class VendorBus final : public detail::VendorBusBase<Participant, VendorWriter, VendorReader> {
 public:
  VendorBus(std::string vendor, int domain, std::string_view profile)
      : detail::VendorBusBase<Participant, VendorWriter, VendorReader>(std::move(vendor), domain, profile) {}
};

}  // namespace ambid::bus
