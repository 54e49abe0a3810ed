#include "stereo_io/output.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "quoted.hpp"

namespace stereo::io {
namespace fs = std::filesystem;
namespace {

// The output layer names paths in double quotes.
std::string quoted(const fs::path& path) {
    return detail::quoted(path, '"');
}

[[noreturn]] void fail_write(const fs::path& path, const std::string& reason) {
    throw std::runtime_error("cannot write " + quoted(path) + ": " + reason);
}

[[noreturn]] void fail_write_errno(const fs::path& path) {
    fail_write(path, std::strerror(errno));
}

fs::path folder_of(const fs::path& path) {
    return path.parent_path().empty() ? fs::path(".") : path.parent_path();
}

// ---- temporary names ----------------------------------------------------------------------

constexpr std::size_t kNameMax = 255;  // bytes of one path component (Linux file systems)
constexpr std::size_t kRandom = 6;     // mkstemp's XXXXXX

std::string read_small_file(const char* path) {
    std::ifstream in(path, std::ios::binary);
    std::string text;
    std::getline(in, text);
    return text;
}

// This machine's tag, the same for every process of one boot, PID namespace and host name:
// a temporary carrying it and a PID that is no live process here was left by a dead process.
const std::string& machine_tag() {
    static const std::string tag = [] {
        std::string key = read_small_file("/proc/sys/kernel/random/boot_id");
        struct stat ns {};
        if (::stat("/proc/self/ns/pid", &ns) == 0) {
            key += '/';
            key += std::to_string(ns.st_dev);
            key += ':';
            key += std::to_string(ns.st_ino);
        }
        std::array<char, 256> host{};
        if (::gethostname(host.data(), host.size() - 1) == 0) {
            key += "/";
            key += host.data();
        }
        std::uint32_t hash = 2166136261U;  // FNV-1a: a tag, not a secret
        for (const char c : key) {
            hash = (hash ^ static_cast<unsigned char>(c)) * 16777619U;
        }
        char text[9];
        std::snprintf(text, sizeof text, "%08x", hash);
        return std::string(text);
    }();
    return tag;
}

// ".NAME.PID-TAG." for a destination named `name`; mkstemp's XXXXXX follows. NAME is cut so
// that the whole name fits in one path component: a legal 250-byte output name stays legal.
std::string temporary_prefix(const std::string& name) {
    std::string tail = ".";
    tail += std::to_string(::getpid());
    tail += '-';
    tail += machine_tag();
    tail += '.';
    const std::size_t room = kNameMax - 1 - tail.size() - kRandom;
    std::string prefix = ".";
    prefix += name.substr(0, std::min(name.size(), room));
    prefix += tail;
    return prefix;
}

// The PID of a temporary of this machine (".NAME.PID-TAG.XXXXXX"), nothing for another name.
std::optional<pid_t> temporary_pid(std::string_view name) {
    const std::string& tag = machine_tag();
    if (name.size() < 1 + 1 + 1 + 1 + tag.size() + 1 + kRandom || name.front() != '.') {
        return std::nullopt;
    }
    const std::string_view random = name.substr(name.size() - kRandom);
    if (!std::all_of(random.begin(), random.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; })) {
        return std::nullopt;
    }
    std::string_view rest = name.substr(0, name.size() - kRandom);  // ".NAME.PID-TAG."
    if (rest.back() != '.') {
        return std::nullopt;
    }
    rest.remove_suffix(1);
    if (rest.size() < tag.size() + 1 || rest.substr(rest.size() - tag.size()) != tag) {
        return std::nullopt;
    }
    rest.remove_suffix(tag.size());
    if (rest.back() != '-') {
        return std::nullopt;
    }
    rest.remove_suffix(1);
    const std::size_t dot = rest.rfind('.');
    if (dot == std::string_view::npos || dot == 0) {
        return std::nullopt;
    }
    const std::string_view digits = rest.substr(dot + 1);
    if (digits.empty() || digits.size() > 10 ||
        !std::all_of(digits.begin(), digits.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; })) {
        return std::nullopt;
    }
    const long long pid = std::stoll(std::string(digits));
    if (pid <= 0 || pid > INT_MAX) {
        return std::nullopt;
    }
    return static_cast<pid_t>(pid);
}

