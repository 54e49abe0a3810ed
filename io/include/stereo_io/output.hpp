// Output files that lose nothing (docs/reliability.md): every file a command writes goes to a
// temporary file in the destination folder, is flushed to disk and renamed over the destination,
// so a failure or a kill mid-write leaves the previous file as it was, never a partial one; and a
// command refuses, before any work, outputs that would overwrite one of its inputs or each other.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace stereo::io {

// Writes `bytes` to `path` atomically. Throws std::runtime_error (naming the file and the
// reason) when the folder is missing, the destination exists but is not writable, or a write
// fails; then only the temporary file is removed and an existing destination is untouched.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

// Several files, all or nothing: every one is written to its temporary file and synced first;
// only when all of them are on disk are they renamed into place. A failure before that leaves
// every destination untouched. (A failure among the renames themselves, on one file system, is
// not expected; it is reported and leaves the files renamed so far.)
void write_files_atomic(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

// A file that another library writes by name (Verilator's FST tracer) and that must still land
// atomically: path() is a fresh temporary file beside the destination, hidden, with the
// destination's extension (".NAME.XXXXXX.EXT"); the writer writes it and closes it, commit()
// syncs it and renames it over the destination. Destroyed uncommitted (an error, an exception),
// it removes the temporary file and leaves the destination as it was. Throws std::runtime_error
// naming the destination when the folder is missing or the destination is not a writable
// regular file.
class StagedOutput {
  public:
    explicit StagedOutput(const std::filesystem::path& destination);
    StagedOutput(const StagedOutput&) = delete;
    StagedOutput& operator=(const StagedOutput&) = delete;
    ~StagedOutput();

    const std::filesystem::path& path() const { return temporary_; }
    const std::filesystem::path& destination() const { return destination_; }
    // Call once the writer has closed the file.
    void commit();

  private:
    std::filesystem::path destination_;
    std::filesystem::path temporary_;  // empty once committed
};

// Throws std::invalid_argument when an output is the same file as an input (same inode, or the
// same resolved path for a file that does not exist yet, through symbolic links), or two outputs
// are the same file. Empty paths are ignored (an option not given).
void check_outputs_distinct(const std::vector<std::filesystem::path>& outputs,
                            const std::vector<std::filesystem::path>& inputs);

}  // namespace stereo::io
