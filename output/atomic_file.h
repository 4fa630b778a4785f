// Writing outputs so that a failure or a kill never leaves a half-written file or a
// mixed set: one file through a temporary and a rename, a folder's set of files
// through a staging folder swapped in as a whole (docs/reliability.md).
#pragma once

#include <functional>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

namespace ilp {

// Calls `write` on a stream to a temporary beside `path` ("<path>.tmp-PID-N", unique
// per process and call), flushes and checks it, then renames it over `path`. Throws
// IlpError "<path>: cannot write" (the temporary cannot be created) or "<path>: write
// failed" (the stream failed or the rename did not happen). On any exception,
// including one from `write`, the temporary is removed, a previous file at `path` is
// left as it was, and the exception goes on. Temporaries of killed processes beside
// `path` are removed.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// The files one command writes into an output folder, replaced as one transaction.
//
// Every file is written into a fresh staging folder beside the output folder
// (".NAME.ilp-tmp-PID-RANDOM", on the same file system). commit() hard-links into it
// whatever else the output folder holds (files this set does not own: another
// command's outputs, the user's own), then swaps the two folders with one atomic
// renameat2(RENAME_EXCHANGE) and deletes the old one. A reader, a crash or a kill at
// any moment sees the old complete folder or the new one, never a mix. Files the set
// owns but this run did not write (a format left out) are gone after the commit: they
// belonged to the previous run. Commits into one parent folder are serialised with
// flock(2), and each commit first removes staging folders of processes that no longer
// run. Where the file system cannot exchange (EINVAL), the folder is renamed aside and
// the new one renamed in; a kill between those two renames leaves the old folder as
// ".NAME.ilp-old-PID-RANDOM", which the next commit puts back before anything else.
//
// Test hooks (docs/reliability.md): ILP_TEST_OUTPUT_PAUSE=N pauses 60 s after the Nth
// file is staged, =carried after the carry-over, =swapped after the swap; it prints
// "ilp-test: paused at ..." to stderr first. ILP_TEST_OUTPUT_FAIL=N throws after the
// Nth file (a full disk).
class OutputSet {
 public:
  // `folder`: the output folder; `owned`: the names of every file this command can
  // write there. Creates the staging folder (and the parents of `folder`), after
  // removing staging folders of killed runs beside it. A symbolic link to a folder is
  // kept: the set goes into its target. Throws IlpError when `folder` is not a folder
  // or holds the current working folder.
  OutputSet(const std::string& folder, std::vector<std::string> owned);
  ~OutputSet();  // removes the staging folder unless committed
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Where file `name` (one of `owned`) is staged; write it there (any writer), then
  // call staged(name). Files may be written and staged from several threads at once
  // (not while set_subfolder changes the sub-folder).
  std::string staging_path(const std::string& name) const;
  void staged(const std::string& name);
  // write_file_atomically into the staging folder, then staged(name).
  void write(const std::string& name, const std::function<void(std::ostream&)>& write);
  // Files staged between begin_batch() and end_batch() (writers running at once) are
  // listed in the order of `owned`, after those staged before; others in the order staged.
  void begin_batch();
  void end_batch();

  // Moves the set into place. Returns the paths of the files written (the folder as
  // given to the constructor / name), in the order staged.
  std::vector<std::string> commit();

  const std::string& folder() const { return folder_; }
  // The full names staged so far, in order (a rank of a distributed run reads their
  // bytes from staging_path to send them to rank 0, docs/cluster.md).
  const std::vector<std::string>& staged_names() const { return written_; }

  // Names given from now on are in this sub-folder of the set ("rooms/office_1": a
  // building's room writes its usual file names there; "" the folder itself). The
  // owned names are the full ones ("rooms/office_1/result.json"); the sub-folder is
  // created in the staging folder as needed.
  void set_subfolder(const std::string& subfolder) { subfolder_ = subfolder; }

  // A failure's message with the staging folder's path replaced by the output
  // folder's (the user's name for where the files go) and the space left on its file
  // system: what a disk-full failure says.
  std::string explained(const std::string& message) const;

 private:
  std::string given_;    // as the caller named it (for the paths commit returns)
  std::string folder_;   // absolute, normalised
  std::string staging_;  // beside it
  std::vector<std::string> owned_;
  std::vector<std::string> written_;
  std::string subfolder_;
  bool committed_ = false;
  static constexpr std::size_t kNoBatch = static_cast<std::size_t>(-1);
  std::size_t batch_from_ = kNoBatch;  // where the current batch starts in written_
  std::mutex mutex_;                   // guards written_ and batch_from_

  std::string full_name(const std::string& name) const { return subfolder_.empty() ? name : subfolder_ + "/" + name; }
};

}  // namespace ilp
