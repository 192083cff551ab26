// SPDX-License-Identifier: Apache-2.0
// D3's figure: the transients (force minus the resting spring) and their spectra per material.
#include <string>

#include "experiment_table.h"
#include "experiments_impl.h"

namespace mrh::experiments::internal {

void PlotD3(const std::filesystem::path& out, bool quiet) {
  std::string script = R"(set terminal pngcairo size 1200,900
set output 'd3.png'
set datafile separator ','
set key top right
set multiplot layout 2,1
set title 'D3: contact transients after the stop (rendered force - resting spring), tap at 0.1 m/s'
set xlabel 'time since contact onset (s)'
set ylabel 'force (N)'
set xrange [0:0.25]
)";
  const char* materials[] = {"aluminium", "wood", "rubber"};
  std::string plot = "plot ";
  for (const char* m : materials) {
    plot += std::string("'d3_transients.csv' skip 1 using (strcol(1) eq '") + m +
            "' && $2 == 0.1 ? $3 : 1/0):4 with lines title '" + m + "', ";
  }
  script += plot.substr(0, plot.size() - 2) + "\n";
  script += R"(set title 'Spectra of the transients (|DFT|), tap at 0.1 m/s'
set xlabel 'frequency (Hz)'
set ylabel '|DFT| (N s)'
set xrange [0:500]
)";
  plot = "plot ";
  for (const char* m : materials) {
    plot += std::string("'d3_spectra.csv' skip 1 using (strcol(1) eq '") + m +
            "' && $2 == 0.1 ? $3 : 1/0):4 with lines title '" + m + "', ";
  }
  script += plot.substr(0, plot.size() - 2) + "\nunset multiplot\n";
  Plot(out, "d3", script, quiet);
}

}  // namespace mrh::experiments::internal
