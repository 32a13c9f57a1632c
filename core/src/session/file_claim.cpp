#include "file_claim.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "palpa/session/session.hpp"

namespace palpa::session::detail {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kCreatingSuffix = ".creating";

bool exists_no_follow(const fs::path& p) {
  std::error_code ec;
  return fs::symlink_status(p, ec).type() != fs::file_type::not_found && !ec;
}

fs::path with_suffix(fs::path p, const char* suffix) {
  p += suffix;
  return p;
}

[[noreturn]] void fail(const fs::path& path, const std::string& reason) {
  throw SessionError(path.string(), "file", reason);
}

std::string folder_of(const fs::path& path) {
  return path.parent_path().empty() ? std::string(".") : path.parent_path().string();
}

// /proc/locks device field "MAJOR:MINOR:INODE" (major and minor in hex) for `st`.
bool same_file(std::string_view field, const struct stat& st) {
  const auto first = field.find(':');
  const auto second = field.find(':', first + 1);
  if (first == std::string_view::npos || second == std::string_view::npos) return false;
  unsigned major_id = 0, minor_id = 0;
  unsigned long long inode = 0;
  const auto parse = [](std::string_view text, auto& value, int base) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value, base);
    return ec == std::errc() && end == text.data() + text.size();
  };
  return parse(field.substr(0, first), major_id, 16) && parse(field.substr(first + 1, second - first - 1), minor_id, 16) &&
         parse(field.substr(second + 1), inode, 10) && major_id == major(st.st_dev) && minor_id == minor(st.st_dev) &&
         inode == static_cast<unsigned long long>(st.st_ino);
}

// The process id in a creating name ".NAME.PID.creating", or 0.
long creator_of(const std::string& entry, const std::string& prefix) {
  if (entry.size() <= prefix.size() + kCreatingSuffix.size() || entry.rfind(prefix, 0) != 0) return 0;
  const std::string_view rest(entry.data() + prefix.size(), entry.size() - prefix.size());
  if (rest.substr(rest.size() - kCreatingSuffix.size()) != kCreatingSuffix) return 0;
  const std::string_view digits = rest.substr(0, rest.size() - kCreatingSuffix.size());
  long pid = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
  return ec == std::errc() && end == digits.data() + digits.size() && pid > 0 ? pid : 0;
}

bool process_is_gone(long pid) { return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH; }

// The new name survives a power cut only once its folder is on disk too.
void sync_folder(const fs::path& path) {
  const int fd = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::optional<long> other_process_locking(const fs::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return std::nullopt;
  std::ifstream locks("/proc/locks");
  std::string line;
  const long self = static_cast<long>(::getpid());
  while (std::getline(locks, line)) {
    // "1: POSIX  ADVISORY  READ 2345 fe:00:10953801 128 128"; a waiter has "->" after the id.
    std::istringstream fields(line);
    std::string id, kind, mode, access, pid_text, device;
    fields >> id >> kind;
    if (kind == "->") fields >> kind;
    fields >> mode >> access >> pid_text >> device;
    if (!same_file(device, st)) continue;
    long pid = 0;
    const auto [end, ec] = std::from_chars(pid_text.data(), pid_text.data() + pid_text.size(), pid);
    if (ec == std::errc() && pid > 0 && pid != self) return pid;
  }
  return std::nullopt;
}

void refuse_taken_name(const fs::path& path) {
  if (exists_no_follow(path)) {
    if (const auto pid = other_process_locking(with_suffix(path, "-shm"))) {
      fail(path, fmt::format("already exists and another process (pid {}) has it open, recording into it or "
                             "reading it; choose a new name",
                             *pid));
    }
    fail(path, "already exists; recorded sessions are never overwritten, choose a new name");
  }
  for (const char* suffix : {"-wal", "-journal"}) {
    // A stale journal beside a new file would be replayed into it.
    const auto side = with_suffix(path, suffix);
    if (exists_no_follow(side)) {
      fail(path, "a leftover " + side.filename().string() +
                     " lies beside it (from an earlier session of that name); move it away first");
    }
  }
  std::error_code ec;
  const fs::path folder = folder_of(path);
  if (!fs::is_directory(folder, ec)) fail(path, "the folder " + folder.string() + " does not exist");
}

fs::path creating_path(const fs::path& path) {
  return path.parent_path() / fmt::format(".{}.{}{}", path.filename().string(), ::getpid(), kCreatingSuffix);
}

void remove_abandoned_creations(const fs::path& path) {
  std::string prefix = ".";  // built by appending: GCC 12 warns falsely on "." + string
  prefix += path.filename().string();
  prefix += ".";
  std::error_code ec;
  fs::directory_iterator it(folder_of(path), ec);
  if (ec) return;
  for (const auto& entry : it) {
    const std::string name = entry.path().filename().string();
    const long pid = creator_of(name, prefix);
    if (pid == 0 || !process_is_gone(pid)) continue;
    for (const char* suffix : {"-journal", "-wal", "-shm", ""}) fs::remove(with_suffix(entry.path(), suffix), ec);
  }
}

void create_exclusive(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd >= 0) {
    ::close(fd);
    return;
  }
  const int error = errno;
  if (error == EEXIST) fail(path, "already exists; recorded sessions are never overwritten, choose a new name");
  if (error == ENOENT) fail(path, "the folder " + folder_of(path) + " does not exist");
  fail(path, std::string("cannot create: ") + std::strerror(error));
}

void publish(const fs::path& built, const fs::path& path) {
  int error = 0;
  if (::renameat2(AT_FDCWD, built.c_str(), AT_FDCWD, path.c_str(), RENAME_NOREPLACE) == 0) {
    sync_folder(path);
    return;
  }
  error = errno;
  if (error == EINVAL || error == ENOSYS) {
    // A file system without RENAME_NOREPLACE: a hard link fails just as atomically on EEXIST.
    if (::link(built.c_str(), path.c_str()) == 0) {
      ::unlink(built.c_str());
      sync_folder(path);
      return;
    }
    error = errno;
  }
  if (error == EEXIST) {
    fail(path, "another process created a file of that name at the same moment; choose a new name");
  }
  fail(path, std::string("cannot give the new session its name: ") + std::strerror(error));
}

}  // namespace palpa::session::detail
