#pragma once
// The Bus of one vendor: a participant shared by every endpoint, and one writer and reader
// factory per topic type. The backends differ only in their Participant and endpoint
// templates, so both instantiate this.
#include <memory>
#include <string>
#include <string_view>

#include "services/bus/bus.hpp"

namespace ambid::bus {

template <class Participant, template <class> class VendorWriter, template <class> class VendorReader>
class VendorBus final : public Bus {
 public:
  VendorBus(std::string vendor, int domain, std::string_view profile)
      : Bus(std::move(vendor), domain), participant_(std::make_shared<Participant>(domain, profile)) {}

 private:
  template <class M>
  std::unique_ptr<Writer<M>> make_writer() {
    return std::make_unique<VendorWriter<M>>(participant_, activity());
  }
  template <class M>
  std::unique_ptr<Reader<M>> make_reader() {
    return std::make_unique<VendorReader<M>>(participant_, activity());
  }

  // clang-format off
  std::unique_ptr<Writer<PlantSamples>> create_writer(std::type_identity<PlantSamples>) override { return make_writer<PlantSamples>(); }
  std::unique_ptr<Reader<PlantSamples>> create_reader(std::type_identity<PlantSamples>) override { return make_reader<PlantSamples>(); }
  std::unique_ptr<Writer<ExcitationCommand>> create_writer(std::type_identity<ExcitationCommand>) override { return make_writer<ExcitationCommand>(); }
  std::unique_ptr<Reader<ExcitationCommand>> create_reader(std::type_identity<ExcitationCommand>) override { return make_reader<ExcitationCommand>(); }
  std::unique_ptr<Writer<PlantSourceCommand>> create_writer(std::type_identity<PlantSourceCommand>) override { return make_writer<PlantSourceCommand>(); }
  std::unique_ptr<Reader<PlantSourceCommand>> create_reader(std::type_identity<PlantSourceCommand>) override { return make_reader<PlantSourceCommand>(); }
  std::unique_ptr<Writer<PlantSourceState>> create_writer(std::type_identity<PlantSourceState>) override { return make_writer<PlantSourceState>(); }
  std::unique_ptr<Reader<PlantSourceState>> create_reader(std::type_identity<PlantSourceState>) override { return make_reader<PlantSourceState>(); }
  std::unique_ptr<Writer<IdentifiedModel>> create_writer(std::type_identity<IdentifiedModel>) override { return make_writer<IdentifiedModel>(); }
  std::unique_ptr<Reader<IdentifiedModel>> create_reader(std::type_identity<IdentifiedModel>) override { return make_reader<IdentifiedModel>(); }
  std::unique_ptr<Writer<FrequencyResponse>> create_writer(std::type_identity<FrequencyResponse>) override { return make_writer<FrequencyResponse>(); }
  std::unique_ptr<Reader<FrequencyResponse>> create_reader(std::type_identity<FrequencyResponse>) override { return make_reader<FrequencyResponse>(); }
  std::unique_ptr<Writer<Alert>> create_writer(std::type_identity<Alert>) override { return make_writer<Alert>(); }
  std::unique_ptr<Reader<Alert>> create_reader(std::type_identity<Alert>) override { return make_reader<Alert>(); }
  std::unique_ptr<Writer<Health>> create_writer(std::type_identity<Health>) override { return make_writer<Health>(); }
  std::unique_ptr<Reader<Health>> create_reader(std::type_identity<Health>) override { return make_reader<Health>(); }
  // clang-format on

  std::shared_ptr<Participant> participant_;
};

}  // namespace ambid::bus
