// SPDX-License-Identifier: Apache-2.0
// report.gp: scans ticks.csv and bodies.csv, then lays out only the panels the run has data for.
#include "report/report_script.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>

#include "mrh/device/safety.h"

namespace mrh::report::internal {
namespace {

// Columns of ticks.csv (1-based, as gnuplot counts): t, p, q, f, tau, contacts, safety.
constexpr int kTickColumns = 16;
constexpr std::uint32_t kClampBits = device::kSafetyForceClamped | device::kSafetyTorqueClamped;
// Each panel gets this many pixels of height; the width fits a legend of body names.
constexpr int kPanelHeightPx = 230;
constexpr int kWidthPx = 1200;

double ToDouble(std::string_view text) {
  double value = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

// Comma-separated fields of one CSV line; a quoted field (a body name with a comma) keeps its
// text without the quotes.
std::vector<std::string> Fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else {
        quoted = !quoted;
      }
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  return out;
}

// A gnuplot single-quoted string: only '' needs escaping, and backslashes stay literal.
std::string Quote(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\n' || c == '\r') continue;
    if (c == '\'') out += '\'';
    out += c;
  }
  return out + "'";
}

std::string ForcePanel(const TickScan& ticks) {
  std::string out = "set ylabel 'force (N)'\n";
  out +=
      "plot 'ticks.csv' using 1:9 with lines title 'f_x', \\\n"
      "     '' using 1:10 with lines title 'f_y', \\\n"
      "     '' using 1:11 with lines title 'f_z', \\\n"
      "     '' using 1:(fnorm($9, $10, $11)) with lines lw 2 title '|f|'";
  // Marks only for events the run had: a legend entry with nothing behind it would mislead.
  if (ticks.clamped > 0) {
    out += fmt::format(
        ", \\\n     '' using 1:((int($16) & {}) != 0 ? fnorm($9, $10, $11) : NaN) with points "
        "pt 2 ps 0.6 lc rgb 'red' title 'clamped ({} ticks)'",
        kClampBits, ticks.clamped);
  }
  if (ticks.contact_losses > 0) {
    out += fmt::format(
        ", \\\n     '' using 1:(lost = prev > 0 && $15 == 0, prev = $15, lost ? 0 : NaN) with "
        "points pt 9 ps 1.2 lc rgb 'black' title 'contact lost ({})'",
        ticks.contact_losses);
  }
  return out + "\n";
}

// Several pointers: ticks.csv's rows cycle through the pointers, so `every n::i` picks pointer
// i's rows; one colour (linetype) per pointer.
std::string PointerForcePanel(const TickScan& ticks, const std::vector<std::string>& names) {
  std::string out = "set ylabel 'force |f| (N)'\n";
  for (std::size_t i = 0; i < names.size(); ++i) {
    out += fmt::format(
        "{}'ticks.csv' every {}::{} using 1:(fnorm($9, $10, $11)) with lines "
        "lt {} title {}",
        i == 0 ? "plot " : ", \\\n     ", names.size(), i, i + 1, Quote("|f| " + names[i]));
  }
  if (ticks.clamped > 0) {
    out += fmt::format(
        ", \\\n     '' using 1:((int($16) & {}) != 0 ? fnorm($9, $10, $11) : NaN) with points "
        "pt 2 ps 0.6 lc rgb 'red' title 'clamped ({} ticks)'",
        kClampBits, ticks.clamped);
  }
  return out + "\n";
}

std::string PointerPositionPanel(const std::vector<std::string>& names) {
  std::string out = "set ylabel 'pointer position (m)'\n";
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      out += fmt::format("{}'ticks.csv' every {}::{} using 1:{} with lines lt {} dt {} title {}",
                         i == 0 && axis == 0 ? "plot " : ", \\\n     ", names.size(), i, 2 + axis,
                         i + 1, axis + 1, Quote(names[i] + " " + std::string(1, "xyz"[axis])));
    }
  }
  return out + "\n";
}

