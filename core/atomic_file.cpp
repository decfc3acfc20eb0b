#include "atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "interrupt_cleanup.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

std::string system_reason(int error) {
  return std::generic_category().message(error);
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
  std::filesystem::path temporary = path;
  temporary += ".partial";
  // POSIX calls rather than a stream: their errno says why (ENOSPC, EFBIG, EIO) and close() is
  // checked, where a delayed write error may be the only sign.
  const InterruptCleanup temporary_on_interrupt = InterruptCleanup::remove_path(temporary);
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError(path.string(), "cannot create: " + system_reason(errno));
  auto fail = [&](const std::string& what, int error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw OutputError(path.string(), what + ": " + system_reason(error));
  };
  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t written = ::write(fd, data, left);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      const int error = written < 0 ? errno : EIO;
      ::close(fd);
      fail("cannot write", error);
    }
    data += written;
    left -= std::size_t(written);
  }
  if (::close(fd) != 0) fail("cannot write (on close)", errno);
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) fail("cannot rename the temporary into place", ec.value());
}

}  // namespace shadowcts
