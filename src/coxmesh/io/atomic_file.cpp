// Atomic file replacement (temporary file + fsync + rename); see atomic_file.h.
#include "coxmesh/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>
#include <streambuf>
#include <vector>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

namespace {

[[noreturn]] void fail(const std::string& path, int error) {
  throw InputError("cannot write " + path + ": " + std::strerror(error));
}

// An output stream buffer on a POSIX file descriptor (64 KiB buffer); remembers the first errno.
class FdBuffer final : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd), buffer_(1 << 16) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!flush_buffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return flush_buffer() ? 0 : -1; }

 private:
  bool flush_buffer() {
    const char* p = pbase();
    std::size_t n = static_cast<std::size_t>(pptr() - pbase());
    while (n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0) {
        if (errno == EINTR) continue;
        if (!error_) error_ = errno;
        return false;
      }
      p += w;
      n -= static_cast<std::size_t>(w);
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return true;
  }

  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.filename().empty()) throw InputError("cannot write " + path + ": not a file name");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");

  // Create the temporary file next to the target (same file system, so rename is atomic).
  std::random_device entropy;
  std::string temp;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    std::string name = ".";
    name.append(target.filename().string()).append(".tmp-").append(std::to_string(entropy()));
    temp = (dir / name).string();
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) fail(path, errno);
  }
  if (fd < 0) fail(path, EEXIST);

  auto discard = [&] {
    if (fd >= 0) ::close(fd);
    ::unlink(temp.c_str());
  };
  try {
    FdBuffer buffer(fd);
    std::ostream os(&buffer);
    write(os);
    os.flush();
    if (!os) fail(path, buffer.error() ? buffer.error() : EIO);
    if (::fsync(fd) != 0) fail(path, errno);
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0) fail(path, errno);
    if (::rename(temp.c_str(), path.c_str()) != 0) fail(path, errno);
  } catch (...) {
    discard();
    throw;
  }
  // Make the rename itself durable; failure here does not undo a complete, renamed file.
  if (const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

void check_writable(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.filename().empty()) throw InputError("cannot write " + path + ": not a file name");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (fs::is_directory(target, ec)) fail(path, EISDIR);
  if (!fs::exists(dir, ec)) fail(path, ENOENT);
  if (!fs::is_directory(dir, ec)) fail(path, ENOTDIR);
  if (::access(dir.c_str(), W_OK | X_OK) != 0) fail(path, errno);
}

}  // namespace coxmesh
