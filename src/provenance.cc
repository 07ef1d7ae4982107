// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Provenance of a result (provenance.h).

#include "fit3dof/provenance.h"

#include <openssl/evp.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>

namespace fit3dof {
namespace {

std::mutex command_line_mutex;
std::string& CommandLineText() {
  static std::string text;
  return text;
}

std::string Quoted(const std::string& arg) {
  if (!arg.empty() && arg.find_first_of(" \t'\"\\") == std::string::npos) {
    return arg;
  }
  std::string out = "'";
  for (char ch : arg)
    out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc;
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace

void SetCommandLine(int argc, const char* const* argv) {
  std::string text;
  for (int i = 0; i < argc; ++i) {
    text += (i == 0 ? "" : " ") + Quoted(argv[i]);
  }
  SetCommandLine(text);
}

void SetCommandLine(const std::string& text) {
  std::lock_guard<std::mutex> lock(command_line_mutex);
  CommandLineText() = text;
}

std::string CommandLine() {
  std::lock_guard<std::mutex> lock(command_line_mutex);
  return CommandLineText();
}

bool Sha256OfFile(const std::string& path,
                  std::string* hex,
                  std::int64_t* bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(),
                                                              &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    return false;
  }
  char buffer[1 << 16];
  *bytes = 0;
  while (in) {
    in.read(buffer, sizeof(buffer));
    const std::streamsize n = in.gcount();
    if (n > 0) {
      EVP_DigestUpdate(ctx.get(), buffer, static_cast<size_t>(n));
      *bytes += n;
    }
  }
  if (in.bad()) return false;
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_DigestFinal_ex(ctx.get(), digest, &size) != 1) return false;
  static const char kHex[] = "0123456789abcdef";
  hex->clear();
  for (unsigned int i = 0; i < size; ++i) {
    *hex += kHex[digest[i] >> 4];
    *hex += kHex[digest[i] & 15];
  }
  return true;
}

Provenance ProvenanceOf(const Case& c) {
  Provenance p;
  if (!c.source.empty() && std::filesystem::exists(c.source)) {
    p.config = std::filesystem::absolute(c.source).lexically_normal().string();
  } else {
    p.config = c.source;
  }
  for (const Segment& s : c.segments) {
    if (s.data_file.empty()) continue;
    const std::string path =
        std::filesystem::absolute(s.data_file).lexically_normal().string();
    const bool seen =
        std::any_of(p.data.begin(), p.data.end(), [&](const DataFileRecord& r) {
          return r.path == path;
        });
    if (seen) continue;
    DataFileRecord record;
    record.path = path;
    if (!Sha256OfFile(path, &record.sha256, &record.bytes)) {
      record.sha256.clear();
      record.bytes = 0;
    }
    p.data.push_back(record);
  }
  p.date = UtcNow();
  p.command_line = CommandLine();
  return p;
}

}  // namespace fit3dof
