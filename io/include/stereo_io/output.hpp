// The output layer every command writes through (docs/reliability.md, "Outputs lose nothing").
//
// * Every file goes to a temporary beside its destination and is renamed over it once complete
//   and synced: a failure or a kill leaves the previous file as it was, never a partial one.
//   Every short write, ENOSPC, EFBIG and fsync/close error is an error (std::runtime_error naming
//   the file), after which only the temporary is removed.
// * Temporaries are created by mkstemp/mkdtemp (O_CREAT | O_EXCL, unpredictable names, never
//   through a symbolic link) and named ".NAME.PID-TAG.XXXXXX" (NAME shortened to fit 255 bytes;
//   TAG: this machine's boot, PID namespace and host name): the signal guards remove every live
//   one on SIGINT, SIGTERM, SIGHUP, SIGQUIT and the other terminating signals a process can
//   catch, and a later run removes what a SIGKILL left (sweep_stale_temporaries).
// * Before any work a command checks its outputs against every file it will read, the files
//   inside its input folders included (check_outputs).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace stereo::io {

// Writes `bytes` to `path` atomically. Throws std::runtime_error (naming the file and the
// reason) when the folder is missing, the destination exists but is not a writable regular file,
// or a write, the fsync or the close fails; then only the temporary file is removed and an
// existing destination is untouched.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

// Several files, all or nothing: every one is written to its temporary file and synced first;
// only when all of them are on disk are they renamed into place. A failure before that leaves
// every destination untouched. (A failure among the renames themselves, on one file system, is
// not expected; it is reported and leaves the files renamed so far.)
void write_files_atomic(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

// A file that another library writes by name (Verilator's FST tracer) and
// that must still land atomically. path() names a file inside a fresh private folder (mode 0700,
// made by mkdtemp beside the destination, ".NAME.PID-TAG.XXXXXX/"), so neither the file nor the
// side files the library opens next to it (FST's ".hier") can be redirected by a link planted
// by someone else. The writer writes and closes it; commit() checks that the file is complete
// (an FST or AVI file's own structure, by the destination's extension: a library that ignores a
// failed write, on a full disk or under a file-size limit, leaves a file whose blocks do not add
// up), syncs it and renames it over the destination. Destroyed uncommitted (an error, an
// exception), it removes the private folder and leaves the destination as it was. Throws
// std::runtime_error naming the destination when the folder is missing or the destination is
// not a writable regular file.
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
    std::filesystem::path folder_;     // the private folder; empty once committed
    std::filesystem::path temporary_;  // the file inside it
    int slot_ = -1;                    // its entry among the live temporaries
};

// Throws std::runtime_error unless an FST waveform (fstapi's block layout) or an AVI file (RIFF
// chunks) at `file` is whole: every block inside the file and the last one ending at its end,
// and for FST the header's count of value-change blocks equal to those present. `name` is the
// destination the message names.
void check_fst_complete(const std::filesystem::path& file, const std::filesystem::path& name);
void check_avi_complete(const std::filesystem::path& file, const std::filesystem::path& name);

// Every file a command will read, named before any work: files by name and folders whose whole
// content (recursively, symbolic links followed) the command may read.
struct Inputs {
    std::vector<std::filesystem::path> files = {};
    std::vector<std::filesystem::path> folders = {};
};

// The check every command runs before any work. Throws std::invalid_argument when
// * an output is a file the command reads: one of `inputs.files`, or any file inside one of
//   `inputs.folders` (compared by device and inode, so another spelling, a symbolic link or a
//   hard link is caught; a named input that does not exist is compared by its resolved path);
// * an output lies inside an input folder, even as a new file: a command never writes into a
//   folder it reads (the folder's files are what it reads, and a list taken of it later would
//   see the output);
// * two outputs are the same file.
// Empty paths are ignored (an option not given). A folder holding more than a million entries
// is refused as well (std::invalid_argument), rather than walked without end.
void check_outputs(const std::vector<std::filesystem::path>& outputs, const Inputs& inputs);

// check_outputs with named input files only.
void check_outputs_distinct(const std::vector<std::filesystem::path>& outputs,
                            const std::vector<std::filesystem::path>& inputs);

// Throws std::runtime_error when `path` cannot be written: its folder is missing or is not
// writable (a temporary is created there and removed again, which also checks that the
// temporary's name fits), `path` is a folder, or it exists and is not a writable regular file.
// Commands call it (through io::check_writable_location) before any work.
void check_can_stage(const std::filesystem::path& path);

// ---- process-wide guards ------------------------------------------------------------------

// Installed once by a command-line program before any work (cli::run):
// * SIGXFSZ ignored, so a write beyond the file-size limit fails with EFBIG and is reported;
// * SIGPIPE ignored, so a write into a closed pipe fails with EPIPE and is reported;
// * SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGALRM, SIGUSR1, SIGUSR2, SIGVTALRM, SIGPROF, SIGXCPU and
//   SIGPWR (those whose action is still the default: a signal ignored by the parent, as nohup
//   does, stays ignored) remove every live temporary and then end the process by the same
//   signal with its default action, so the exit status still shows it;
// * SIGBUS (a memory-mapped file that cannot be backed: FST's writer on a full disk) removes
//   every live temporary, prints "PROGRAM: error: ..." and exits with status 1;
// * every file the program's readers read (note_input_read) is remembered, and a write that
//   would replace one of them is refused: the last line of defence behind check_outputs.
// The Python module installs none of these (the interpreter owns its signals).
void install_process_guards(std::string_view program);

// Called by the readers of stereo_io (images, text files): remembers the file's identity when
// the guards are installed, so that no output replaces it.
void note_input_read(const std::filesystem::path& path);

// Removes the temporaries left in `folder` by processes that no longer exist: entries named
// ".NAME.PID-TAG.XXXXXX" with this machine's TAG (same boot, PID namespace and host name), owned
// by this user, whose PID is not a live process here. Another run's live temporaries, other
// users' files and files from other machines sharing the folder are never touched. Runs once
// per folder and process, when a temporary is first created there; best effort (errors
// ignored). Returns how many entries it removed.
int sweep_stale_temporaries(const std::filesystem::path& folder);

}  // namespace stereo::io
