// SPDX-License-Identifier: Apache-2.0
// The trials file of a psychophysics run: one CSV row per answered trial, appended and flushed.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace mrh::psychophysics {

/// One answered 2AFC trial (docs/psychophysics.md, "Trials file").
struct TrialRow {
  std::string subject;
  int trial = 0;                    ///< 0-based index in the run's schedule
  std::string method;               ///< rendering method of the comparison stimulus
  std::string standard_method;      ///< rendering method of the standard stimulus
  double standard_mass = 0.0;       ///< kg
  double comparison_mass = 0.0;     ///< kg
  double speed = 0.0;               ///< m/s, initial speed of the cube (both stimuli)
  bool comparison_first = false;    ///< the comparison was stimulus 1 (else 2)
  int answer = 0;                   ///< stimulus the subject called heavier: 1 or 2
  bool comparison_heavier = false;  ///< the answer named the comparison
  double response_time = 0.0;       ///< s from the question to the answer
  std::uint64_t seed = 0;           ///< seed of the run's random order
};

/// The header line (without newline): subject,trial,method,standard_method,standard_mass,
/// comparison_mass,speed,comparison_first,answer,comparison_heavier,response_time,seed.
std::string TrialsHeader();

/// One CSV line (without newline); numbers with 17 significant digits at most.
/// @throws mrh::InvalidArgument if a text field holds a comma, quote or line break.
std::string FormatTrialRow(const TrialRow& row);

/// Every row of a trials file (header checked; columns in any order; blank lines skipped). Only
/// subject, method, standard_mass, comparison_mass and comparison_heavier are required; absent
/// bookkeeping columns take the defaults documented in docs/psychophysics.md.
/// @throws mrh::InvalidArgument naming the file, line and column for a missing column, a bad
/// number, an answer other than 1/2, or comparison_heavier inconsistent with the answer.
std::vector<TrialRow> ReadTrials(const std::filesystem::path& file);

/// Appends rows to a trials file, writing the header first if the file is new or empty, and
/// flushing after each row (fflush, then fsync if `sync`), so that a stopped run loses no
/// answered trial (with fsync, not even on a power cut). Not RT-safe; one thread.
class TrialsWriter {
 public:
  /// @throws mrh::RuntimeError naming the file if it cannot be opened for appending.
  explicit TrialsWriter(const std::filesystem::path& file, bool sync = true);
  ~TrialsWriter();
  TrialsWriter(const TrialsWriter&) = delete;
  TrialsWriter& operator=(const TrialsWriter&) = delete;

  /// @throws mrh::RuntimeError naming the file on a write error.
  void Append(const TrialRow& row);

 private:
  void Write(const std::string& line);

  std::filesystem::path file_;
  std::FILE* out_ = nullptr;
  bool sync_ = true;
};

}  // namespace mrh::psychophysics