std::string TorquePanel() {
  return "set ylabel 'torque (N m)'\n"
         "plot 'ticks.csv' using 1:12 with lines title 'tau_x', \\\n"
         "     '' using 1:13 with lines title 'tau_y', \\\n"
         "     '' using 1:14 with lines title 'tau_z'\n";
}

std::string PositionPanel() {
  return "set ylabel 'pointer position (m)'\n"
         "plot 'ticks.csv' using 1:2 with lines title 'x', \\\n"
         "     '' using 1:3 with lines title 'y', \\\n"
         "     '' using 1:4 with lines title 'z'\n";
}

// The pointer's orientation as a rotation vector (axis times angle, degrees), from the
// quaternion columns 5..8.
std::string OrientationPanel() {
  return "set ylabel 'pointer rotation (deg)'\n"
         "plot 'ticks.csv' using 1:(rotvec($5, $6, $7, $8, $6)) with lines title 'r_x', \\\n"
         "     '' using 1:(rotvec($5, $6, $7, $8, $7)) with lines title 'r_y', \\\n"
         "     '' using 1:(rotvec($5, $6, $7, $8, $8)) with lines title 'r_z'\n";
}

// One line per drawn body: the distance of its origin from where it started. Rows come in the
// same body order every physics step, so `every n::k` picks body k's rows.
std::string ObjectsPanel(const BodyScan& scan, const std::vector<BodyTrace>& drawn) {
  std::string out = "set ylabel 'object moved |p - p_0| (m)'\n";
  if (drawn.size() < scan.bodies.size()) {
    out += fmt::format("set title '{} of {} objects shown: touched, then most moved'\n",
                       drawn.size(), scan.bodies.size());
  }
  const std::size_t n = scan.bodies.size();
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    const BodyTrace& body = drawn[i];
    out += i == 0 ? "plot 'bodies.csv'" : ", \\\n     ''";
    out += fmt::format(
        " every {}::{} using 1:(fnorm($3 - ({}), $4 - ({}), $5 - ({}))) with lines "
        "title {}",
        n, body.index, body.p0.x(), body.p0.y(), body.p0.z(), Quote(body.name));
  }
  out += "\n";
  if (drawn.size() < scan.bodies.size()) out += "unset title\n";
  return out;
}

}  // namespace

TickScan ScanTicks(const std::filesystem::path& path) {
  TickScan scan;
  std::ifstream file(path);
  std::string line;
  if (!std::getline(file, line)) return scan;
  scan.has_safety = Fields(line).size() >= kTickColumns;
  int previous_contacts = 0;
  while (std::getline(file, line)) {
    const std::vector<std::string> f = Fields(line);
    if (f.size() < kTickColumns - 1) continue;
    const double t = ToDouble(f[0]);
    if (scan.rows++ == 0) scan.t_first = t;
    scan.t_last = t;
    const int contacts = static_cast<int>(ToDouble(f[14]));
    if (previous_contacts > 0 && contacts == 0) ++scan.contact_losses;
    previous_contacts = contacts;
    if (scan.has_safety && f.size() >= kTickColumns) {
      const auto bits = static_cast<std::uint32_t>(ToDouble(f[15]));
      if ((bits & kClampBits) != 0) ++scan.clamped;
    }
  }
  return scan;
}

BodyScan ScanBodies(const std::filesystem::path& path) {
  BodyScan scan;
  std::ifstream file(path);
  std::string line;
  if (!std::getline(file, line)) return scan;
  std::map<std::string, std::size_t> by_name;
  while (std::getline(file, line)) {
    const std::vector<std::string> f = Fields(line);
    if (f.size() < 5) continue;
    scan.t_last = ToDouble(f[0]);
    const Vec3 p(ToDouble(f[2]), ToDouble(f[3]), ToDouble(f[4]));
    const auto [it, added] = by_name.try_emplace(f[1], scan.bodies.size());
    if (added) {
      scan.bodies.push_back(
          BodyTrace{.name = f[1], .index = static_cast<int>(it->second), .p0 = p});
      continue;
    }
    BodyTrace& body = scan.bodies[it->second];
    body.max_moved = std::max(body.max_moved, (p - body.p0).norm());
  }
  return scan;
}

