#pragma once
// Fast DDS writers and readers of one message type: convert, write / take, and report the
// middleware status through Endpoint. Every writer has its own listener (Fast DDS 2.9.1 crashes
// on an offered deadline miss of a writer without one).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "core/error.hpp"
#include "services/bus/endpoint.hpp"
#include "services/bus/fastdds/convert.hpp"
#include "services/bus/fastdds/participant.hpp"
#include "services/bus/fastdds/qos.hpp"
#include "services/bus/topics.hpp"

namespace ambid::bus::fastdds {

template <class Message>
class FastWriter final : public Writer<Message>, private eprosima::fastdds::dds::DataWriterListener {
 public:
  FastWriter(std::shared_ptr<Participant> participant, std::shared_ptr<Activity> activity)
      : Writer<Message>(Topic<Message>::name, std::move(activity)), participant_(std::move(participant)) {
    writer_ = participant_->publisher()->create_datawriter(participant_->topic<Message>(),
                                                           writer_qos(Topic<Message>::profile), this,
                                                           eprosima::fastdds::dds::StatusMask::all());
    if (writer_ == nullptr) {
      throw Error(std::string("Fast DDS refused to create a writer on ") + Topic<Message>::name);
    }
  }
  ~FastWriter() override { participant_->publisher()->delete_datawriter(writer_); }

 private:
  void write_valid(const Message& message) override {
    typename Generated<Message>::Data data;
    to_fast(message, data);
    if (!writer_->write(&data)) {
      throw Error(std::string("Fast DDS failed to write on ") + Topic<Message>::name);
    }
  }

  void on_publication_matched(eprosima::fastdds::dds::DataWriter*,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& s) override {
    this->matched_changed(s.current_count, s.current_count_change);
  }
  void on_offered_deadline_missed(eprosima::fastdds::dds::DataWriter*,
                                  const eprosima::fastdds::dds::OfferedDeadlineMissedStatus& s) override {
    this->deadline_missed(s.total_count);
  }
  void on_liveliness_lost(eprosima::fastdds::dds::DataWriter*,
                          const eprosima::fastdds::dds::LivelinessLostStatus& s) override {
    this->liveliness_lost(s.total_count);
  }

  std::shared_ptr<Participant> participant_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

template <class Message>
class FastReader final : public Reader<Message>, private eprosima::fastdds::dds::DataReaderListener {
 public:
  FastReader(std::shared_ptr<Participant> participant, std::shared_ptr<Activity> activity)
      : Reader<Message>(Topic<Message>::name, std::move(activity)), participant_(std::move(participant)) {
    reader_ = participant_->subscriber()->create_datareader(participant_->topic<Message>(),
                                                            reader_qos(Topic<Message>::profile), this,
                                                            eprosima::fastdds::dds::StatusMask::all());
    if (reader_ == nullptr) {
      throw Error(std::string("Fast DDS refused to create a reader on ") + Topic<Message>::name);
    }
  }
  ~FastReader() override { participant_->subscriber()->delete_datareader(reader_); }

  std::vector<Message> take() override {
    std::vector<Message> out;
    typename Generated<Message>::Data data;
    eprosima::fastdds::dds::SampleInfo info;
    while (reader_->take_next_sample(&data, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) out.push_back(from_fast(data));
    }
    return out;
  }

 private:
  void on_data_available(eprosima::fastdds::dds::DataReader*) override { this->data_available(); }
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& s) override {
    this->matched_changed(s.current_count, s.current_count_change);
  }
  void on_requested_deadline_missed(eprosima::fastdds::dds::DataReader*,
                                    const eprosima::fastdds::dds::RequestedDeadlineMissedStatus& s) override {
    this->deadline_missed(s.total_count);
  }
  void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                             const eprosima::fastdds::dds::LivelinessChangedStatus& s) override {
    this->liveliness_changed(s.alive_count, s.alive_count_change, s.not_alive_count_change);
  }

  std::shared_ptr<Participant> participant_;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};

}  // namespace ambid::bus::fastdds
