// Atomic file replacement: every output file of coxmesh is written to a temporary file in the
// target's directory, flushed to disk, then renamed over the target, so a reader (or a crash)
// sees either the complete previous file or the complete new one, never a partial file.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace coxmesh {

/// Writes `path` atomically: `write` fills a binary stream on a temporary file
/// `<dir>/.<name>.tmp-<random>`, which is fsynced and renamed over `path` (then the directory is
/// fsynced). On any error — the directory is missing or unwritable, `write` throws, the stream
/// fails (disk full) — the temporary file is removed and the previous `path`, if any, is untouched.
/// The new file gets the mode 0666 minus the umask, like a plain open(). A symbolic link is
/// followed: its target is replaced atomically and the link stays. A file that cannot be replaced
/// (a FIFO, a device such as /dev/null) is written directly, and "-" means standard output.
///   Throws InputError naming the path for I/O failures; rethrows what `write` throws.
///
///   write_file_atomically("out.off", [&](std::ostream& os) { os << "OFF\n0 0 0\n"; });
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Checks, without creating anything, that a file can be created at `path`: its directory exists,
/// is a directory and is writable (access(2)), and `path` is not itself a directory. For an early,
/// cheap failure before long computations; write_file_atomically still reports the real errors.
///   Throws InputError naming the path.
void check_writable(const std::string& path);

}  // namespace coxmesh
