// SPDX-License-Identifier: Apache-2.0
// The one table / checks writer and gnuplot runner of the experiment drivers.
// Not RT-safe (allocates, does I/O): drivers call it after their runs.
#pragma once

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace mrh::experiments::internal {

/// A table of named columns whose cells the driver has already formatted (each column keeps
/// its own precision and unit). Writes CSV (header line, comma-separated rows) and Markdown.
class Table {
 public:
  explicit Table(std::vector<std::string> columns) : columns_(std::move(columns)) {}

  /// Appends a row. @throws mrh::InvalidArgument if it has not one cell per column.
  void Add(std::vector<std::string> cells);

  /// `format` (a fmt format string with one replacement per column) applied to `values`,
  /// split at commas into cells: one CSV row.
  template <typename... T>
  void AddFormatted(fmt::format_string<T...> format, T&&... values) {
    AddCsvLine(fmt::format(format, std::forward<T>(values)...));
  }

  const std::vector<std::string>& columns() const { return columns_; }

  const std::vector<std::vector<std::string>>& rows() const { return rows_; }

  /// "a,b\n1,2\n..." (no quoting: cells hold numbers and plain names).
  std::string Csv() const;
  /// "| a | b |\n|---|---|\n| 1 | 2 |\n..." (an empty cell is "| |").
  std::string Markdown() const;
  /// Each row as an object column → number (cells that parse as a number) or string.
  nlohmann::json Json() const;

 private:
  void AddCsvLine(const std::string& line);

  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
};

/// A cell of an optional value: `format` applied to it, or empty.
std::string OptionalCell(const std::optional<double>& value, std::string_view format);

/// The pass/fail checks of an experiment. ok() needs at least one check: an empty list is a
/// failure, not a pass.
class Checks {
 public:
  /// A check with no number behind it.
  void Add(const std::string& name, bool pass) { checks_.push_back({name, pass, {}, {}}); }

  /// A check that compares `value` against `bound` (units in the name).
  void Add(const std::string& name, bool pass, double value, double bound) {
    checks_.push_back({name, pass, value, bound});
  }

  /// Adds every name → bool of `checks` (as older checkers return them).
  void AddJson(const nlohmann::json& checks);

  bool empty() const { return checks_.empty(); }

  /// True if there is at least one check and every check passed.
  bool ok() const;
  /// {"name": pass, ...}: summary.json's "checks".
  nlohmann::json Json() const;
  /// | check | value | bound | result |.
  std::string Markdown() const;
  /// "check <name>: pass|FAIL" lines, in summary.json's (sorted) order.
  void Print(std::ostream& out) const;

 private:
  struct Check {
    std::string name;
    bool pass = false;
    std::optional<double> value, bound;
  };

  std::vector<Check> checks_;
};

/// The common tail of a driver: sets summary["checks"], writes out/summary.json and, unless
/// `quiet`, prints the checks and the results folder. Returns 0 if checks.ok(), else 1.
/// @throws mrh::RuntimeError if summary.json cannot be written.
int FinishExperiment(const std::filesystem::path& out, nlohmann::json summary, const Checks& checks,
                     bool quiet);

/// Writes out/<stem>.gp (`script`, which must `set output '<stem>.png'`) and runs gnuplot on
/// it in `out`. A missing or failing gnuplot is a warning on stderr (unless `quiet`), never
/// an error: the CSVs are the results, the PNG a view of them.
void Plot(const std::filesystem::path& out, const std::string& stem, const std::string& script,
          bool quiet);

}  // namespace mrh::experiments::internal
