// SPDX-License-Identifier: Apache-2.0
// Trials CSV: formatting, strict reading (file:line:column errors), append + flush per row.
#include "mrh/psychophysics/trials.h"

#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "mrh/core/error.h"

namespace mrh::psychophysics {
namespace {

constexpr std::array<const char*, 12> kColumns{
    "subject",         "trial", "method",           "standard_method", "standard_mass",
    "comparison_mass", "speed", "comparison_first", "answer",          "comparison_heavier",
    "response_time",   "seed"};

// What the fit needs; data from another tool (PsychoPy, a spreadsheet) may hold only these.
// The other columns are bookkeeping of mrh's own runs, with defaults when absent.
constexpr std::array<const char*, 5> kEssentialColumns{"subject", "method", "standard_mass",
                                                       "comparison_mass", "comparison_heavier"};

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// Reads one row's cells by column name, with errors naming file, line and column.
class RowReader {
 public:
  RowReader(const std::filesystem::path& file, int line, const std::map<std::string, int>& index,
            const std::vector<std::string>& cells)
      : file_(file), line_(line), index_(index), cells_(cells) {}

  bool Has(const char* column) const { return index_.contains(column); }

  int line() const { return line_; }

  const std::string& Text(const char* column) const {
    const int at = index_.at(column);
    if (at >= static_cast<int>(cells_.size())) Fail(column, "", "a value");
    return cells_[at];
  }

  double Number(const char* column) const {
    const std::string& text = Text(column);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
      Fail(column, text, "a finite number");
    }
    return value;
  }

  long long Integer(const char* column, long long lo, long long hi) const {
    const std::string& text = Text(column);
    long long value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < lo || value > hi) {
      Fail(column, text, fmt::format("an integer in [{}, {}]", lo, hi));
    }
    return value;
  }

  std::uint64_t Unsigned(const char* column) const {
    const std::string& text = Text(column);
    std::uint64_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) {
      Fail(column, text, "an unsigned integer");
    }
    return value;
  }

  [[noreturn]] void Fail(const char* column, const std::string& value,
                         const std::string& expected) const {
    throw InvalidArgument(fmt::format("{}:{}: column {} = \"{}\"; expected {}", file_.string(),
                                      line_, column, value, expected));
  }

 private:
  const std::filesystem::path& file_;
  int line_;
  const std::map<std::string, int>& index_;
  const std::vector<std::string>& cells_;
};

// Columns beyond kEssentialColumns default when absent: trial = the row's index, no standard
// method, speed 0, comparison first 0, the answer that names the comparison when it was
// called heavier, response time 0, seed 0.
TrialRow ParseRow(const RowReader& r) {
  TrialRow row;
  row.subject = r.Text("subject");
  row.trial =
      r.Has("trial") ? static_cast<int>(r.Integer("trial", 0, 1'000'000'000)) : r.line() - 2;
  row.method = r.Text("method");
  if (r.Has("standard_method")) row.standard_method = r.Text("standard_method");
  row.standard_mass = r.Number("standard_mass");
  row.comparison_mass = r.Number("comparison_mass");
  if (r.Has("speed")) row.speed = r.Number("speed");
  if (r.Has("comparison_first")) row.comparison_first = r.Integer("comparison_first", 0, 1) == 1;
  row.comparison_heavier = r.Integer("comparison_heavier", 0, 1) == 1;
  row.answer = r.Has("answer") ? static_cast<int>(r.Integer("answer", 1, 2))
                               : (row.comparison_heavier == row.comparison_first ? 1 : 2);
  if (r.Has("response_time")) row.response_time = r.Number("response_time");
  if (r.Has("seed")) row.seed = r.Unsigned("seed");
  if (row.comparison_heavier != ((row.answer == 1) == row.comparison_first)) {
    r.Fail("comparison_heavier", row.comparison_heavier ? "1" : "0",
           fmt::format("{} (answer {} with comparison_first {})",
                       (row.answer == 1) == row.comparison_first ? 1 : 0, row.answer,
                       row.comparison_first ? 1 : 0));
  }
  return row;
}

std::map<std::string, int> HeaderIndex(const std::filesystem::path& file,
                                       const std::string& header) {
  std::map<std::string, int> index;
  const std::vector<std::string> names = Split(header);
  for (int i = 0; i < static_cast<int>(names.size()); ++i) index[names[i]] = i;
  for (const char* column : kEssentialColumns) {
    if (!index.contains(column)) {
      throw InvalidArgument(
          fmt::format("{}:1: no column \"{}\"; expected at least subject, method, standard_mass, "
                      "comparison_mass and comparison_heavier (mrh's own header: {})",
                      file.string(), column, TrialsHeader()));
    }
  }
  return index;
}

}  // namespace

std::string TrialsHeader() {
  std::string header;
  for (const char* column : kColumns) header += (header.empty() ? "" : ",") + std::string(column);
  return header;
}

std::string FormatTrialRow(const TrialRow& row) {
  for (const std::string* text : {&row.subject, &row.method, &row.standard_method}) {
    if (text->find_first_of(",\"\r\n") != std::string::npos) {
      throw InvalidArgument(fmt::format(
          "trials file: \"{}\" holds a comma, quote or line break; expected a plain name", *text));
    }
  }
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{:.6f},{}", row.subject, row.trial, row.method,
                     row.standard_method, row.standard_mass, row.comparison_mass, row.speed,
                     row.comparison_first ? 1 : 0, row.answer, row.comparison_heavier ? 1 : 0,
                     row.response_time, row.seed);
}

std::vector<TrialRow> ReadTrials(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) {
    throw InvalidArgument(
        fmt::format("{}: cannot open the trials file; expected a readable CSV", file.string()));
  }
  std::string line;
  if (!std::getline(in, line)) {
    throw InvalidArgument(
        fmt::format("{}:1: empty file; expected the header {}", file.string(), TrialsHeader()));
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::map<std::string, int> index = HeaderIndex(file, line);
  std::vector<TrialRow> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> cells = Split(line);
    rows.push_back(ParseRow(RowReader(file, number, index, cells)));
  }
  return rows;
}

TrialsWriter::TrialsWriter(const std::filesystem::path& file, bool sync)
    : file_(file), sync_(sync) {
  out_ = std::fopen(file.c_str(), "a");
  if (out_ == nullptr) {
    throw RuntimeError(
        fmt::format("{}: cannot open for appending ({})", file.string(), std::strerror(errno)));
  }
  if (std::ftell(out_) == 0) Write(TrialsHeader());
}

TrialsWriter::~TrialsWriter() {
  if (out_ != nullptr) (void)std::fclose(out_);  // every row was flushed already
}

void TrialsWriter::Append(const TrialRow& row) {
  Write(FormatTrialRow(row));
}

void TrialsWriter::Write(const std::string& line) {
  const std::string text = line + "\n";
  const bool ok = std::fwrite(text.data(), 1, text.size(), out_) == text.size() &&
                  std::fflush(out_) == 0 && (!sync_ || ::fsync(::fileno(out_)) == 0);
  if (!ok) {
    throw RuntimeError(
        fmt::format("{}: cannot write a trial ({})", file_.string(), std::strerror(errno)));
  }
}

}  // namespace mrh::psychophysics
