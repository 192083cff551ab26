// SPDX-License-Identifier: Apache-2.0
// The CSV reader behind LoadKeyframesCsv and the replay device.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <span>
#include <string>

#include "device/csv_impl.h"
#include "mrh/core/error.h"
#include "mrh/core/validate.h"

namespace mrh::device::internal {
namespace {

std::string_view Trim(std::string_view s) {
  constexpr std::string_view kSpace = " \t\r";
  const auto begin = s.find_first_not_of(kSpace);
  if (begin == std::string_view::npos) return {};
  return s.substr(begin, s.find_last_not_of(kSpace) - begin + 1);
}

std::vector<std::string_view> SplitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(Trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

std::string JoinColumns(std::span<const std::string_view> columns) {
  std::string joined;
  for (const auto& c : columns) {
    if (!joined.empty()) joined += ',';
    joined += c;
  }
  return joined;
}

// Reads one CSV file line by line and reports errors as "<file>:<line>: ...".
class PoseCsvReader {
 public:
  PoseCsvReader(const std::filesystem::path& path, const PoseColumns& columns,
                std::string_view kind)
      : path_(path), columns_(columns), kind_(kind) {}

  std::vector<Keyframe> Read() {
    std::ifstream in(path_);
    if (!in) Fail("cannot open the file; expected a readable " + std::string(kind_));
    std::string line;
    if (!std::getline(in, line) || Trim(line).empty()) {
      line_ = 1;
      Fail("no header; expected a " + std::string(kind_) + " header with columns " +
           JoinColumns(columns_));
    }
    line_ = 1;
    ParseHeader(line);
    std::vector<Keyframe> keyframes;
    while (std::getline(in, line)) {
      ++line_;
      if (Trim(line).empty()) continue;
      keyframes.push_back(ParseRow(line));
      const double previous = keyframes.size() > 1 ? keyframes[keyframes.size() - 2].t : NAN;
      const Problem problem = KeyframeTimeProblem(keyframes.back().t, previous);
      if (problem) Fail("column '" + std::string(columns_[0]) + "': " + problem.Text());
    }
    if (keyframes.empty()) Fail("no data rows; expected at least one row after the header");
    return keyframes;
  }

 private:
  [[noreturn]] void Fail(const std::string& message) const {
    std::string where = path_.string();
    if (line_ > 0) where += ":" + std::to_string(line_);
    throw InvalidArgument(where + ": " + message);
  }

  void ParseHeader(std::string_view header) {
    const auto names = SplitFields(header);
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      std::size_t found = names.size();
      for (std::size_t i = 0; i < names.size() && found == names.size(); ++i) {
        if (names[i] == columns_[c]) found = i;
      }
      if (found == names.size()) {
        Fail("header lacks column '" + std::string(columns_[c]) + "'; expected a " +
             std::string(kind_) + " header with columns " + JoinColumns(columns_) +
             " (any order, extra columns ignored)");
      }
      index_[c] = found;
      num_fields_ = std::max(num_fields_, found + 1);
    }
  }

  double ParseField(std::string_view field, std::size_t column) const {
    double value = 0.0;
    const auto result = std::from_chars(field.data(), field.data() + field.size(), value);
    if (field.empty() || result.ec != std::errc() || result.ptr != field.data() + field.size()) {
      Fail("column '" + std::string(columns_[column]) + "' = '" + std::string(field) +
           "' is not a number; expected a decimal number");
    }
    if (!std::isfinite(value)) {
      Fail("column '" + std::string(columns_[column]) + "' = " + std::string(field) +
           "; expected a finite number");
    }
    return value;
  }

  Keyframe ParseRow(std::string_view line) const {
    const auto fields = SplitFields(line);
    if (fields.size() < num_fields_) {
      Fail(std::to_string(fields.size()) + " fields; expected at least " +
           std::to_string(num_fields_) + " as the header needs");
    }
    std::array<double, 8> v{};
    for (std::size_t c = 0; c < columns_.size(); ++c) v[c] = ParseField(fields[index_[c]], c);
    Keyframe k;
    k.t = v[0];
    k.X_DT.p = Vec3(v[1], v[2], v[3]);
    k.X_DT.q = Quat(v[4], v[5], v[6], v[7]);
    // The same rules as the session's poses and keyframes (mrh/core/validate.h).
    const Problem problem = PoseProblem(k.X_DT.p, k.X_DT.q);
    if (problem) {
      Fail("columns " + JoinColumns(std::span(columns_).subspan(1)) + ": " + problem.Text());
    }
    k.X_DT.q.normalize();
    return k;
  }

  const std::filesystem::path& path_;
  const PoseColumns& columns_;
  std::string_view kind_;
  std::size_t line_ = 0;
  std::array<std::size_t, 8> index_{};
  std::size_t num_fields_ = 0;
};

}  // namespace

std::vector<Keyframe> ReadPoseCsv(const std::filesystem::path& path, const PoseColumns& columns,
                                  std::string_view kind) {
  return PoseCsvReader(path, columns, kind).Read();
}

}  // namespace mrh::device::internal
