#include "stereo_io/output.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace stereo::io {
namespace fs = std::filesystem;
namespace {

std::string quoted(const fs::path& path) {
    return "\"" + path.string() + "\"";
}

// Creates the hidden file ".<name>.XXXXXX<suffix>" beside `destination` (the same folder, so a
// rename over the destination stays atomic) with the permissions a new file normally gets;
// returns its open descriptor and sets `created`.
int create_hidden_beside(const fs::path& destination, const std::string& name,
                         const std::string& suffix, fs::path& created) {
    const fs::path folder =
        destination.parent_path().empty() ? fs::path(".") : destination.parent_path();
    std::string pattern = (folder / ("." + name + ".XXXXXX" + suffix)).string();
    const int descriptor = ::mkstemps(pattern.data(), static_cast<int>(suffix.size()));
    if (descriptor < 0) {
        throw std::runtime_error("cannot write " + quoted(destination) + ": " +
                                 std::strerror(errno));
    }
    // mkstemps creates the file 0600.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(descriptor, 0666 & ~mask);
    created = pattern;
    return descriptor;
}

// Closes the descriptor and removes the temporary file unless released.
class TemporaryFile {
  public:
    explicit TemporaryFile(const fs::path& destination)
        : descriptor_(
              create_hidden_beside(destination, destination.filename().string(), "", path_)) {}
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    ~TemporaryFile() {
        if (descriptor_ >= 0) {
            ::close(descriptor_);
        }
        if (!path_.empty()) {
            std::error_code ignored;
            fs::remove(path_, ignored);
        }
    }

    int descriptor() const { return descriptor_; }
    const fs::path& path() const { return path_; }
    // Closes the file; returns false (errno set) when the close reports an error.
    bool close() {
        const int result = ::close(descriptor_);
        descriptor_ = -1;
        return result == 0;
    }
    void release() { path_.clear(); }

  private:
    fs::path path_;  // before descriptor_: its initializer sets path_
    int descriptor_ = -1;
};

// The file a path names, for comparison: its identity when it exists, else the resolved path.
bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code error;
    if (fs::exists(a, error) && fs::exists(b, error)) {
        return fs::equivalent(a, b, error);
    }
    return fs::weakly_canonical(fs::absolute(a), error) ==
           fs::weakly_canonical(fs::absolute(b), error);
}

}  // namespace

namespace {

// Refuses a destination the rename must not replace.
void check_destination(const fs::path& path) {
    std::error_code error;
    if (fs::exists(path, error) && ::access(path.c_str(), W_OK) != 0) {
        throw std::runtime_error("cannot write " + quoted(path) + ": " + std::strerror(errno));
    }
    // The rename would replace a device (/dev/null), FIFO or socket with a regular file.
    if (fs::exists(path, error) && !fs::is_regular_file(path, error)) {
        throw std::runtime_error("cannot write " + quoted(path) + ": not a regular file");
    }
}

// The bytes in a synced temporary file beside `path`, ready to be renamed over it.
std::unique_ptr<TemporaryFile> stage(const fs::path& path, std::string_view bytes) {
    check_destination(path);
    auto temporary = std::make_unique<TemporaryFile>(path);
    const char* data = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t written = ::write(temporary->descriptor(), data, left);
        if (written < 0) {
            if (errno == EINTR) {
                continue;
            }
            throw std::runtime_error("cannot write " + quoted(path) + ": " + std::strerror(errno));
        }
        data += written;
        left -= static_cast<std::size_t>(written);
    }
    if (::fsync(temporary->descriptor()) != 0 || !temporary->close()) {
        throw std::runtime_error("cannot write " + quoted(path) + ": " + std::strerror(errno));
    }
    return temporary;
}

void commit(TemporaryFile& temporary, const fs::path& path) {
    if (::rename(temporary.path().c_str(), path.c_str()) != 0) {
        throw std::runtime_error("cannot write " + quoted(path) + ": " + std::strerror(errno));
    }
    temporary.release();
}

}  // namespace

StagedOutput::StagedOutput(const fs::path& destination) : destination_(destination) {
    check_destination(destination);
    // The destination's extension kept last: the writer may choose its format by it.
    ::close(create_hidden_beside(destination, destination.stem().string(),
                                 destination.extension().string(), temporary_));
}

StagedOutput::~StagedOutput() {
    if (!temporary_.empty()) {
        std::error_code ignored;
        fs::remove(temporary_, ignored);
    }
}

void StagedOutput::commit() {
    if (temporary_.empty()) {
        throw std::logic_error("StagedOutput::commit called twice for " + quoted(destination_));
    }
    // The writer closed the file; sync what it wrote before the rename makes it visible.
    const int descriptor = ::open(temporary_.c_str(), O_RDONLY);
    if (descriptor < 0 || ::fsync(descriptor) != 0) {
        const std::string reason = std::strerror(errno);
        if (descriptor >= 0) {
            ::close(descriptor);
        }
        throw std::runtime_error("cannot write " + quoted(destination_) + ": " + reason);
    }
    ::close(descriptor);
    if (::rename(temporary_.c_str(), destination_.c_str()) != 0) {
        throw std::runtime_error("cannot write " + quoted(destination_) + ": " +
                                 std::strerror(errno));
    }
    temporary_.clear();
}

void write_file_atomic(const fs::path& path, std::string_view bytes) {
    const auto temporary = stage(path, bytes);
    commit(*temporary, path);
}

void write_files_atomic(const std::vector<std::pair<fs::path, std::string>>& files) {
    std::vector<std::unique_ptr<TemporaryFile>> staged;
    staged.reserve(files.size());
    for (const auto& [path, bytes] : files) {
        staged.push_back(stage(path, bytes));  // a throw here removes every staged file
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        commit(*staged[i], files[i].first);
    }
}

void check_outputs_distinct(const std::vector<fs::path>& outputs,
                            const std::vector<fs::path>& inputs) {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        if (outputs[i].empty()) {
            continue;
        }
        for (const fs::path& input : inputs) {
            if (!input.empty() && same_file(outputs[i], input)) {
                throw std::invalid_argument("output " + quoted(outputs[i]) + " is the input " +
                                            quoted(input) + ": refusing to overwrite it");
            }
        }
        for (std::size_t j = i + 1; j < outputs.size(); ++j) {
            if (!outputs[j].empty() && same_file(outputs[i], outputs[j])) {
                throw std::invalid_argument("outputs " + quoted(outputs[i]) + " and " +
                                            quoted(outputs[j]) + " are the same file");
            }
        }
    }
}

}  // namespace stereo::io