std::vector<BodyTrace> BodiesToDraw(const BodyScan& scan, const ReportOptions& options) {
  const auto limit = static_cast<std::size_t>(std::max(1, options.max_legend_bodies));
  std::vector<BodyTrace> order = scan.bodies;
  if (order.size() <= limit) return order;
  const auto touched = [&](const BodyTrace& b) {
    return std::find(options.touched_bodies.begin(), options.touched_bodies.end(), b.name) !=
           options.touched_bodies.end();
  };
  std::stable_sort(order.begin(), order.end(), [&](const BodyTrace& a, const BodyTrace& b) {
    if (touched(a) != touched(b)) return touched(a);
    return a.max_moved > b.max_moved;
  });
  order.resize(limit);
  // Keep the file order in the legend, so that colours do not depend on the ranking.
  std::sort(order.begin(), order.end(), [](const BodyTrace& a, const BodyTrace& b) {
    return a.index < b.index;
  });
  return order;
}

namespace {

// The report's panels, top to bottom, and the end of the multiplot.
std::string Panels(const ReportOptions& options, const TickScan& ticks, const BodyScan& bodies) {
  std::string out;
  const bool several = options.pointers.size() >= 2;
  out += several ? PointerForcePanel(ticks, options.pointers) : ForcePanel(ticks);
  if (options.six_dof) out += TorquePanel();
  out += several ? PointerPositionPanel(options.pointers) : PositionPanel();
  if (options.six_dof) out += OrientationPanel();
  if (!bodies.bodies.empty()) out += ObjectsPanel(bodies, BodiesToDraw(bodies, options));
  out += "unset multiplot\n";
  return out;
}

}  // namespace

std::string ReportScript(const std::string& title, const ReportOptions& options,
                         const TickScan& ticks, const BodyScan& bodies) {
  const bool objects = !bodies.bodies.empty();
  const int panels = 2 + (options.six_dof ? 2 : 0) + (objects ? 1 : 0);
  // One time axis: every panel spans the first to the last record of either file, so a body
  // row past the last tick (or the reverse) cannot stretch one panel's axis alone.
  const double t_end = std::max(ticks.t_last, bodies.t_last);
  const double t_begin = std::min(ticks.t_first, t_end);
  std::string out = fmt::format(
      R"(# Generated by mrh from ticks.csv and bodies.csv. Re-run from this folder: gnuplot report.gp
set terminal pngcairo size {},{} noenhanced font ',10'
set output 'report.png'
set datafile separator ','
set key autotitle columnhead outside right noenhanced
set grid
set lmargin 12
set rmargin 24
set offsets 0, 0, graph 0.05, graph 0.05
set xrange [{:.6g}:{:.6g}]
fnorm(x, y, z) = sqrt(x**2 + y**2 + z**2)
# Rotation vector component (deg) of the unit quaternion (w, x, y, z): angle * axis_c.
qv(x, y, z) = sqrt(x**2 + y**2 + z**2)
rotvec(w, x, y, z, c) = qv(x, y, z) > 1e-12 ? \
  (w < 0 ? -2 : 2) * atan2(qv(x, y, z), abs(w)) * c / qv(x, y, z) * 180 / pi : 0
prev = 0
set multiplot layout {},1 title {}
)",
      kWidthPx, kPanelHeightPx * panels + 40, t_begin, t_end > t_begin ? t_end : t_begin + 1.0,
      panels, Quote(title));
  out += Panels(options, ticks, bodies);
  // The time label goes on the bottom panel only: insert it before that panel's plot command.
  const std::size_t last_plot = out.rfind("\nplot ");
  out.insert(last_plot + 1, "set xlabel 't (s)'\n");
  return out;
}

}  // namespace mrh::report::internal
