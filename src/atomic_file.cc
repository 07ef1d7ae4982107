// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Output files written whole or not at all (atomic_file.h): a temporary
// beside the target, renamed over it when complete.

#include "fit3dof/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "fit3dof/input_error.h"

namespace fit3dof {
namespace {

namespace fs = std::filesystem;

std::string Reason() { return std::strerror(errno); }

// Writes every byte to `fd`; false (errno set) on failure.
bool WriteAll(int fd, const std::string& content) {
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

// A character device (/dev/null, a terminal) or a FIFO: written through,
// never replaced.
void WriteThrough(const std::string& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot write: " + Reason());
  const bool ok = WriteAll(fd, content);
  const std::string reason = Reason();
  ::close(fd);
  if (!ok) throw InputError(path + ": write failed: " + reason);
}

// The new file goes to a unique temporary (mkstemp) beside the target and is
// renamed over it when complete; the temporary is removed on every failure.
void WriteAndRename(const std::string& path, const std::string& content) {
  std::vector<char> name(path.begin(), path.end());
  const std::string suffix = ".tmp.XXXXXX";
  name.insert(name.end(), suffix.begin(), suffix.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw InputError(path + ": cannot write: " + Reason());
  const std::string temporary(name.data());
  // mkstemp creates mode 0600; an output file gets the usual 0666 & ~umask.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  bool ok = ::fchmod(fd, 0666 & ~mask) == 0 && WriteAll(fd, content) &&
            ::fsync(fd) == 0;
  std::string reason = Reason();
  ok = (::close(fd) == 0) && ok;
  if (ok && std::rename(temporary.c_str(), path.c_str()) != 0) {
    ok = false;
    reason = "cannot rename into place: " + Reason();
  }
  if (!ok) {
    std::remove(temporary.c_str());
    throw InputError(path + ": write failed: " + reason);
  }
}

}  // namespace

void WriteFileAtomically(const std::string& path, const std::string& content) {
  fs::path target(path);
  std::error_code ec;
  // A symbolic link is followed: the file it names is written, the link
  // stays (a dangling link gets its target created).
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
    if (hops == 40) throw InputError(path + ": too many symbolic links");
    const fs::path link = fs::read_symlink(target, ec);
    if (ec) throw InputError(path + ": cannot read the link: " + ec.message());
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  const fs::file_status status = fs::status(target, ec);
  switch (status.type()) {
    case fs::file_type::not_found:
    case fs::file_type::regular:
      break;
    case fs::file_type::character:
    case fs::file_type::fifo:
      WriteThrough(target.string(), content);
      return;
    case fs::file_type::directory:
      throw InputError(path + ": is a directory (expected a file to write)");
    default:
      throw InputError(path +
                       ": exists and is not a regular file; refusing to "
                       "replace it");
  }
  if (target.has_parent_path()) {
    fs::create_directories(target.parent_path(), ec);
    if (ec) {
      throw InputError(path + ": cannot create directory " +
                       target.parent_path().string() + ": " + ec.message());
    }
  }
  WriteAndRename(target.string(), content);
}

bool IsTemporaryFileName(const std::string& name) {
  const size_t at = name.rfind(".tmp.");
  return at != std::string::npos && at > 0 && name.size() == at + 11;
}

}  // namespace fit3dof
