// CSV records of other tools: a header line of column names, then rows of cells; only the
// columns a mapping names must hold numbers.
#include <cmath>
#include <map>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/experiment_file.hpp"
#include "core/format/csv_lines.hpp"
#include "core/format/experiment_text.hpp"
#include "core/format/recorded_columns.hpp"

namespace ambid {
namespace {

class CsvColumns : public RecordedColumns {
 public:
  explicit CsvColumns(std::string text) : text_(std::move(text)) {
    std::string_view view = text_;
    if (view.substr(0, 3) == "\xEF\xBB\xBF") view.remove_prefix(3);  // UTF-8 byte order mark
    Lines lines(view);
    const auto header = lines.next();
    if (!header || is_blank(*header)) throw Error("line 1: expected a header line of column names, got an empty line");
    split_cells(*header, header_);
    for (std::size_t c = 0; c < header_.size(); ++c)
      if (!index_.emplace(header_[c], c).second)
        throw Error("line 1: column '" + std::string(header_[c]) + "' appears twice");
    std::vector<std::string_view> row;
    while (const auto line = lines.next()) {
      if (is_blank(*line)) {
        if (lines.rest_is_blank()) break;
        throw Error("line " + std::to_string(lines.number()) + " is empty");
      }
      split_cells(*line, row);
      if (row.size() != header_.size())
        throw Error("line " + std::to_string(lines.number()) + " has " + std::to_string(row.size()) +
                    " cells, the header has " + std::to_string(header_.size()));
      cells_.insert(cells_.end(), row.begin(), row.end());
      line_of_row_.push_back(lines.number());
    }
    if (line_of_row_.size() < 2)
      throw Error("has " + std::to_string(line_of_row_.size()) + " data rows; at least 2 are needed");
  }

  Eigen::VectorXd column(const std::string& source) const override {
    const auto it = index_.find(source);
    if (it == index_.end()) {
      std::string names;
      for (const auto& h : header_) names += (names.empty() ? "'" : ", '") + std::string(h) + "'";
      throw Error("no column '" + source + "' (the header has " + names + ")");
    }
    const std::size_t stride = header_.size();
    Eigen::VectorXd values(static_cast<Eigen::Index>(line_of_row_.size()));
    for (std::size_t k = 0; k < line_of_row_.size(); ++k) {
      const std::string_view cell = cells_[k * stride + it->second];
      const std::optional<double> v = parse_number(cell);
      if (!v || !std::isfinite(*v))
        throw Error("line " + std::to_string(line_of_row_[k]) + ", column '" + source +
                    "': expected a finite number, got " +
                    (cell.empty() ? std::string("an empty cell") : quote_excerpt(cell)));
      values(Eigen::Index(k)) = *v;
    }
    return values;
  }

  std::string kind() const override { return "CSV"; }

 private:
  std::string text_;  // the cells below point into it
  std::vector<std::string_view> header_, cells_;
  std::map<std::string_view, std::size_t> index_;
  std::vector<std::size_t> line_of_row_;
};

}  // namespace

std::unique_ptr<RecordedColumns> open_csv_columns(const std::filesystem::path& file) {
  return std::make_unique<CsvColumns>(read_text_file(file));
}

}  // namespace ambid