// The process's umask without changing it (umask(2) can only be read by setting it, which would
// race with other threads creating files): /proc/self/status, else the set-and-restore.
mode_t process_umask() {
    static const mode_t mask = [] {
        std::ifstream status("/proc/self/status");
        for (std::string line; std::getline(status, line);) {
            if (line.rfind("Umask:", 0) == 0) {
                return static_cast<mode_t>(std::stoul(line.substr(6), nullptr, 8));
            }
        }
        const mode_t old = ::umask(0);
        ::umask(old);
        return old;
    }();
    return mask;
}

// ---- the live temporaries, removable from a signal handler -------------------------------

// One slot per temporary that exists now (or is being created). The signal handlers read the
// slots without locks: a state and a fixed path buffer, no allocation.
constexpr int kSlots = 256;
enum SlotState : int { kFree = 0, kClaimed = 1, kLive = 2 };
struct Slot {
    std::atomic<int> state{kFree};
    bool folder = false;
    char path[PATH_MAX] = {};
};
Slot g_slots[kSlots];

// Claims a slot whose buffer holds `pattern` (a mkstemp/mkdtemp template, absolute); the caller
// creates the temporary in the buffer itself (slot_path), so that a signal arriving at any moment
// finds its name. Throws when the path is too long or too many temporaries are live.
int claim_slot(const fs::path& destination, const std::string& pattern, bool folder) {
    if (pattern.size() >= PATH_MAX) {
        fail_write(destination, "the path is too long");
    }
    for (int i = 0; i < kSlots; ++i) {
        int expected = kFree;
        if (g_slots[i].state.compare_exchange_strong(expected, kClaimed)) {
            std::memcpy(g_slots[i].path, pattern.c_str(), pattern.size() + 1);
            g_slots[i].folder = folder;
            g_slots[i].state.store(kLive, std::memory_order_release);
            return i;
        }
    }
    fail_write(destination, "more than " + std::to_string(kSlots) + " files written at once");
}

char* slot_path(int slot) {
    return g_slots[slot].path;
}

void release_slot(int slot) {
    if (slot >= 0) {
        g_slots[slot].state.store(kFree, std::memory_order_release);
    }
}

// The temporary of a claimed slot could not be created (mkostemp, mkdtemp): releases the slot,
// sets it to -1 and throws the creation's error (errno kept across the release).
[[noreturn]] void fail_creating(int& slot, const fs::path& destination) {
    const int error = errno;
    release_slot(slot);
    slot = -1;
    errno = error;
    fail_write_errno(destination);
}

// Removes every entry of an open folder (files only: a private folder holds nothing else).
// Async-signal-safe: raw getdents64 and unlinkat, a buffer on the stack.
void empty_folder(int descriptor) noexcept {
    struct Entry {
        std::uint64_t inode;
        std::int64_t offset;
        unsigned short length;
        unsigned char type;
        char name[1];
    };
    alignas(8) char buffer[4096];
    for (int round = 0; round < 1000; ++round) {
        const long read = ::syscall(SYS_getdents64, descriptor, buffer, sizeof buffer);
        if (read <= 0) {
            return;
        }
        for (long at = 0; at < read;) {
            const auto* entry = reinterpret_cast<const Entry*>(buffer + at);
            at += entry->length;
            const char* name = entry->name;
            if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0) {
                ::unlinkat(descriptor, name, 0);
            }
        }
    }
}

// A private folder and what the library left in it. Async-signal-safe.
void remove_folder_now(const char* path) noexcept {
    const int descriptor = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (descriptor >= 0) {
        empty_folder(descriptor);
        ::close(descriptor);
    }
    ::rmdir(path);
}

void remove_live_temporaries() noexcept {
    for (Slot& slot : g_slots) {
        if (slot.state.load(std::memory_order_acquire) == kLive) {
            if (slot.folder) {
                remove_folder_now(slot.path);
            } else {
                ::unlink(slot.path);
            }
        }
    }
}

