#pragma once
// Line and cell splitting of CSV text, shared by the experiment reader and `ambid import`.
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

namespace ambid {

bool is_blank(std::string_view text);

// Lines without their '\n' or "\r\n", numbered from 1.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  std::optional<std::string_view> next();
  std::size_t number() const { return number_; }
  bool rest_is_blank() const { return pos_ >= text_.size() || is_blank(text_.substr(pos_)); }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

// Cells of one line split at commas, with spaces and tabs around each cell removed.
void split_cells(std::string_view line, std::vector<std::string_view>& cells);

}  // namespace ambid
