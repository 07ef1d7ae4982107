// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// CSV parsing is Ben Strasser's fast-cpp-csv-parser (Debian libfccp-dev).

#include "fit3dof/time_history.h"

// csv.h uses std::numeric_limits without including <limits>.
#include <limits>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-truncation"
#include <libfccp/csv.h>
#pragma GCC diagnostic pop

#include <cmath>
#include <cstdio>
#include <string>

#include "fit3dof/atomic_file.h"
#include "fit3dof/input_error.h"

namespace fit3dof {

TimeHistory ReadTimeHistory(const std::string& path) {
  TimeHistory history;
  try {
    io::CSVReader<4,
                  io::trim_chars<' ', '\t'>,
                  io::no_quote_escape<','>,
                  io::throw_on_overflow,
                  io::single_line_comment<'#'>>
        reader(path);
    reader.read_header(io::ignore_extra_column, "t", "phi", "theta", "psi");
    double t, phi, theta, psi;
    while (reader.read_row(t, phi, theta, psi)) {
      const int line = static_cast<int>(reader.get_file_line());
      if (!std::isfinite(t) || !std::isfinite(phi) || !std::isfinite(theta) ||
          !std::isfinite(psi)) {
        throw InputError(path + ":" + std::to_string(line) +
                         ": every value must be a finite number");
      }
      if (!history.t.empty() && !(t > history.t.back())) {
        throw InputError(
            path + ":" + std::to_string(line) +
            ": times must increase strictly (t = " + std::to_string(t) +
            " after " + std::to_string(history.t.back()) + ")");
      }
      history.Append(t, phi, theta, psi);
    }
  } catch (const io::error::base& e) {
    throw InputError(std::string(e.what()) +
                     " (expected a CSV file with header columns t, phi, "
                     "theta, psi)");
  }
  if (history.size() < 2) {
    throw InputError(path + ": needs at least two rows of data");
  }
  return history;
}

std::string FormatTimeHistory(const TimeHistory& history) {
  std::string out = "t,phi,theta,psi\n";
  char line[160];
  for (int i = 0; i < history.size(); ++i) {
    std::snprintf(line,
                  sizeof(line),
                  "%.12g,%.12g,%.12g,%.12g\n",
                  history.t[i],
                  history.phi[i],
                  history.theta[i],
                  history.psi[i]);
    out += line;
  }
  return out;
}

void WriteTimeHistory(const std::string& path, const TimeHistory& history) {
  WriteFileAtomically(path, FormatTimeHistory(history));
}

}  // namespace fit3dof
