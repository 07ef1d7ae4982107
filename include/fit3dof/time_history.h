// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A record of measured (or simulated) angles against time, and its CSV
// form: a header line, required columns t, phi, theta, psi (seconds,
// degrees) in any order, other columns ignored, times strictly increasing.

#ifndef FIT3DOF_TIME_HISTORY_H_
#define FIT3DOF_TIME_HISTORY_H_

#include <functional>
#include <string>
#include <vector>

namespace fit3dof {

struct TimeHistory {
  std::vector<double> t;
  std::vector<double> phi;
  std::vector<double> theta;
  std::vector<double> psi;

  int size() const { return static_cast<int>(t.size()); }
  // Angle channel `ch`: 0 phi, 1 theta, 2 psi (ChannelValues' order).
  const std::vector<double>& channel(int ch) const;
  std::vector<double>& channel(int ch);
  void Append(double time, double phi_deg, double theta_deg, double psi_deg) {
    t.push_back(time);
    phi.push_back(phi_deg);
    theta.push_back(theta_deg);
    psi.push_back(psi_deg);
  }
};

// The name of angle channel `channel` (TimeHistory::channel's order):
// "phi", "theta" or "psi", as in the CSV header and the configs' keys.
const char* ChannelName(int channel);

// Reads a CSV record. Throws InputError naming the file and line for a
// missing column, a token that is not a whole finite decimal number (an
// empty field, "-", ".", "1.5e", "nan"; the message names the column and
// the token), non-increasing times or fewer than two rows. Fields may be
// double-quoted ("1.25", as pandas' QUOTE_ALL writes them).
TimeHistory ReadTimeHistory(const std::string& path);

// Reads the file row by row with the same checks and messages, passing each
// sample to `sink` instead of keeping it (a long record costs only what the
// sink keeps). Returns the number of rows.
using SampleSink =
    std::function<void(double t, double phi, double theta, double psi)>;
int ForEachSample(const std::string& path, const SampleSink& sink);

// The same from CSV text in memory; `source` names it in messages.
TimeHistory ParseTimeHistory(const std::string& text,
                             const std::string& source);

// The CSV text of a record (columns t, phi, theta, psi).
std::string FormatTimeHistory(const TimeHistory& history);

// Writes the CSV atomically.
void WriteTimeHistory(const std::string& path, const TimeHistory& history);

// A rough period of the angular motion (s): twice the record's length over
// the zero crossings of theta and psi about their means (averaged over the
// two channels); 0 when there are fewer than `min_crossings`. The
// continuation's first window and the epicyclic start's span use it.
double CrossingPeriod(const TimeHistory& data, double min_crossings);

// The largest total angle (deg) of the record's readings, sqrt(theta^2 +
// psi^2): the scale a bearing moment's fade and its bounds are set
// against.
double LargestTotalAngle(const TimeHistory& data);

}  // namespace fit3dof

#endif  // FIT3DOF_TIME_HISTORY_H_
