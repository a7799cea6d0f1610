#pragma once
// One Fast DDS DomainParticipant with one Publisher, one Subscriber and the topics created on it
// so far. Endpoints hold it by shared_ptr; the last one out deletes everything.
#include <map>
#include <mutex>
#include <string>
#include <string_view>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "services/bus/fastdds/convert.hpp"
#include "services/bus/topics.hpp"

namespace ambid::bus::fastdds {

class Participant {
 public:
  // profile: loopback_profile (configured here in C++) or a Fast DDS XML file with a
  // participant profile "ambid". Throws Error when Fast DDS refuses.
  Participant(int domain, std::string_view profile);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  eprosima::fastdds::dds::Publisher* publisher() const { return publisher_; }
  eprosima::fastdds::dds::Subscriber* subscriber() const { return subscriber_; }

  // The topic that carries Message; its type is registered and the topic created on first use.
  template <class Message>
  eprosima::fastdds::dds::Topic* topic() {
    return topic(Topic<Message>::name,
                 [] { return eprosima::fastdds::dds::TypeSupport(new typename Generated<Message>::PubSub()); });
  }

 private:
  eprosima::fastdds::dds::Topic* topic(const char* name, eprosima::fastdds::dds::TypeSupport (*make_type)());

  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::mutex mutex_;
  std::map<std::string, eprosima::fastdds::dds::Topic*, std::less<>> topics_;
};

}  // namespace ambid::bus::fastdds
