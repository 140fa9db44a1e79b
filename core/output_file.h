#pragma once
// Result files written so that a failure (a full disk, a file-size limit, a killed run) never
// leaves a truncated file under the real name: the data goes to a temporary in the same folder,
// which is renamed into place only when complete, and removed otherwise.
#include <functional>
#include <string>

namespace shadowlab {

// A resource (the temporary), hence a class: construct, write to temp_path(), commit().
class OutputFile {
 public:
  explicit OutputFile(std::string path);
  // The temporary is registered for removal on an interrupt (core/temp_cleanup.h).
  ~OutputFile();  // removes the temporary unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& temp_path() const { return temp_; }
  // Renames the temporary to the real path; InputError(path, the OS's reason) on failure.
  void commit();

 private:
  std::string path_, temp_;
  bool committed_ = false;
};

// A check every OutputFile::commit runs on its real path before the rename (the experiments'
// output folder sets one: no output may name an input or be written twice); none by default.
void set_commit_check(std::function<void(const std::string& path)> check);

// Writes `text` to `path` through an OutputFile; InputError(path, "cannot write: <reason>").
void write_text_file(const std::string& path, const std::string& text);

}  // namespace shadowlab
