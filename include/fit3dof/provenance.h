// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Where a result came from, recorded in report.json so that a coefficient
// can be traced a year later: the fit3dof version, the config, each data
// file with its SHA-256 (the same digest `sha256sum` prints), when and by
// which command line.
//
// Example Usage:
//
//   SetCommandLine(argc, argv);  // once, in main
//   FitResult r = Fit(c);        // r.provenance filled from c
//   // report.json: "provenance": {"fit3dof_version": "0.2.0", ...}

#ifndef FIT3DOF_PROVENANCE_H_
#define FIT3DOF_PROVENANCE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "fit3dof/case.h"

namespace fit3dof {

struct DataFileRecord {
  std::string path;    // absolute
  std::string sha256;  // lowercase hex; empty when the file cannot be read
  std::int64_t bytes = 0;
};

// (report.json adds the version, FIT3DOF_VERSION of fit3dof/version.h.)
struct Provenance {
  std::string config;                // the config's path (Case::source)
  std::vector<DataFileRecord> data;  // one per distinct data file, in order
  std::string date;                  // UTC, ISO 8601 (2026-11-23T05:41:07Z)
  std::string command_line;          // as SetCommandLine recorded it
};

// The process's command line as reports quote it (arguments joined by
// spaces, each quoted when it holds a space or a quote). The Python module
// records its own call ("python3: fit3dof.fit(...)").
void SetCommandLine(int argc, const char* const* argv);
void SetCommandLine(const std::string& text);
std::string CommandLine();

// The provenance of a fit of `c` now: every segment's data file hashed.
Provenance ProvenanceOf(const Case& c);

// SHA-256 of a file's bytes as lowercase hex (OpenSSL); false when the file
// cannot be read.
bool Sha256OfFile(const std::string& path,
                  std::string* hex,
                  std::int64_t* bytes);

}  // namespace fit3dof

#endif  // FIT3DOF_PROVENANCE_H_
