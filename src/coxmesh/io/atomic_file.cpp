// Atomic file replacement (temporary file + fsync + rename); see atomic_file.h.
#include "coxmesh/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <random>
#include <streambuf>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

namespace {

[[noreturn]] void fail(const std::string& path, int error) {
  throw InputError("cannot write " + path + ": " + std::strerror(error));
}

// An output stream buffer on a POSIX file descriptor; remembers the first errno.
//
// A regular file about to be fsynced (`to_disk`) goes out, past its first buffer, with direct I/O
// (O_DIRECT): it must reach the disk anyway, so a copy in the page cache would only cost a copy
// of every byte into freshly allocated pages (slow to touch on virtual machines that hand freed
// memory back to their host) and evict what other programs cache. Direct I/O wants the buffer,
// the file offsets and the sizes aligned; kAlign covers every logical block size in use, and the
// unaligned tail is written last without it. A file system that refuses direct I/O gets buffered
// writes, a big block then going out in slices, each handed to the disk as soon as it is in the
// page cache, so that the writeback overlaps the rest of the writing instead of all waiting for
// the fsync.
class FdBuffer final : public std::streambuf {
 public:
  explicit FdBuffer(int fd, bool to_disk = false)
      : fd_(fd),
        to_disk_(to_disk),
        size_(to_disk ? kStagingBytes : kPlainBytes),
        buffer_(static_cast<char*>(std::aligned_alloc(kAlign, size_))) {
    if (!buffer_) throw std::bad_alloc();
    setp(buffer_.get(), buffer_.get() + size_);
  }
  int error() const { return error_; }
  // Writes every byte still held (the last, unaligned ones without direct I/O). Call once, last.
  bool finish() { return drain(true); }

 protected:
  int_type overflow(int_type c) override {
    if (to_disk_ && !direct_tried_) start_direct();
    if (!drain(false)) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  // (with direct I/O, up to kAlign - 1 bytes stay until more come or finish())
  int sync() override { return drain(false) ? 0 : -1; }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    const auto size = static_cast<std::size_t>(n);
    if (to_disk_ && !direct_tried_ && held() + size >= size_) start_direct();
    if (direct_ || size < size_) return std::streambuf::xsputn(s, n);
    // A block at least as big as the buffer goes to the file as it is, not through the buffer.
    if (!drain(true)) return 0;
    constexpr std::size_t kSlice = std::size_t{8} << 20;
    for (std::size_t done = 0; done < size;) {
      const std::size_t slice = to_disk_ ? std::min(kSlice, size - done) : size - done;
      if (!write_all(s + done, slice)) return 0;
      done += slice;
      // (a hint: an error here shows again at fsync)
      if (to_disk_) ::sync_file_range(fd_, written_ - slice, slice, SYNC_FILE_RANGE_WRITE);
    }
    return n;
  }

 private:
  static constexpr std::size_t kAlign = 4096;
  static constexpr std::size_t kStagingBytes = std::size_t{4} << 20;
  static constexpr std::size_t kPlainBytes = std::size_t{1} << 16;

  std::size_t held() const { return static_cast<std::size_t>(pptr() - pbase()); }

  void start_direct() {
    direct_tried_ = true;
    const int flags = ::fcntl(fd_, F_GETFL);
    direct_ = flags >= 0 && ::fcntl(fd_, F_SETFL, flags | O_DIRECT) == 0;
  }
  void stop_direct() {
    if (!direct_) return;
    direct_ = false;
    if (const int flags = ::fcntl(fd_, F_GETFL); flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_DIRECT);
  }

  // Writes the bytes held: with direct I/O only whole blocks unless `all`; the rest moves to the
  // front of the buffer (whose start stays aligned).
  bool drain(bool all) {
    const std::size_t n = held();
    std::size_t done = direct_ ? n / kAlign * kAlign : n;
    if (!write_all(pbase(), done)) return false;
    if (done < n && all) {
      stop_direct();
      if (!write_all(pbase() + done, n - done)) return false;
      done = n;
    }
    std::memmove(buffer_.get(), pbase() + done, n - done);
    setp(buffer_.get(), buffer_.get() + size_);
    pbump(static_cast<int>(n - done));
    return true;
  }
  bool write_all(const char* p, std::size_t n) {
    while (n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0) {
        if (errno == EINTR) continue;
        // (a file system may take O_DIRECT at fcntl and refuse a write; the same write buffered)
        if (errno == EINVAL && direct_) {
          stop_direct();
          continue;
        }
        if (!error_) error_ = errno;
        return false;
      }
      p += w;
      n -= static_cast<std::size_t>(w);
      written_ += w;
    }
    return true;
  }

  struct Free {
    void operator()(char* p) const { std::free(p); }
  };
  int fd_;
  bool to_disk_;
  bool direct_tried_ = false;
  bool direct_ = false;
  std::size_t size_;
  std::unique_ptr<char, Free> buffer_;
  off_t written_ = 0;  // (bytes written so far: the offset of the next)
  int error_ = 0;
};

// Writes straight to an open descriptor: standard output, or a file that cannot be replaced (a FIFO,
// a device such as /dev/null).
void write_to_descriptor(const std::string& path, int fd, const std::function<void(std::ostream&)>& write) {
  FdBuffer buffer(fd);
  std::ostream os(&buffer);
  write(os);
  if (!os || !buffer.finish()) fail(path, buffer.error() ? buffer.error() : EIO);
}

// The file a path names once every symbolic link is followed (it need not exist: a dangling link
// names the file to create). Replacing the link itself would cut it from its target.
std::filesystem::path follow_links(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  std::error_code ec;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    if (hops == 40) fail(path, ELOOP);
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) fail(path, ec.value());
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  return p;
}

bool is_special_file(const std::filesystem::path& p) {
  std::error_code ec;
  const auto status = std::filesystem::status(p, ec);
  return !ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
         !std::filesystem::is_directory(status);
}

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  if (path == "-") return write_to_descriptor(path, STDOUT_FILENO, write);
  const fs::path target = follow_links(path);
  if (target.filename().empty()) throw InputError("cannot write " + path + ": not a file name");
  if (is_special_file(target)) {
    const int fd = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) fail(path, errno);
    try {
      write_to_descriptor(path, fd, write);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0) fail(path, errno);
    return;
  }
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
    FdBuffer buffer(fd, true);
    std::ostream os(&buffer);
    write(os);
    if (!os || !buffer.finish()) fail(path, buffer.error() ? buffer.error() : EIO);
    if (::fsync(fd) != 0) fail(path, errno);
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0) fail(path, errno);
    if (::rename(temp.c_str(), target.c_str()) != 0) fail(path, errno);
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
  if (path == "-") return;
  const fs::path target = follow_links(path);
  if (target.filename().empty()) throw InputError("cannot write " + path + ": not a file name");
  if (is_special_file(target)) {
    if (::access(target.c_str(), W_OK) != 0) fail(path, errno);
    return;
  }
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (fs::is_directory(target, ec)) fail(path, EISDIR);
  if (!fs::exists(dir, ec)) fail(path, ENOENT);
  if (!fs::is_directory(dir, ec)) fail(path, ENOTDIR);
  if (::access(dir.c_str(), W_OK | X_OK) != 0) fail(path, errno);
}

}  // namespace coxmesh
