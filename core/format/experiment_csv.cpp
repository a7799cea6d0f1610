#include "core/format/experiment_csv.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <new>
#include <optional>

#include "core/error.hpp"
#include "core/format/csv_lines.hpp"
#include "core/format/experiment_text.hpp"
#include "core/format/file_lines.hpp"
#include "core/format/resample.hpp"

namespace ambid {
namespace {

std::string at(std::size_t line) { return "line " + std::to_string(line); }

double parse_cell(std::string_view cell, std::size_t line, const std::string& column) {
  const std::string where = at(line) + ", column '" + column + "': ";
  if (cell.empty()) throw Error(where + "empty cell; expected a finite number");
  const std::optional<double> value = parse_number(cell);
  if (!value)
    throw Error(where + "expected a finite number ('.' decimal point, no thousands separators), got " +
                quote_excerpt(cell));
  if (!std::isfinite(*value)) throw Error(where + "expected a finite number, got " + quote_excerpt(cell));
  return *value;
}

// Column index of every signal, in signal_names() order; warns about columns nobody named.
std::vector<std::size_t> locate_columns(const std::vector<std::string_view>& header, const Experiment& e,
                                        std::vector<std::string>& warnings) {
  if (header.front() != "t")
    throw Error(at(1) + ": the first column must be 't' (time in seconds), got " + quote_excerpt(header.front()));
  std::map<std::string_view, std::size_t> index;
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (header[c].empty()) throw Error(at(1) + ": column " + std::to_string(c + 1) + " has an empty name");
    const auto [it, fresh] = index.emplace(header[c], c);
    if (!fresh)
      throw Error(at(1) + ": column '" + std::string(header[c]) + "' appears twice (columns " +
                  std::to_string(it->second + 1) + " and " + std::to_string(c + 1) + ")");
  }
  std::vector<std::size_t> columns;
  const std::pair<const std::vector<std::string>*, const char*> groups[] = {
      {&e.y_names, "signals.y"}, {&e.u_names, "signals.u"}, {&e.r_names, "signals.r"}};
  for (const auto& [names, key] : groups)
    for (const auto& name : *names) {
      const auto it = index.find(name);
      if (it == index.end())
        throw Error(at(1) + ": column '" + name + "' named in " + key + " is missing from the header");
      columns.push_back(it->second);
      index.erase(it);
    }
  index.erase("t");
  if (!index.empty()) {
    std::vector<std::pair<std::size_t, std::string_view>> ignored;  // in file order
    for (const auto& [name, c] : index) ignored.emplace_back(c, name);
    std::sort(ignored.begin(), ignored.end());
    std::string list;
    for (const auto& [c, name] : ignored) list += (list.empty() ? "'" : ", '") + std::string(name) + "'";
    warnings.push_back("columns " + list + " are not named in the sidecar; ignored");
  }
  return columns;
}

// Linear interpolation onto the sample_time grid, refusing a grid much denser than the rows.
void resample_uniform(Eigen::VectorXd& t, Eigen::MatrixXd& values, double T, std::size_t last_line) {
  const Eigen::Index n = t.size();
  // Interpolation invents the samples between rows; ten per row is no longer jitter but a
  // wrong sample_time or a broken clock (and a bad timestamp would exhaust memory).
  if (std::floor((t(n - 1) - t(0)) / T + 1e-9) + 1 > 10.0 * static_cast<double>(n))
    throw Error("resampling " + std::to_string(n) + " rows spanning t = " + number_text(t(0)) + " to " +
                number_text(t(n - 1)) + " (" + at(last_line) + ") every sample_time " + number_text(T) +
                " s would invent more than 10 samples per row; check sample_time and the t column");
  resample_linear(t, values, T);
}

// The data rows a second pass can expect: the non-blank lines after the header, up to the
// first whose number of cells differs from the header's (the second pass refuses it there).
// Counting cells keeps a file of short garbage lines from sizing arrays far beyond its bytes.
Eigen::Index count_rows(const std::filesystem::path& file) {
  FileLines lines(file);
  const auto header = lines.next();
  if (!header) return 0;
  const auto commas = std::count(header->begin(), header->end(), ',');
  Eigen::Index rows = 0;
  while (const auto line = lines.next()) {
    if (is_blank(*line)) continue;
    if (std::count(line->begin(), line->end(), ',') != commas) break;
    ++rows;
  }
  return rows;
}

template <class Array>
Array allocate(Eigen::Index rows, Eigen::Index cols) {
  try {
    return Array(rows, cols);
  } catch (const std::bad_alloc&) {
    throw Error(std::to_string(rows) + " rows of " + std::to_string(cols) + " signals need " +
                std::to_string(double(rows) * double(cols) * 8e-9) + " GB of memory, more than there is");
  }
}

}  // namespace