// ---- signals --------------------------------------------------------------------------------

// The signals whose default action ends the process and that a process can catch (SIGPIPE and
// SIGXFSZ are ignored instead, SIGBUS has its own handler).
constexpr std::array kTerminating = {SIGHUP,  SIGINT,    SIGQUIT, SIGTERM, SIGALRM, SIGUSR1,
                                     SIGUSR2, SIGVTALRM, SIGPROF, SIGXCPU, SIGPWR};

int g_stderr = STDERR_FILENO;  // a duplicate: descriptor 2 may point at /dev/null for a moment
char g_bus_message[512];
std::size_t g_bus_length = 0;

extern "C" void on_terminating_signal(int signal_number) {
    const int saved = errno;
    remove_live_temporaries();
    // The default action, taken when the handler returns (the signal is blocked until then):
    // the process ends by this signal, as it would have without the handler.
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    ::sigaction(signal_number, &default_action, nullptr);
    ::raise(signal_number);
    errno = saved;
}

extern "C" void on_bus_error(int) {
    remove_live_temporaries();
    if (g_bus_length > 0) {
        const ssize_t ignored = ::write(g_stderr, g_bus_message, g_bus_length);
        (void)ignored;
    }
    ::_exit(1);
}

// ---- files the process read ---------------------------------------------------------------

using Identity = std::pair<dev_t, ino_t>;

std::optional<Identity> identity_of(const fs::path& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) {
        return std::nullopt;
    }
    return Identity{status.st_dev, status.st_ino};
}

std::atomic<bool> g_guard_reads{false};
std::mutex g_reads_mutex;
std::map<Identity, fs::path> g_reads;

// The last line of defence: a write that would replace a file this process read.
void refuse_if_read(const fs::path& destination) {
    if (!g_guard_reads.load()) {
        return;
    }
    const auto identity = identity_of(destination);
    if (!identity) {
        return;
    }
    const std::lock_guard lock(g_reads_mutex);
    const auto found = g_reads.find(*identity);
    if (found != g_reads.end()) {
        throw std::invalid_argument("output " + quoted(destination) + " is " +
                                    quoted(found->second) +
                                    ", a file this command read: refusing to replace it");
    }
}

// ---- staging -------------------------------------------------------------------------------

std::mutex g_swept_mutex;
std::set<Identity> g_swept;

// sweep_stale_temporaries once per folder and process.
void sweep_once(const fs::path& folder) {
    const auto identity = identity_of(folder);
    if (!identity) {
        return;
    }
    {
        const std::lock_guard lock(g_swept_mutex);
        if (!g_swept.insert(*identity).second) {
            return;
        }
    }
    sweep_stale_temporaries(folder);
}

// Refuses a destination the rename must not replace.
void check_destination(const fs::path& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) == 0) {
        if (S_ISDIR(status.st_mode)) {
            fail_write(path, "is a directory");
        }
        // The rename would replace a device (/dev/null), FIFO or socket with a regular file.
        if (!S_ISREG(status.st_mode)) {
            fail_write(path, "not a regular file");
        }
        if (::access(path.c_str(), W_OK) != 0) {
            fail_write_errno(path);
        }
    }
    refuse_if_read(path);
}

// The folder's entry made durable (best effort: not every file system syncs folders).
void sync_folder(const fs::path& folder) {
    const int descriptor = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (descriptor >= 0) {
        ::fsync(descriptor);
        ::close(descriptor);
    }
}

