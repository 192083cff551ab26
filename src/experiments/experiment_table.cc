// SPDX-License-Identifier: Apache-2.0
// The shared table / checks writer and gnuplot runner of the experiment drivers.
#include "experiment_table.h"

#include <charconv>
#include <iostream>
#include <map>

#include "experiment_util.h"
#include "mrh/core/error.h"
#include "mrh/report/report.h"

namespace mrh::experiments::internal {

void Table::Add(std::vector<std::string> cells) {
  if (cells.size() != columns_.size()) {
    throw InvalidArgument(fmt::format("table row has {} cells; expected {} (columns {})",
                                      cells.size(), columns_.size(), fmt::join(columns_, ",")));
  }
  rows_.push_back(std::move(cells));
}

void Table::AddCsvLine(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t begin = 0;
  for (std::size_t comma = line.find(','); comma != std::string::npos;
       comma = line.find(',', begin)) {
    cells.push_back(line.substr(begin, comma - begin));
    begin = comma + 1;
  }
  cells.push_back(line.substr(begin));
  Add(std::move(cells));
}

std::string Table::Csv() const {
  std::string csv = fmt::format("{}\n", fmt::join(columns_, ","));
  for (const auto& row : rows_) csv += fmt::format("{}\n", fmt::join(row, ","));
  return csv;
}

std::string Table::Markdown() const {
  std::string md = fmt::format("| {} |\n|", fmt::join(columns_, " | "));
  for (std::size_t i = 0; i < columns_.size(); ++i) md += "---|";
  md += "\n";
  for (const auto& row : rows_) {
    for (const std::string& cell : row) md += cell.empty() ? "| " : fmt::format("| {} ", cell);
    md += "|\n";
  }
  return md;
}

nlohmann::json Table::Json() const {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& row : rows_) {
    nlohmann::json object;
    for (std::size_t i = 0; i < columns_.size(); ++i) {
      const std::string& cell = row[i];
      double number = 0.0;
      const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), number);
      const bool numeric = !cell.empty() && ec == std::errc() && end == cell.data() + cell.size();
      object[columns_[i]] = numeric ? nlohmann::json(number) : nlohmann::json(cell);
    }
    rows.push_back(std::move(object));
  }
  return rows;
}

std::string OptionalCell(const std::optional<double>& value, std::string_view format) {
  return value ? fmt::format(fmt::runtime(format), *value) : std::string();
}

void Checks::AddJson(const nlohmann::json& checks) {
  for (const auto& [name, pass] : checks.items()) Add(name, pass.get<bool>());
}

bool Checks::ok() const {
  bool ok = !checks_.empty();  // no checks is a failure, not a pass
  for (const Check& c : checks_) ok = ok && c.pass;
  return ok;
}

nlohmann::json Checks::Json() const {
  nlohmann::json json = nlohmann::json::object();
  for (const Check& c : checks_) json[c.name] = c.pass;
  return json;
}

std::string Checks::Markdown() const {
  Table table({"check", "value", "bound", "result"});
  for (const Check& c : checks_) {
    table.Add({c.name, OptionalCell(c.value, "{:.6g}"), OptionalCell(c.bound, "{:.6g}"),
               c.pass ? "pass" : "FAIL"});
  }
  return table.Markdown();
}

void Checks::Print(std::ostream& out) const {
  const nlohmann::json sorted = Json();  // summary.json's order
  for (const auto& [name, pass] : sorted.items()) {
    out << "check " << name << ": " << (pass.get<bool>() ? "pass" : "FAIL") << "\n";
  }
}

int FinishExperiment(const std::filesystem::path& out, nlohmann::json summary, const Checks& checks,
                     bool quiet) {
  summary["checks"] = checks.Json();
  WriteText(out / "summary.json", summary.dump(2) + "\n");
  if (!quiet) {
    checks.Print(std::cout);
    std::cout << "results: " << std::filesystem::absolute(out).string() << "\n";
  }
  return checks.ok() ? 0 : 1;
}

void Plot(const std::filesystem::path& out, const std::string& stem, const std::string& script,
          bool quiet) {
  WriteText(out / (stem + ".gp"), script);
  std::string why;
  if (!report::RunGnuplotScript(out, stem + ".gp", stem + ".png", &why) && !quiet) {
    std::cerr << "mrh: warning: " << stem << ".png not drawn: " << why << "\n";
  }
}

}  // namespace mrh::experiments::internal
