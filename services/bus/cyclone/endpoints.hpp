#pragma once
// Cyclone DDS writers and readers of one message type: convert, write / take (with loans), and
// report the middleware status through Endpoint from Cyclone's listener callbacks.
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <dds/dds.h>

#include "core/error.hpp"
#include "services/bus/cyclone/convert.hpp"
#include "services/bus/cyclone/participant.hpp"
#include "services/bus/cyclone/qos.hpp"
#include "services/bus/endpoint.hpp"
#include "services/bus/topics.hpp"

namespace ambid::bus::cyclone {

using ListenerPtr = std::unique_ptr<dds_listener_t, decltype(&dds_delete_listener)>;

template <class Message>
class CycloneWriter final : public Writer<Message> {
 public:
  CycloneWriter(std::shared_ptr<Participant> participant, std::shared_ptr<Activity> activity)
      : Writer<Message>(Topic<Message>::name, std::move(activity)), participant_(std::move(participant)) {
    const QosPtr qos = endpoint_qos(Topic<Message>::profile);
    const ListenerPtr listener(dds_create_listener(this), &dds_delete_listener);
    dds_lset_publication_matched(listener.get(), &on_publication_matched);
    dds_lset_offered_deadline_missed(listener.get(), &on_offered_deadline_missed);
    dds_lset_liveliness_lost(listener.get(), &on_liveliness_lost);
    writer_ = dds_create_writer(participant_->handle(), participant_->topic<Message>(), qos.get(), listener.get());
    if (writer_ < 0) {
      throw Error(std::string("Cyclone DDS refused to create a writer on ") + Topic<Message>::name + ": " +
                  dds_strretcode(writer_));
    }
  }
  ~CycloneWriter() override { dds_delete(writer_); }

 private:
  void write_valid(const Message& message) override {
    CSample<Message> sample;
    to_cyclone(message, sample.data);
    if (const dds_return_t rc = dds_write(writer_, &sample.data); rc < 0) {
      throw Error(std::string("Cyclone DDS failed to write on ") + Topic<Message>::name + ": " + dds_strretcode(rc));
    }
  }

  static void on_publication_matched(dds_entity_t, const dds_publication_matched_status_t s, void* self) {
    static_cast<CycloneWriter*>(self)->matched_changed(static_cast<int>(s.current_count), s.current_count_change);
  }
  static void on_offered_deadline_missed(dds_entity_t, const dds_offered_deadline_missed_status_t s, void* self) {
    static_cast<CycloneWriter*>(self)->deadline_missed(static_cast<int>(s.total_count));
  }
  static void on_liveliness_lost(dds_entity_t, const dds_liveliness_lost_status_t s, void* self) {
    static_cast<CycloneWriter*>(self)->liveliness_lost(static_cast<int>(s.total_count));
  }

  std::shared_ptr<Participant> participant_;
  dds_entity_t writer_ = 0;
};

template <class Message>
class CycloneReader final : public Reader<Message> {
 public:
  CycloneReader(std::shared_ptr<Participant> participant, std::shared_ptr<Activity> activity)
      : Reader<Message>(Topic<Message>::name, std::move(activity)), participant_(std::move(participant)) {
    const QosPtr qos = endpoint_qos(Topic<Message>::profile);
    const ListenerPtr listener(dds_create_listener(this), &dds_delete_listener);
    dds_lset_data_available(listener.get(), &on_data_available);
    dds_lset_subscription_matched(listener.get(), &on_subscription_matched);
    dds_lset_requested_deadline_missed(listener.get(), &on_requested_deadline_missed);
    dds_lset_liveliness_changed(listener.get(), &on_liveliness_changed);
    reader_ = dds_create_reader(participant_->handle(), participant_->topic<Message>(), qos.get(), listener.get());
    if (reader_ < 0) {
      throw Error(std::string("Cyclone DDS refused to create a reader on ") + Topic<Message>::name + ": " +
                  dds_strretcode(reader_));
    }
  }
  ~CycloneReader() override { dds_delete(reader_); }

  std::vector<Message> take() override {
    std::vector<Message> out;
    for (;;) {
      Loan loan(reader_);  // buffers[0] null: Cyclone lends its samples
      loan.count = dds_take(reader_, loan.buffers.data(), loan.infos.data(), batch, batch);
      if (loan.count < 0) {
        throw Error(std::string("Cyclone DDS failed to take from ") + Topic<Message>::name + ": " +
                    dds_strretcode(loan.count));
      }
      if (loan.count == 0) break;
      for (dds_return_t i = 0; i < loan.count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (!loan.infos[k].valid_data) continue;
        out.push_back(from_cyclone(*static_cast<const Data*>(loan.buffers[k])));
      }
    }
    return out;
  }

 private:
  using Data = typename Generated<Message>::Data;
  static constexpr std::size_t batch = 16;

  // Samples Cyclone lent to take(); given back when it goes.
  struct Loan {
    explicit Loan(dds_entity_t r) : reader(r) {}
    Loan(const Loan&) = delete;
    Loan& operator=(const Loan&) = delete;
    ~Loan() {
      if (count > 0) dds_return_loan(reader, buffers.data(), count);
    }
    dds_entity_t reader;
    std::array<void*, batch> buffers{};
    std::array<dds_sample_info_t, batch> infos{};
    dds_return_t count = 0;
  };

  static void on_data_available(dds_entity_t, void* self) { static_cast<CycloneReader*>(self)->data_available(); }
  static void on_subscription_matched(dds_entity_t, const dds_subscription_matched_status_t s, void* self) {
    static_cast<CycloneReader*>(self)->matched_changed(static_cast<int>(s.current_count), s.current_count_change);
  }
  static void on_requested_deadline_missed(dds_entity_t, const dds_requested_deadline_missed_status_t s, void* self) {
    static_cast<CycloneReader*>(self)->deadline_missed(static_cast<int>(s.total_count));
  }
  static void on_liveliness_changed(dds_entity_t, const dds_liveliness_changed_status_t s, void* self) {
    static_cast<CycloneReader*>(self)->liveliness_changed(static_cast<int>(s.alive_count), s.alive_count_change,
                                                          s.not_alive_count_change);
  }

  std::shared_ptr<Participant> participant_;
  dds_entity_t reader_ = 0;
};

}  // namespace ambid::bus::cyclone