// A hidden temporary file beside its destination (mkstemp: O_CREAT | O_EXCL, mode 0600, then
// the mode a new file normally gets), listed among the live temporaries until it is renamed or
// removed.
class TemporaryFile {
  public:
    explicit TemporaryFile(const fs::path& destination) : destination_(destination) {
        const fs::path folder = fs::absolute(folder_of(destination));
        sweep_once(folder);
        const std::string pattern =
            (folder / (temporary_prefix(destination.filename().string()) + "XXXXXX")).string();
        slot_ = claim_slot(destination, pattern, false);
        descriptor_ = ::mkostemp(slot_path(slot_), O_CLOEXEC);
        if (descriptor_ < 0) {
            fail_creating(slot_, destination);
        }
        path_ = slot_path(slot_);
        ::fchmod(descriptor_, 0666 & ~process_umask());
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    ~TemporaryFile() {
        if (descriptor_ >= 0) {
            ::close(descriptor_);
        }
        if (slot_ >= 0) {
            ::unlink(path_.c_str());
            release_slot(slot_);
        }
    }

    // Every byte, or an error: a short write is retried, and a write that fails (ENOSPC, EFBIG
    // with SIGXFSZ ignored, EIO) or makes no progress is reported.
    void write_all(std::string_view bytes) {
        const char* data = bytes.data();
        std::size_t left = bytes.size();
        while (left > 0) {
            const ssize_t written = ::write(descriptor_, data, left);
            if (written < 0) {
                if (errno == EINTR) {
                    continue;
                }
                fail_write_errno(destination_);
            }
            if (written == 0) {
                fail_write(destination_, "the write made no progress");
            }
            data += written;
            left -= static_cast<std::size_t>(written);
        }
    }

    void sync_and_close() {
        if (::fsync(descriptor_) != 0) {
            fail_write_errno(destination_);
        }
        const int result = ::close(descriptor_);
        descriptor_ = -1;
        if (result != 0) {
            fail_write_errno(destination_);
        }
    }

    void rename_over_destination() {
        refuse_if_read(destination_);
        if (::rename(path_.c_str(), destination_.c_str()) != 0) {
            fail_write_errno(destination_);
        }
        release_slot(slot_);
        slot_ = -1;
        sync_folder(folder_of(destination_));
    }

  private:
    fs::path destination_;
    fs::path path_;
    int slot_ = -1;
    int descriptor_ = -1;
};

// The bytes in a synced temporary file beside `path`, ready to be renamed over it.
std::unique_ptr<TemporaryFile> stage(const fs::path& path, std::string_view bytes) {
    check_destination(path);
    auto temporary = std::make_unique<TemporaryFile>(path);
    temporary->write_all(bytes);
    temporary->sync_and_close();
    return temporary;
}

std::string lower_extension(const fs::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

// ---- the structure of files written by libraries ------------------------------------------

class OpenFile {
  public:
    // Throws as a failed write of `name` (the output being checked) when `path` cannot be opened.
    OpenFile(const fs::path& path, const fs::path& name)
        : descriptor_(::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC)) {
        if (descriptor_ < 0) {
            fail_write_errno(name);
        }
        struct stat status {};
        if (::fstat(descriptor_, &status) == 0) {
            size_ = static_cast<std::uint64_t>(status.st_size);
        }
    }
    OpenFile(const OpenFile&) = delete;
    OpenFile& operator=(const OpenFile&) = delete;
    ~OpenFile() {
        if (descriptor_ >= 0) {
            ::close(descriptor_);
        }
    }
    std::uint64_t size() const { return size_; }
    // `count` bytes at `offset`, or false when the file ends before them.
    bool read(std::uint64_t offset, unsigned char* out, std::size_t count) const {
        while (count > 0) {
            const ssize_t got = ::pread(descriptor_, out, count, static_cast<off_t>(offset));
            if (got < 0 && errno == EINTR) {
                continue;
            }
            if (got <= 0) {
                return false;
            }
            out += got;
            offset += static_cast<std::uint64_t>(got);
            count -= static_cast<std::size_t>(got);
        }
        return true;
    }

  private:
    int descriptor_;
    std::uint64_t size_ = 0;
};

std::uint64_t big_endian64(const unsigned char* bytes) {
    std::uint64_t value = 0;
    for (int i = 0; i < 8; ++i) {
        value = (value << 8) | bytes[i];
    }
    return value;
}

std::uint32_t little_endian32(const unsigned char* bytes) {
    return static_cast<std::uint32_t>(bytes[0]) | static_cast<std::uint32_t>(bytes[1]) << 8 |
           static_cast<std::uint32_t>(bytes[2]) << 16 | static_cast<std::uint32_t>(bytes[3]) << 24;
}

[[noreturn]] void incomplete(const fs::path& name, const std::string& what,
                             const std::string& why) {
    fail_write(name, "the " + what + " writer did not write all of it (" + why +
                         "; is the disk full, or a file-size limit reached?)");
}

// ---- checks before the work ----------------------------------------------------------------

constexpr std::size_t kMaxFolderEntries = 1000000;
constexpr int kMaxFolderDepth = 64;

// Every file and folder a command reads, by identity.
struct InputIndex {
    std::map<Identity, fs::path> files;    // -> how the command names it
    std::map<Identity, fs::path> folders;  // -> the input folder it belongs to
    std::vector<fs::path> missing;         // named inputs that do not exist (yet)
    std::size_t entries = 0;
};

void walk(const fs::path& folder, const fs::path& input, InputIndex& index, int depth) {
    const auto identity = identity_of(folder);
    if (!identity || !index.folders.emplace(*identity, input).second) {
        return;  // gone, or seen already (a link back up the tree)
    }
    std::error_code error;
    for (fs::directory_iterator entry(folder, fs::directory_options::skip_permission_denied, error),
         end;
         !error && entry != end; entry.increment(error)) {
        if (++index.entries > kMaxFolderEntries) {
            throw std::invalid_argument("input folder " + quoted(input) + " holds more than " +
                                        std::to_string(kMaxFolderEntries) +
                                        " entries: refusing to list it");
        }
        struct stat status {};
        if (::stat(entry->path().c_str(), &status) != 0) {
            continue;  // a dangling link: nothing to read
        }
        if (S_ISDIR(status.st_mode)) {
            if (depth < kMaxFolderDepth) {
                walk(entry->path(), input, index, depth + 1);
            }
        } else {
            index.files.emplace(Identity{status.st_dev, status.st_ino}, entry->path());
        }
    }
}

fs::path resolved(const fs::path& path) {
    std::error_code error;
    return fs::weakly_canonical(fs::absolute(path), error);
}

// The file a path names, for comparison: its identity when it exists, else the resolved path.
bool same_file(const fs::path& a, const fs::path& b) {
    const auto first = identity_of(a);
    const auto second = identity_of(b);
    if (first && second) {
        return *first == *second;
    }
    return resolved(a) == resolved(b);
}

// The input folder `output` would be created in, if any: the nearest existing folder above it.
std::optional<fs::path> enclosing_input_folder(const fs::path& output, const InputIndex& index) {
    std::error_code error;
    fs::path location = fs::absolute(output, error).parent_path();
    while (!location.empty()) {
        if (const auto identity = identity_of(location)) {
            const auto found = index.folders.find(*identity);
            if (found != index.folders.end()) {
                return found->second;
            }
            return std::nullopt;
        }
        if (location == location.root_path()) {
            break;
        }
        location = location.parent_path();
    }
    return std::nullopt;
}

}  // namespace

