// Scene files through open/fstat/read: the file's type and size are known before reading, from the
// descriptor that is read (no window between a check and the open).
#include "scene_file_reading.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "penumbra/error.h"

namespace penumbra::scene {
namespace {

const char* fileTypeName(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

// Closes the descriptor on every way out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) close(fd);
  }
};

}  // namespace

std::optional<std::vector<uint8_t>> readSceneFile(const std::filesystem::path& path,
                                                  const std::string& what,
                                                  const std::string& source, MemoryBudget& budget) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
  const Descriptor file{open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) return std::nullopt;
  struct stat status {};
  if (fstat(file.fd, &status) != 0) return std::nullopt;
  if (!S_ISREG(status.st_mode)) {
    throw Error(source + ": " + what + " is not a regular file (" + path.string() + " is " +
                fileTypeName(status.st_mode) + "); a scene reads regular files only");
  }
  const uint64_t size = uint64_t(status.st_size);
  budget.addFile(source, what, size);
  std::vector<uint8_t> bytes(size);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = read(file.fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      throw Error(source + ": cannot read " + what + " (" + path.string() +
                  "): " + std::strerror(errno));
    }
    if (n == 0) break;  // shorter than fstat said: it shrank meanwhile
    done += size_t(n);
  }
  bytes.resize(done);  // a file that grows meanwhile is read to the size it had
  return bytes;
}

}  // namespace penumbra::scene
