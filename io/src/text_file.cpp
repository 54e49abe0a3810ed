#include "stereo_io/text_file.hpp"
#include "stereo_io/output.hpp"

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

namespace stereo::io {

namespace fs = std::filesystem;

std::string read_text_file(const fs::path& path, const std::string& what,
                           std::uintmax_t max_bytes) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    const std::string name = what + " " + path.string();
    if (!fs::exists(status)) {
        throw std::runtime_error("cannot read " + name + ": no such file");
    }
    if (fs::is_directory(status)) {
        throw std::runtime_error("cannot read " + name + ": is a directory");
    }
    if (!fs::is_regular_file(status)) {
        throw std::runtime_error("cannot read " + name + ": not a regular file");
    }
    const std::uintmax_t size = fs::file_size(path, error);
    if (!error && size > max_bytes) {
        throw std::invalid_argument(name + " is " + std::to_string(size) +
                                    " bytes, more than the limit of " + std::to_string(max_bytes));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw std::runtime_error("cannot read " + name);
    }
    note_input_read(path);  // no output may replace it (stereo_io/output.hpp)
    std::string text;
    // Read at most max_bytes + 1 bytes: the file may have grown since it was measured.
    std::istreambuf_iterator<char> it(in);
    const std::istreambuf_iterator<char> end;
    for (; it != end && text.size() <= max_bytes; ++it) {
        text.push_back(*it);
    }
    if (in.bad()) {
        throw std::runtime_error("cannot read " + name + ": read error");
    }
    if (text.size() > max_bytes) {
        throw std::invalid_argument(name + " is larger than the limit of " +
                                    std::to_string(max_bytes) + " bytes");
    }
    return text;
}

}  // namespace stereo::io