// ---- public ---------------------------------------------------------------------------------

void install_process_guards(std::string_view program) {
    static std::once_flag once;
    std::call_once(once, [program] {
        const int duplicate = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3);
        g_stderr = duplicate >= 0 ? duplicate : STDERR_FILENO;
        const std::string message =
            std::string(program) +
            ": error: a memory-mapped file could not be read or written (bus error: is the disk "
            "full, or a file-size limit reached?)\n";
        g_bus_length = std::min(message.size(), sizeof g_bus_message);
        std::memcpy(g_bus_message, message.data(), g_bus_length);
        machine_tag();    // computed now, not in the middle of a write
        process_umask();  // likewise

        struct sigaction ignore {};
        ignore.sa_handler = SIG_IGN;
        sigemptyset(&ignore.sa_mask);
        ::sigaction(SIGXFSZ, &ignore, nullptr);
        ::sigaction(SIGPIPE, &ignore, nullptr);

        struct sigaction cleanup {};
        cleanup.sa_handler = on_terminating_signal;
        sigfillset(&cleanup.sa_mask);  // one handler at a time
        for (const int signal_number : kTerminating) {
            struct sigaction current {};
            if (::sigaction(signal_number, nullptr, &current) == 0 &&
                (current.sa_flags & SA_SIGINFO) == 0 && current.sa_handler == SIG_DFL) {
                ::sigaction(signal_number, &cleanup, nullptr);
            }
        }
        struct sigaction bus {};
        bus.sa_handler = on_bus_error;
        sigfillset(&bus.sa_mask);
        struct sigaction current {};
        if (::sigaction(SIGBUS, nullptr, &current) == 0 && (current.sa_flags & SA_SIGINFO) == 0 &&
            current.sa_handler == SIG_DFL) {  // not over a sanitizer's or fuzzer's own handler
            ::sigaction(SIGBUS, &bus, nullptr);
        }
        g_guard_reads.store(true);
    });
}