void read_samples_csv(const std::filesystem::path& file, const ReadOptions& options, Experiment& e,
                      std::vector<std::string>& warnings) {
  const Eigen::Index capacity = count_rows(file);
  FileLines lines(file);
  std::optional<std::string_view> header_line = lines.next();
  if (header_line && header_line->substr(0, 3) == "\xEF\xBB\xBF") header_line->remove_prefix(3);  // UTF-8 BOM
  if (!header_line || is_blank(*header_line))
    throw Error(at(1) + ": expected a header line of column names starting with 't', got an empty line");
  std::vector<std::string_view> cells;  // views into `lines`: valid until its next line
  split_cells(*header_line, cells);
  const std::size_t header_cells = cells.size();
  const std::vector<std::size_t> columns = locate_columns(cells, e, warnings);
  const std::vector<std::string> names = e.signal_names();

  // The arrays are sized once from the first pass and filled in place: memory is the samples'
  // 8 bytes x (1 + signals) per row, never the file's text or a growing copy.
  const auto ny = static_cast<Eigen::Index>(e.y_names.size());
  const auto nu = static_cast<Eigen::Index>(e.u_names.size());
  const auto nr = static_cast<Eigen::Index>(e.r_names.size());
  Eigen::VectorXd t = allocate<Eigen::VectorXd>(capacity, 1);
  e.y = allocate<Eigen::MatrixXd>(capacity, ny);
  e.u = allocate<Eigen::MatrixXd>(capacity, nu);
  e.r = allocate<Eigen::MatrixXd>(capacity, nr);
  Eigen::MatrixXd* const groups[] = {&e.y, &e.u, &e.r};
  const Eigen::Index first_column[] = {0, ny, ny + nu};
  Eigen::Index rows = 0;
  std::size_t blank_line = 0;  // a blank line, harmless only at the end of the file
  while (const auto line = lines.next()) {
    if (is_blank(*line)) {
      if (blank_line == 0) blank_line = lines.number();
      continue;
    }
    if (blank_line != 0) throw Error(at(blank_line) + " is empty; expected " + std::to_string(header_cells) + " cells");
    split_cells(*line, cells);
    if (cells.size() != header_cells)
      throw Error(at(lines.number()) + " has " + std::to_string(cells.size()) + " cells, the header has " +
                  std::to_string(header_cells) + " (a ',' decimal point or thousands separator splits a number)");
    if (rows == capacity) throw Error(at(lines.number()) + ": the file changed while it was read");
    const double time = parse_cell(cells[0], lines.number(), "t");
    if (rows > 0 && !(time > t(rows - 1)))
      throw Error(at(lines.number()) + ": t = " + quote_excerpt(cells[0]) + " is not greater than t = " +
                  number_text(t(rows - 1)) + " on " + at(lines.number() - 1) + "; t must be strictly increasing");
    t(rows) = time;
    for (std::size_t g = 0, s = 0; g < 3; ++g)
      for (Eigen::Index j = 0; j < groups[g]->cols(); ++j, ++s)
        (*groups[g])(rows, j) = parse_cell(cells[columns[s]], lines.number(), names[s]);
    ++rows;
  }
  if (rows < 2) throw Error("has " + std::to_string(rows) + " data rows; at least 2 are needed");
  if (rows != capacity)
    throw Error("the file changed while it was read (" + std::to_string(rows) + " rows, " + std::to_string(capacity) +
                " before)");
  // Rows are the lines after the header, one each: row k is on line k + 2.
  const auto line_of_row = [](Eigen::Index k) { return std::size_t(k) + 2; };
  const double T = e.sample_time;
  if (const auto gap = find_sampling_gap(t, T)) {
    const std::size_t line = line_of_row(*gap);
    const std::string where = "t jumps by " + number_text(t(*gap) - t(*gap - 1)) + " s from " +
                              number_text(t(*gap - 1)) + " (" + at(line - 1) + ") to " + number_text(t(*gap)) + " (" +
                              at(line) + ")";
    if (!options.resample)
      throw Error(at(line) + ": sampling is not uniform: " + where + "; every step must be sample_time " +
                  number_text(T) + " s within 1 % (reading with resampling interpolates onto a uniform grid)");
    // Resampling works on one table of all signals (a copy: the one path that needs more
    // memory than the samples).
    const double span = t(rows - 1) - t(0);
    Eigen::MatrixXd values(rows, ny + nu + nr);
    for (std::size_t g = 0; g < 3; ++g) values.middleCols(first_column[g], groups[g]->cols()) = *groups[g];
    resample_uniform(t, values, T, line_of_row(rows - 1));
    if (t.size() < 2)
      throw Error("spans " + number_text(span) + " s, less than one sample_time " + number_text(T) +
                  " s; resampling leaves 1 sample, at least 2 are needed");
    warnings.push_back("sampling is not uniform (first at " + at(line) + ": " + where + "); resampled " +
                       std::to_string(rows) + " rows onto " + std::to_string(t.size()) + " samples every " +
                       number_text(T) + " s by linear interpolation");
    for (std::size_t g = 0; g < 3; ++g) *groups[g] = values.middleCols(first_column[g], groups[g]->cols());
  }
  e.t = std::move(t);
}

std::string samples_csv(const Experiment& e) {
  std::string out = "t";
  for (const auto& name : e.signal_names()) out += "," + name;
  out += '\n';
  const Eigen::MatrixXd* groups[] = {&e.y, &e.u, &e.r};
  for (Eigen::Index k = 0; k < e.samples(); ++k) {
    out += number_text(e.t(k));
    for (const Eigen::MatrixXd* values : groups)
      for (Eigen::Index j = 0; j < values->cols(); ++j) {
        out += ',';
        out += number_text((*values)(k, j));
      }
    out += '\n';
  }
  return out;
}

}  // namespace ambid
