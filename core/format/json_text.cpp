#include "core/json_text.hpp"

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/experiment_file.hpp"

namespace ambid {

void check_json_bounds(std::string_view text) {
  if (text.size() > kMaxJsonBytes)
    throw Error("JSON text of " + std::to_string(text.size()) + " bytes exceeds the limit of " +
                std::to_string(kMaxJsonBytes) + " bytes");
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonDepth)
        throw Error("JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                    std::to_string(k) + ")");
    } else if (c == '}' || c == ']') {
      --depth;  // unbalanced brackets are the parser's to report
    }
  }
}

std::string read_json_file(const std::filesystem::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && std::size_t(info.st_size) > kMaxJsonBytes)
    throw Error(path.string() + ": " + std::to_string(info.st_size) + " bytes, more than the " +
                std::to_string(kMaxJsonBytes) + " bytes a JSON file may have");
  return read_text_file(path);
}

nlohmann::json parse_json_text(std::string_view text) {
  check_json_bounds(text);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("malformed JSON: ") + e.what());
  }
}

}  // namespace ambid
