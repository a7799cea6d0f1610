#pragma once
// Escapes text for XML/HTML content and attribute values (& < > " ').
#include <string>
#include <string_view>

namespace ambid::report {

std::string xml_escape(std::string_view text);

}  // namespace ambid::report
