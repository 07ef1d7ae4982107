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

#include <glog/logging.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>

#include "fit3dof/atomic_file.h"
#include "fit3dof/input_error.h"

namespace fit3dof {

namespace {

using CsvReader = io::CSVReader<4,
                                io::trim_chars<' ', '\t'>,
                                io::double_quote_escape<',', '"'>,
                                io::throw_on_overflow,
                                io::single_line_comment<'#'>>;

// A whole decimal number: [+-] digits [. digits] [e [+-] digits], with at
// least one digit before the exponent. strtod alone would read "1.5e" as
// 1.5, "-" as 0 and accept "nan", "inf" and hexadecimal.
bool ParseDecimal(const char* token, double* value) {
  const char* c = token;
  if (*c == '+' || *c == '-') ++c;
  int digits = 0;
  while (*c >= '0' && *c <= '9') ++c, ++digits;
  if (*c == '.') {
    ++c;
    while (*c >= '0' && *c <= '9') ++c, ++digits;
  }
  if (digits == 0) return false;
  if (*c == 'e' || *c == 'E') {
    ++c;
    if (*c == '+' || *c == '-') ++c;
    if (!(*c >= '0' && *c <= '9')) return false;
    while (*c >= '0' && *c <= '9') ++c;
  }
  if (*c != '\0') return false;
  *value = std::strtod(token, nullptr);
  return std::isfinite(*value);
}

// Passes every row to `sink` after checking it; returns the row count.
int ReadRows(CsvReader* reader,
             const std::string& source,
             const SampleSink& sink) {
  static const char* const kColumns[4] = {"t", "phi", "theta", "psi"};
  reader->read_header(io::ignore_extra_column, "t", "phi", "theta", "psi");
  char* fields[4];
  int rows = 0;
  double last_t = 0.0;
  while (reader->read_row(fields[0], fields[1], fields[2], fields[3])) {
    auto where = [&] {
      return source + ":" + std::to_string(reader->get_file_line());
    };
    double row[4];
    for (int j = 0; j < 4; ++j) {
      if (!ParseDecimal(fields[j], &row[j])) {
        std::string token(fields[j]);
        if (token.size() > 40) token = token.substr(0, 40) + "...";
        throw InputError(where() + ": column '" + kColumns[j] +
                         "': expected a finite decimal number, got '" + token +
                         "'");
      }
    }
    if (rows > 0 && !(row[0] > last_t)) {
      throw InputError(where() + ": times must increase strictly (t = " +
                       fields[0] + " after " + std::to_string(last_t) + ")");
    }
    if (rows == std::numeric_limits<int>::max()) {
      throw InputError(where() + ": more rows than a record may hold (" +
                       std::to_string(rows) + ")");
    }
    last_t = row[0];
    ++rows;
    sink(row[0], row[1], row[2], row[3]);
  }
  if (rows < 2) {
    throw InputError(source + ": needs at least two rows of data");
  }
  return rows;
}

// The parser's own errors in the project's form: file:line: what, what was
// expected.
std::string CsvProblem(const io::error::base& e, const std::string& source) {
  std::string where = source;
  if (const auto* l = dynamic_cast<const io::error::with_file_line*>(&e)) {
    if (l->file_line >= 0) where += ":" + std::to_string(l->file_line);
  }
  std::string column;
  if (const auto* c = dynamic_cast<const io::error::with_column_name*>(&e)) {
    column = c->column_name;
  }
  std::string what;
  if (dynamic_cast<const io::error::too_many_columns*>(&e)) {
    what = "more fields than the header has columns";
  } else if (dynamic_cast<const io::error::too_few_columns*>(&e)) {
    what = "fewer fields than the header has columns";
  } else if (dynamic_cast<const io::error::missing_column_in_header*>(&e)) {
    what = "the header has no column '" + column + "'";
  } else if (dynamic_cast<const io::error::duplicated_column_in_header*>(&e)) {
    what = "the header names column '" + column + "' twice";
  } else if (dynamic_cast<const io::error::header_missing*>(&e)) {
    what = "the file is empty (no header line)";
  } else if (dynamic_cast<const io::error::escaped_string_not_closed*>(&e)) {
    what = "a quoted field is not closed";
  } else if (dynamic_cast<const io::error::line_length_limit_exceeded*>(&e)) {
    what = "the line is longer than 16 MB";
  } else {
    what = e.what();
  }
  return where + ": " + what +
         " (expected CSV with a header naming the columns t, phi, theta, psi)";
}

}  // namespace

const std::vector<double>& TimeHistory::channel(int ch) const {
  CHECK(ch >= 0 && ch < 3) << "channel " << ch;
  return ch == 0 ? phi : ch == 1 ? theta : psi;
}

std::vector<double>& TimeHistory::channel(int ch) {
  return const_cast<std::vector<double>&>(std::as_const(*this).channel(ch));
}

const char* ChannelName(int channel) {
  CHECK(channel >= 0 && channel < 3) << "channel " << channel;
  static const char* const kNames[] = {"phi", "theta", "psi"};
  return kNames[channel];
}

int ForEachSample(const std::string& path, const SampleSink& sink) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    throw InputError(path + ": cannot open the data file (" +
                     std::strerror(errno) + ")");
  }
  try {
    CsvReader reader(path, file);  // the reader closes the file
    return ReadRows(&reader, path, sink);
  } catch (const io::error::base& e) {
    throw InputError(CsvProblem(e, path));
  }
}

TimeHistory ReadTimeHistory(const std::string& path) {
  TimeHistory history;
  ForEachSample(path, [&](double t, double phi, double theta, double psi) {
    history.Append(t, phi, theta, psi);
  });
  return history;
}

TimeHistory ParseTimeHistory(const std::string& text,
                             const std::string& source) {
  TimeHistory history;
  try {
    CsvReader reader(source, text.data(), text.data() + text.size());
    ReadRows(
        &reader, source, [&](double t, double phi, double theta, double psi) {
          history.Append(t, phi, theta, psi);
        });
  } catch (const io::error::base& e) {
    throw InputError(CsvProblem(e, source));
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

double CrossingPeriod(const TimeHistory& data, double min_crossings) {
  if (data.size() < 2) return 0.0;
  double crossings = 0.0;
  for (const std::vector<double>* channel : {&data.theta, &data.psi}) {
    double mean = 0.0;
    for (double x : *channel) mean += x;
    mean /= channel->size();
    for (size_t i = 1; i < channel->size(); ++i) {
      if (((*channel)[i] - mean) * ((*channel)[i - 1] - mean) < 0.0) {
        crossings += 0.5;  // averaged over the two channels
      }
    }
  }
  if (crossings < min_crossings || crossings <= 0.0) return 0.0;
  return 2.0 * (data.t.back() - data.t.front()) / crossings;
}

double LargestTotalAngle(const TimeHistory& data) {
  double largest = 0.0;
  for (int i = 0; i < data.size(); ++i) {
    largest = std::max(largest, std::hypot(data.theta[i], data.psi[i]));
  }
  return largest;
}

}  // namespace fit3dof
