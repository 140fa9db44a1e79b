#pragma once
// A run's outputs appear all together or not at all (docs/bad_input.md "Outputs appear all
// together or not at all"). The run writes its folder's files into a staging folder beside
// --out (DIR.staging-PID, the same file system), and commit() puts the whole set in place with
// two renames: the previous folder to DIR.old-PID, the staging folder to DIR; then the backup is
// removed. Before that, the staging folder receives (as hard links) every entry of the previous
// folder that the run does not write and that is not part of the previous run's set, so files
// a user keeps there survive; the previous set, listed in DIR/.shadowlab_outputs, is replaced
// as a whole (a shard of a run and merge add to it instead). Files named by their own flag
// outside --out (--plot, --contours) are written to FILE.staged-PID beside them and renamed
// after the folder.
//
// A failure or an interrupt before commit() leaves the previous folder as it was: the staging
// folder and temporaries are removed (core/temp_cleanup.h). A crash of the machine (or SIGKILL)
// between the two renames leaves no DIR, DIR.old-PID (the previous results) and DIR.staging-PID
// (the new ones); the next run with the same --out renames the backup back to DIR and removes
// the staging folders of processes that no longer exist, before it does anything else.
#include <set>
#include <string>
#include <vector>

namespace shadowlab {

class RunOutputs {
 public:
  // A run with an output folder: `dir` is --out, `flag` names it in errors. Checks the folder
  // and creates the staging folder beside it, so call it before the first expensive step: any
  // reason the outputs could not be put in place is an InputError(flag, …) now. `additive`: the
  // run adds its files to the folder's previous set (a shard, merge) instead of replacing it.
  RunOutputs(const std::string& dir, const std::string& flag, bool additive = false);
  // A run without a folder, whose outputs are files named by their flags (metric --contours).
  RunOutputs();
  ~RunOutputs();  // removes the staging folder and the temporaries unless committed
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  // Where the run writes the files of its folder: the staging folder.
  const std::string& dir() const { return stage_; }
  // Creates and returns the staging folder's subfolder `name` (one level).
  std::string subfolder(const std::string& name) const;
  // Checks now, for output names known before the run, that --out/NAME is not an input of this
  // run, and not a folder (with `folders`: nothing but a folder) where the run writes a file.
  void check_names(const std::vector<std::string>& names, bool folders = false) const;
  // A file output named by its flag: it must end in `extension` (any case), name no input of
  // the run (inputs read so far), no other output and no folder, and its folder must exist.
  // Returns the path to write: in the staging folder when the file lies directly in --out, else
  // FILE.staged-PID beside it, created now (so an unwritable place is refused now).
  std::string file(const std::string& flag, const std::string& path, const std::string& extension);
  // Puts every output in place (see above). InputError naming the entry when the folder holds a
  // folder where the run writes a file (or the reverse); the previous folder is unchanged then.
  void commit();

 private:
  struct Staged {
    std::string temp, path, flag;
  };
  void commit_folder();
  void check_write(const std::string& written);
  std::string final_path(const std::string& written) const;

  std::string flag_, dir_, stage_;  // dir_ absolute; empty without a folder
  bool additive_ = false, committed_ = false;
  std::vector<Staged> files_;
  std::set<std::string> written_;   // paths committed by OutputFile in this run
};

}  // namespace shadowlab