void note_input_read(const fs::path& path) {
    if (!g_guard_reads.load()) {
        return;
    }
    if (const auto identity = identity_of(path)) {
        const std::lock_guard lock(g_reads_mutex);
        g_reads.emplace(*identity, path);
    }
}

int sweep_stale_temporaries(const fs::path& folder) {
    const int descriptor =
        ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (descriptor < 0) {
        return 0;
    }
    DIR* listing = ::fdopendir(descriptor);
    if (listing == nullptr) {
        ::close(descriptor);
        return 0;
    }
    int removed = 0;
    while (const dirent* entry = ::readdir(listing)) {
        const auto pid = temporary_pid(entry->d_name);
        if (!pid || *pid == ::getpid()) {
            continue;
        }
        // Only a process that does not exist: EPERM means it lives (as another user).
        if (::kill(*pid, 0) == 0 || errno != ESRCH) {
            continue;
        }
        struct stat status {};
        if (::fstatat(descriptor, entry->d_name, &status, AT_SYMLINK_NOFOLLOW) != 0 ||
            status.st_uid != ::geteuid()) {
            continue;
        }
        if (S_ISDIR(status.st_mode)) {
            const int inside = ::openat(descriptor, entry->d_name,
                                        O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            if (inside >= 0) {
                empty_folder(inside);
                ::close(inside);
            }
            removed += ::unlinkat(descriptor, entry->d_name, AT_REMOVEDIR) == 0 ? 1 : 0;
        } else {
            removed += ::unlinkat(descriptor, entry->d_name, 0) == 0 ? 1 : 0;
        }
    }
    ::closedir(listing);
    return removed;
}

StagedOutput::StagedOutput(const fs::path& destination) : destination_(destination) {
    check_destination(destination);
    const fs::path folder = fs::absolute(folder_of(destination));
    sweep_once(folder);
    const std::string name = destination.filename().string();
    slot_ = claim_slot(destination, (folder / (temporary_prefix(name) + "XXXXXX")).string(), true);
    if (::mkdtemp(slot_path(slot_)) == nullptr) {
        fail_creating(slot_, destination);
    }
    folder_ = slot_path(slot_);
    // Inside the private folder: ".STEM.XXXXXX.EXT", the destination's extension kept last
    // (the writer may choose its format by it).
    const std::string random = folder_.string().substr(folder_.string().size() - kRandom);
    std::string stem = destination.stem().string().substr(0, 64);
    std::string extension = destination.extension().string();
    if (extension.size() > 32) {
        extension.clear();
    }
    std::string inner = ".";
    inner += stem;
    inner += '.';
    inner += random;
    inner += extension;
    temporary_ = folder_ / inner;
}

StagedOutput::~StagedOutput() {
    if (!folder_.empty()) {
        remove_folder_now(folder_.c_str());
    }
    release_slot(slot_);
}

void StagedOutput::commit() {
    if (folder_.empty()) {
        throw std::logic_error("StagedOutput::commit called twice for " + quoted(destination_));
    }
    struct stat status {};
    if (::lstat(temporary_.c_str(), &status) != 0 || !S_ISREG(status.st_mode)) {
        fail_write(destination_, "the writer did not create the file");
    }
    const std::string extension = lower_extension(destination_);
    if (extension == ".fst") {
        check_fst_complete(temporary_, destination_);
    } else if (extension == ".avi") {
        check_avi_complete(temporary_, destination_);
    }
    // The writer closed the file; sync what it wrote before the rename makes it visible.
    const int descriptor = ::open(temporary_.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (descriptor < 0 || ::fsync(descriptor) != 0) {
        const int error = errno;
        if (descriptor >= 0) {
            ::close(descriptor);
        }
        errno = error;
        fail_write_errno(destination_);
    }
    ::close(descriptor);
    refuse_if_read(destination_);
    if (::rename(temporary_.c_str(), destination_.c_str()) != 0) {
        fail_write_errno(destination_);
    }
    remove_folder_now(folder_.c_str());  // what the writer left beside the file
    folder_.clear();
    release_slot(slot_);
    slot_ = -1;
    sync_folder(folder_of(destination_));
}

void check_fst_complete(const fs::path& file, const fs::path& name) {
    // fstapi's layout: blocks of [type: 1 byte][length: 8 bytes, big-endian, counting itself]
    // [payload], the header block first; its field at offset 65 counts the value-change blocks.
    constexpr int kHeader = 0;
    constexpr int kValueChanges = 1;
    constexpr int kGeometry = 3;
    constexpr int kHierarchy = 4;
    constexpr int kValueChangesAlias = 5;
    constexpr int kHierarchyLz4 = 6;
    constexpr int kHierarchyLz4Duo = 7;
    constexpr int kValueChangesAlias2 = 8;
    constexpr int kBeingWritten = 255;  // FST_BL_SKIP
    constexpr std::uint64_t kSectionCountAt = 65;
    const OpenFile in(file, name);
    const std::string what = "FST";
    std::array<unsigned char, 9> block{};
    std::uint64_t at = 0;
    std::uint64_t value_blocks = 0;
    bool geometry = false;
    bool hierarchy = false;
    while (at < in.size()) {
        if (!in.read(at, block.data(), block.size())) {
            incomplete(name, what, "a block header is cut off at byte " + std::to_string(at));
        }
        const int type = block[0];
        const std::uint64_t length = big_endian64(block.data() + 1);
        if (at == 0 && type != kHeader) {
            incomplete(name, what, "no FST header");
        }
        if (type == kBeingWritten) {
            incomplete(name, what, "a block was never finished");
        }
        if (type > kValueChangesAlias2 || (type == kHeader && at != 0)) {
            incomplete(name, what, "an unknown block at byte " + std::to_string(at));
        }
        if (length < 8 || length > in.size() - at - 1) {
            incomplete(name, what, "a block runs past the end of the file");
        }
        value_blocks +=
            type == kValueChanges || type == kValueChangesAlias || type == kValueChangesAlias2;
        geometry = geometry || type == kGeometry;
        hierarchy =
            hierarchy || type == kHierarchy || type == kHierarchyLz4 || type == kHierarchyLz4Duo;
        at += 1 + length;
    }
    std::array<unsigned char, 8> count{};
    if (!in.read(kSectionCountAt, count.data(), count.size())) {
        incomplete(name, what, "the header is cut off");
    }
    if (big_endian64(count.data()) != value_blocks) {
        incomplete(name, what,
                   "the header counts " + std::to_string(big_endian64(count.data())) +
                       " value-change blocks, the file holds " + std::to_string(value_blocks));
    }
    if (!geometry || !hierarchy) {
        incomplete(name, what, "no geometry or hierarchy block");
    }
}

void check_avi_complete(const fs::path& file, const fs::path& name) {
    // RIFF: chunks of ["RIFF"][length: 4 bytes, little-endian][form: "AVI " first, then "AVIX"
    // (OpenDML)][length - 4 bytes], padded to even, one after another to the end of the file.
    const OpenFile in(file, name);
    const std::string what = "AVI";
    std::array<unsigned char, 12> chunk{};
    std::uint64_t at = 0;
    while (at < in.size()) {
        if (!in.read(at, chunk.data(), chunk.size())) {
            incomplete(name, what, "a chunk header is cut off at byte " + std::to_string(at));
        }
        const std::string id(reinterpret_cast<const char*>(chunk.data()), 4);
        const std::string form(reinterpret_cast<const char*>(chunk.data()) + 8, 4);
        if (id != "RIFF" || form != (at == 0 ? "AVI " : "AVIX")) {
            incomplete(name, what, "no RIFF AVI chunk at byte " + std::to_string(at));
        }
        const std::uint64_t length = little_endian32(chunk.data() + 4);
        const std::uint64_t end = at + 8 + length + (length & 1);
        if (length < 4 || end > in.size() + (length & 1)) {
            incomplete(name, what, "a chunk runs past the end of the file");
        }
        at = std::min(end, in.size());
    }
    if (in.size() == 0) {
        incomplete(name, what, "the file is empty");
    }
}

void write_file_atomic(const fs::path& path, std::string_view bytes) {
    const auto temporary = stage(path, bytes);
    temporary->rename_over_destination();
}

void write_files_atomic(const std::vector<std::pair<fs::path, std::string>>& files) {
    std::vector<std::unique_ptr<TemporaryFile>> staged;
    staged.reserve(files.size());
    for (const auto& [path, bytes] : files) {
        staged.push_back(stage(path, bytes));  // a throw here removes every staged file
    }
    for (const auto& temporary : staged) {
        temporary->rename_over_destination();
    }
}

void check_can_stage(const fs::path& path) {
    const fs::path folder = folder_of(path);
    struct stat status {};
    if (::stat(folder.c_str(), &status) != 0 || !S_ISDIR(status.st_mode)) {
        fail_write(path, "folder " + quoted(folder) + " does not exist");
    }
    check_destination(path);
    // A temporary made and removed: the folder is writable and the temporary's name fits.
    const TemporaryFile probe(path);
}

void check_outputs(const std::vector<fs::path>& outputs, const Inputs& inputs) {
    InputIndex index;
    for (const fs::path& file : inputs.files) {
        if (file.empty()) {
            continue;
        }
        struct stat status {};
        if (::stat(file.c_str(), &status) != 0) {
            index.missing.push_back(file);
        } else if (S_ISDIR(status.st_mode)) {
            walk(file, file, index, 0);  // a folder named where a file may be: all it holds
        } else {
            index.files.emplace(Identity{status.st_dev, status.st_ino}, file);
        }
    }
    for (const fs::path& folder : inputs.folders) {
        if (!folder.empty()) {
            walk(folder, folder, index, 0);
        }
    }
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const fs::path& output = outputs[i];
        if (output.empty()) {
            continue;
        }
        const auto refuse = [&output](const fs::path& input) {
            throw std::invalid_argument("output " + quoted(output) + " is the input " +
                                        quoted(input) + ": refusing to overwrite it");
        };
        if (const auto identity = identity_of(output)) {
            const auto found = index.files.find(*identity);
            if (found != index.files.end()) {
                refuse(found->second);
            }
        }
        for (const fs::path& input : index.missing) {
            if (same_file(output, input)) {
                refuse(input);
            }
        }
        if (const auto folder = enclosing_input_folder(output, index)) {
            throw std::invalid_argument("output " + quoted(output) +
                                        " lies inside the input folder " + quoted(*folder) +
                                        ": refusing to write into a folder the command reads");
        }
        for (std::size_t j = i + 1; j < outputs.size(); ++j) {
            if (!outputs[j].empty() && same_file(output, outputs[j])) {
                throw std::invalid_argument("outputs " + quoted(output) + " and " +
                                            quoted(outputs[j]) + " are the same file");
            }
        }
    }
}

void check_outputs_distinct(const std::vector<fs::path>& outputs,
                            const std::vector<fs::path>& inputs) {
    check_outputs(outputs, Inputs{inputs, {}});
}

}  // namespace stereo::io
