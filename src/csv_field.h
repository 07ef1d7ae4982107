// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A text field of the CSV files fit3dof writes (fit.csv, summary.csv), as
// RFC 4180 has it: a field holding a comma, a double quote or a line break
// is enclosed in double quotes, with each double quote doubled. Python's csv
// module, pandas and spreadsheets read it back unchanged.

#ifndef FIT3DOF_SRC_CSV_FIELD_H_
#define FIT3DOF_SRC_CSV_FIELD_H_

#include <string>

namespace fit3dof {

inline std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_CSV_FIELD_H_
