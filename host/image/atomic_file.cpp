#include "host/image/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include "host/image/image_io.h"
#include "host/util/error.h"

namespace gc {
namespace {

std::atomic<int> g_injected_errno{0};

std::string errno_text(int error) { return std::error_code(error, std::generic_category()).message(); }

// Closes on scope exit so every early throw releases the descriptor.
class Fd {
public:
    explicit Fd(int fd) : m_fd(fd) {}
    ~Fd()
    {
        if (m_fd >= 0) ::close(m_fd);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    int get() const { return m_fd; }
    // close() can report a deferred write error (NFS, quota): check it, don't drop it.
    int close()
    {
        const int r = ::close(m_fd);
        m_fd = -1;
        return r;
    }

private:
    int m_fd;
};

}  // namespace

void image_io_testing::fail_next_write(int error) { g_injected_errno = error; }

namespace detail {

std::string cannot_write(const std::filesystem::path& target)
{
    return "cannot write image '" + target.string() + "': ";
}

std::filesystem::path temp_path_for(const std::filesystem::path& target)
{
    std::filesystem::path tmp = target;
    tmp += ".tmp-" + std::to_string(::getpid());
    return tmp;
}

void write_bytes(const std::filesystem::path& path, std::string_view bytes, const std::filesystem::path& target)
{
    Fd fd(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
    if (fd.get() < 0) throw OutputError(cannot_write(target) + "cannot create '" + path.string() + "': " + errno_text(errno));
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd.get(), bytes.data() + done, bytes.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw OutputError(cannot_write(target) + errno_text(errno));
        }
        done += size_t(n);
    }
    if (fd.close() != 0) throw OutputError(cannot_write(target) + errno_text(errno));
}

void replace_file_atomically(const std::filesystem::path& target,
                             const std::function<void(const std::filesystem::path& tmp)>& write_tmp)
{
    const std::filesystem::path tmp = temp_path_for(target);
    try {
        write_tmp(tmp);
        Fd fd(::open(tmp.c_str(), O_RDONLY | O_CLOEXEC));
        if (fd.get() < 0) throw OutputError(cannot_write(target) + "temp file vanished: " + errno_text(errno));
        if (const int injected = g_injected_errno.exchange(0); injected != 0)
            throw OutputError(cannot_write(target) + errno_text(injected) + " (injected by a test)");
        // Data on disk before the rename makes it visible: otherwise a crash could leave
        // the new name pointing at an empty file (the ext4 delayed-allocation lesson).
        if (::fsync(fd.get()) != 0) throw OutputError(cannot_write(target) + errno_text(errno));
        fd.close();
        if (::rename(tmp.c_str(), target.c_str()) != 0) throw OutputError(cannot_write(target) + errno_text(errno));
    } catch (...) {
        ::unlink(tmp.c_str());
        throw;
    }
    // Best effort: persist the directory entry. A failure here cannot undo the rename.
    std::filesystem::path dir = target.parent_path();
    if (dir.empty()) dir = ".";
    Fd dfd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (dfd.get() >= 0) ::fsync(dfd.get());
}

}  // namespace detail
}  // namespace gc
