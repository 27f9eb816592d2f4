#pragma once
// Reading inputs and writing outputs without ever destroying anything (docs/robustness.md,
// "Writers that never destroy"). One policy for every output path, decided by resolveOutput:
//
//   "-"                          standard output, written once the whole output is made
//   a regular file, or none yet  written to a temporary beside it, renamed into place when
//                                complete (an existing file's permission bits are kept)
//   a symbolic link (a chain)    followed to its final target, which is written as above (the
//                                temporary beside the target), so the link stays a link
//   a FIFO, a character device   opened and written directly once the whole output is made:
//                                never replaced, never removed (/dev/null stays /dev/null); a
//                                FIFO no process reads is refused after kFifoReaderWaitSeconds
//   a link into /proc            the open file it names, written directly, appended to
//   (/dev/stdout, /dev/fd/N)     (a shell's "> file" left it empty, ">> file" keeps it)
//   a folder, a block device,    refused with an Error naming the path
//   a socket
//
// Temporaries are named .NAME.prt-tmp-PID-RANDOM (partial folders .NAME.prt-partial-PID-RANDOM)
// beside the target, so one killed mid-write is recognisably ours: the next write to the same
// target removes those whose process no longer runs and reports each through the note handler.
// Nothing else is ever removed: not another name, not a symbolic link, not a live process's.

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace prt {

/// How long a FIFO output waits for a reader to open it before it is refused (a FIFO no process
/// reads would block its writer forever).
inline constexpr int kFifoReaderWaitSeconds = 5;

/// What an output path names, and so how it is written.
enum class OutputKind {
  Stdout,   ///< "-": standard output
  File,     ///< a regular file, or none yet: temporary beside it, then rename
  Special,  ///< a FIFO, a character device, an open file named through /proc: written directly
};

/// An output path resolved once: its kind and the file actually written (the end of a symbolic
/// link chain; "-" for standard output).
struct ResolvedOutput {
  OutputKind kind = OutputKind::File;
  std::string target;
  bool viaLink = false;  ///< reached through a symbolic link
};

/// Resolves `path` by the policy above; throws Error naming it for a folder, a block device, a
/// socket, a link loop or an empty path.
ResolvedOutput resolveOutput(const std::string& path);
/// True for "-", the name of standard output wherever an output path is taken.
inline bool isStandardOutput(const std::string& path) {
  return path == "-";
}

/// Receives one line about something the writers did besides writing ("removed stale temporary
/// ..."); the library never prints. Returns the previous handler. None is set by default.
using FileNoteFn = std::function<void(const std::string&)>;
FileNoteFn setFileNoteHandler(FileNoteFn handler);

/// Writes an output by the policy above: calls write(stream) and puts the result at `path`
/// only when write returned and every byte was stored. On any failure nothing is left behind
/// and an Error naming `path` (or write's own exception) is thrown.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);
/// Same for a byte buffer.
void writeFileAtomically(const std::string& path, std::string_view bytes);
/// Reads a whole regular file (never a pipe, device or socket: a FIFO would block in open());
/// throws Error("path: cannot open ...") on failure, or when it is larger than
/// limits().maxFileBytes (PRT_MAX_FILE_BYTES).
std::vector<unsigned char> readFileBytes(const std::string& path);
/// The same with a cap of the caller's (a format's own limit), named `capName` in the refusal.
std::vector<unsigned char> readFileBytes(const std::string& path, std::uint64_t maxBytes,
                                         const char* capName);
/// A regular file mapped read-only into memory: its bytes are read from disk as they are first
/// touched, so a reader of a few of them (prt validate's rows of a large bake) reads those pages
/// alone, and nothing is zero-filled or copied. Unmapped when the last owner lets go. A file
/// truncated by another process while mapped faults (SIGBUS) where its lost bytes are touched:
/// map inputs only, never files this process writes.
class MappedFile {
 public:
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::span<const unsigned char> bytes() const { return {data_, size_}; }
  /// From here on, reads ahead of nothing (MADV_RANDOM): a page is read from disk when touched
  /// and not its neighbours, for a reader that picks scattered rows (the kernel otherwise reads
  /// megabytes around each). A hint: where the system ignores it, nothing changes but the I/O.
  void adviseRandomAccess() const;

 private:
  MappedFile(const unsigned char* data, std::size_t size) : data_(data), size_(size) {}
  const unsigned char* data_;
  std::size_t size_;
  friend std::shared_ptr<const MappedFile> mapFile(const std::string&, std::uint64_t, const char*);
};
/// Maps a whole regular file as readFileBytes reads one (the same refusals: not a pipe, device
/// or socket, nothing above `maxBytes`, named `capName`).
std::shared_ptr<const MappedFile> mapFile(const std::string& path, std::uint64_t maxBytes,
                                          const char* capName);
/// The first `bytes` bytes of a regular file (fewer when it is shorter), whatever its size: what
/// a reader sniffs a file's kind from before it reads the whole under that kind's own limit.
std::vector<unsigned char> readFileHead(const std::string& path, std::size_t bytes);
/// Throws Error naming `path` if it cannot be written by the policy above: its directory (the
/// link target's, for a symbolic link) does not exist or is not writable, or it is refused.
void checkWritable(const std::string& path);
/// Lower-case extension without the dot ("hdr", "exr", "gz"); "" if none.
std::string fileExtension(const std::string& path);

/// Removes the temporaries and partial folders of our naming beside `target` whose process
/// no longer runs, reporting each through the note handler; returns how many. The writers call
/// it for every target they write; exposed for tests.
int removeStaleTemporaries(const std::string& target);

/// Several outputs all or nothing. While a batch is alive on this thread, writeFileAtomically
/// leaves each output complete in its temporary (standard output and special files: in
/// memory); commit() moves them all into place, in the order written. A batch destroyed
/// without commit removes them, so a failure part-way writes none of the outputs.
class OutputBatch {
 public:
  OutputBatch();
  ~OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;
  /// Moves every output into place. If a rename fails (rare: the temporaries sit beside their
  /// targets), the outputs not yet moved are removed and an Error naming the file is thrown.
  void commit();

  struct Pending;  ///< one output waiting for commit (internal)

 private:
  std::vector<Pending> pending_;
  OutputBatch* previous_;
  bool committed_ = false;
  friend void writeFileAtomically(const std::string&, const std::function<void(std::ostream&)>&);
};

/// A folder written as a whole. The files go into a partial folder beside `destination`
/// (.NAME.prt-partial-PID-RANDOM); commit() marks it as made by `maker` (a file `.prt-output`
/// whose first line is `maker`, e.g. "prt web") and renames it into place, replacing an earlier
/// folder in one step. Destroyed without commit, the partial folder is removed: a failure never
/// leaves a half-made folder, and an earlier one stays as it was.
class FolderOutput {
 public:
  /// Checks `destination` (checkFolderReplaceable), creates its parent folders if missing and
  /// the partial folder.
  FolderOutput(const std::string& destination, const std::string& maker);
  ~FolderOutput();
  FolderOutput(const FolderOutput&) = delete;
  FolderOutput& operator=(const FolderOutput&) = delete;

  /// The partial folder, to write into.
  const std::string& path() const { return partial_; }
  /// `relative` inside the partial folder.
  std::string file(const std::string& relative) const;
  /// Writes `relative` inside the partial folder (writeFileAtomically); an error names the file
  /// as it will be, DESTINATION/relative.
  void write(const std::string& relative, std::string_view bytes) const;
  /// Moves the folder into place. Throws Error naming the destination on failure (the partial
  /// folder is then removed and an earlier folder is left as it was).
  void commit();

  /// The name of the mark a made folder holds.
  static constexpr const char* kMarkName = ".prt-output";

 private:
  std::string given_, destination_, partial_, maker_;
  bool committed_ = false;
};

/// Throws Error naming `destination` unless a FolderOutput may replace it: it does not exist,
/// is an empty folder, or is a folder whose mark names `maker`. Refused: standard output, a path
/// that is not a folder, a non-empty folder `maker` did not make. Writes nothing.
void checkFolderReplaceable(const std::string& destination, const std::string& maker);

}  // namespace prt
