// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Output files are written atomically: the text goes to a unique temporary
// file (mkstemp, NAME.tmp.XXXXXX) in the same directory, which is renamed
// over the target only when complete. A crash or a full disk never leaves a
// half-written report behind, and two threads writing beside each other
// never share a temporary.
//
// Only regular files and new paths are replaced: a symbolic link is
// followed (the file it names is written, the link stays), a character
// device or FIFO (/dev/null, /dev/stdout, a named pipe) is written through,
// and anything else (a directory, a socket) is refused.

#ifndef FIT3DOF_ATOMIC_FILE_H_
#define FIT3DOF_ATOMIC_FILE_H_

#include <string>

namespace fit3dof {

// Writes `content` to `path` as above; creates missing parent directories.
// Throws InputError naming the path when it cannot (exit status 2).
void WriteFileAtomically(const std::string& path, const std::string& content);

// True for the name of a temporary that WriteFileAtomically leaves behind
// only when the process is killed mid-write (NAME.tmp.XXXXXX).
bool IsTemporaryFileName(const std::string& name);

}  // namespace fit3dof

#endif  // FIT3DOF_ATOMIC_FILE_H_
