#include "lab/output_folder.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/output_file.h"
#include "core/run_inputs.h"
#include "core/temp_cleanup.h"

namespace shadowlab {
namespace {

namespace fs = std::filesystem;

// The previous run's set: the names (one per line) of the entries a run put in its folder.
const char* const kManifest = ".shadowlab_outputs";

std::string pid_text() { return std::to_string(long(::getpid())); }

std::string os_reason(int err) { return std::strerror(err); }

// An exclusive lock on a folder (flock on its descriptor), held while runs into folders of that
// parent recover or move their outputs into place: shards run in parallel into one --out.
class FolderLock {
 public:
  explicit FolderLock(const std::string& folder) : fd_(::open(folder.c_str(), O_RDONLY | O_DIRECTORY)) {
    // A file system without locks (some network mounts) runs unlocked.
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~FolderLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_;
};

bool process_exists(long pid) { return ::kill(pid_t(pid), 0) == 0 || errno == EPERM; }

// The pid after `prefix` in `name` ("S.staging-123" with prefix "S.staging-" → 123, also with
// the ".removing" an interrupt's cleanup renames it to), else 0.
long pid_after(std::string name, const std::string& prefix) {
  const std::string removing = ".removing";
  if (name.size() > removing.size() && name.compare(name.size() - removing.size(), removing.size(), removing) == 0)
    name.resize(name.size() - removing.size());
  if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size() || name.size() > prefix.size() + 10) return 0;
  long pid = 0;
  for (size_t i = prefix.size(); i < name.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return 0;
    pid = pid * 10 + (name[i] - '0');
  }
  return pid;
}

// What an interrupted run left beside `dir` (see output_folder.h): a backup of a process that
// no longer exists goes back to `dir` when `dir` is missing; its staging folders are removed.
void recover(const fs::path& dir) {
  const std::string base = dir.filename().string();
  std::error_code ec;
  std::vector<fs::path> backups, stagings;
  for (const fs::directory_entry& e : fs::directory_iterator(dir.parent_path(), ec)) {
    const std::string name = e.path().filename().string();
    if (long pid = pid_after(name, base + ".old-"); pid > 0 && !process_exists(pid)) backups.push_back(e.path());
    if (long pid = pid_after(name, base + ".staging-"); pid > 0 && !process_exists(pid)) stagings.push_back(e.path());
  }
  for (const fs::path& b : backups) {
    std::error_code e1;
    if (!fs::exists(fs::symlink_status(dir, e1))) fs::rename(b, dir, e1);
    if (fs::exists(fs::symlink_status(b, e1))) fs::remove_all(b, e1);
  }
  for (const fs::path& s : stagings) fs::remove_all(s, ec);
}

std::set<std::string> read_manifest(const fs::path& dir) {
  std::set<std::string> names;
  std::ifstream in(dir / kManifest);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line.find('/') == std::string::npos && line != "." && line != "..") names.insert(line);
  return names;
}

// Puts `from` (an entry of the previous folder) into the staging folder as `to`: hard links
// for files (a copy where the file system refuses the link), folders recursively, links as links.
void carry(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(from, ec);
  if (fs::is_symlink(st)) {
    fs::copy_symlink(from, to, ec);
  } else if (fs::is_directory(st)) {
    fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::copy_symlinks | fs::copy_options::create_hard_links, ec);
    if (ec) {
      std::error_code ignored;
      fs::remove_all(to, ignored);
      ec.clear();
      fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::copy_symlinks, ec);
    }
  } else if (fs::is_regular_file(st)) {
    fs::create_hard_link(from, to, ec);
    if (ec) {
      ec.clear();
      fs::copy_file(from, to, ec);
    }
  } else {
    throw InputError(from.string(), "cannot be kept in the run's new folder (not a file, folder or link); move it away");
  }
  if (ec) throw InputError(from.string(), "cannot be kept in the run's new folder: " + ec.message());
}

bool ends_with_ci(const std::string& s, const std::string& tail) {
  if (s.size() < tail.size()) return false;
  for (size_t i = 0; i < tail.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - tail.size() + i])) !=
        std::tolower(static_cast<unsigned char>(tail[i])))
      return false;
  return true;
}

// Whether `inner` is `outer` or lies inside it (both absolute and normal).
bool is_within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

}  // namespace

RunOutputs::RunOutputs() { set_commit_check([this](const std::string& p) { check_write(p); }); }

RunOutputs::RunOutputs(const std::string& dir, const std::string& flag, bool additive)
    : flag_(flag), additive_(additive) {
  if (dir.empty()) throw InputError(flag, "needs a folder name");
  std::error_code ec;
  fs::path d = fs::absolute(dir, ec).lexically_normal();
  if (!d.has_filename()) d = d.parent_path();  // "out/" → "out"
  if (fs::is_symlink(fs::symlink_status(d, ec))) {
    d = fs::canonical(d, ec);
    if (ec) throw InputError(flag, "'" + dir + "' is a link to nothing: " + ec.message());
  }
  if (d == d.root_path() || !d.has_filename())
    throw InputError(flag, "'" + dir + "' is the root folder; give a folder of its own");
  const fs::path parent = d.parent_path();
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent))
    throw InputError(flag, "cannot create folder '" + parent.string() + "': " +
                               (ec ? ec.message() : std::string("not a folder")));
  // First what an earlier run left (output_folder.h), so the checks below see the folder the
  // run will replace.
  try {
    const FolderLock lock(parent.string());
    recover(d);
  } catch (const fs::filesystem_error&) {
    // What could not be recovered stays for a later run; this one does not depend on it.
  }
  const fs::file_status st = fs::status(d, ec);
  const bool exists = fs::exists(st);
  if (exists && !fs::is_directory(st)) throw InputError(flag, "'" + dir + "' exists and is not a folder");
  const fs::path cwd = fs::current_path(ec);
  if (exists && !ec && is_within(fs::weakly_canonical(cwd, ec), fs::canonical(d, ec)))
    throw InputError(flag, "'" + dir + "' holds the current folder; the run replaces its folder as a whole, so give a folder of its own");
  if (exists) {
    struct stat ds {}, ps {};
    if (::stat(d.c_str(), &ds) == 0 && ::stat(parent.c_str(), &ps) == 0 && ds.st_dev != ps.st_dev)
      throw InputError(flag, "'" + dir + "' is a mount point; the run replaces its folder by renaming, so give a folder inside it");
  }
  if (exists) {
    fs::directory_iterator it(d, ec);
    if (ec) throw InputError(flag, "cannot read '" + dir + "': " + ec.message());
  }
  dir_ = d.string();
  stage_ = dir_ + ".staging-" + pid_text();
  if (::mkdir(stage_.c_str(), 0777) != 0) {
    const int err = errno;
    stage_.clear();
    throw InputError(flag, "cannot write beside '" + dir + "' (its staging folder): " + os_reason(err));
  }
  register_temporary(stage_);
  set_commit_check([this](const std::string& p) { check_write(p); });
}

RunOutputs::~RunOutputs() {
  set_commit_check(nullptr);
  if (committed_) return;
  std::error_code ec;
  if (!stage_.empty()) {
    fs::remove_all(stage_, ec);
    unregister_temporary(stage_);
  }
  for (const Staged& f : files_) {
    fs::remove(f.temp, ec);
    unregister_temporary(f.temp);
  }
}

std::string RunOutputs::subfolder(const std::string& name) const {
  const std::string p = stage_ + "/" + name;
  // One level (mkdir, not create_directories): an interrupt that removed the staging folder
  // must not see it created again.
  if (::mkdir(p.c_str(), 0777) != 0 && errno != EEXIST)
    throw InputError(flag_, "cannot create folder '" + p + "': " + os_reason(errno));
  return p;
}

void RunOutputs::check_names(const std::vector<std::string>& names, bool folders) const {
  for (const std::string& n : names) {
    const fs::path p = fs::path(dir_) / n;
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(p, ec);
    if (!folders && fs::is_directory(st))
      throw InputError(p.string(), "is a folder; the run writes a file of that name");
    if (folders && fs::exists(st) && !fs::is_directory(st))
      throw InputError(p.string(), "is not a folder; the run writes a folder of that name");
    if (const std::string in = input_named_by(p.string()); !in.empty())
      throw InputError(p.string(), "is an input of this run; its output of that name would replace it");
  }
}

std::string RunOutputs::file(const std::string& flag, const std::string& path, const std::string& extension) {
  if (path.empty()) throw InputError(flag, "needs a file name");
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw InputError(flag, "'" + path + "' is a folder; give a file name such as out" + extension);
  if (!ends_with_ci(path, extension))
    throw InputError(flag, "'" + path + "' must end in " + extension + " (the file is written in that format)");
  if (const std::string in = input_named_by(path); !in.empty())
    throw InputError(flag, "'" + path + "' is an input of this run" + (in != path ? " ('" + in + "')" : "") +
                               "; an output may not replace it");
  const fs::path norm = normalized_path(path);
  for (const Staged& f : files_)
    if (normalized_path(f.path) == norm.string())
      throw InputError(flag, "'" + path + "' is also the run's " + f.flag);
  if (!dir_.empty() && norm.parent_path() == fs::path(dir_)) {
    // Directly in --out: a file of the folder's set, staged with it.
    const std::string staged = stage_ + "/" + norm.filename().string();
    if (fs::exists(fs::symlink_status(staged, ec)))
      throw InputError(flag, "'" + path + "' is also one of the run's outputs");
    return staged;
  }
  // Elsewhere (deeper in --out too: renamed after the folder, which keeps that subfolder as an
  // entry the run does not write): beside its final place.
  const fs::path parent = norm.parent_path();
  if (!fs::is_directory(parent, ec)) throw InputError(flag, "'" + path + "': folder does not exist");
  const std::string temp = norm.string() + ".staged-" + pid_text();
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0666);
  if (fd < 0) throw InputError(flag, "cannot write '" + path + "': " + os_reason(errno));
  ::close(fd);
  register_temporary(temp);
  files_.push_back({temp, norm.string(), flag});
  return temp;
}

std::string RunOutputs::final_path(const std::string& written) const {
  if (!stage_.empty() && written.rfind(stage_ + "/", 0) == 0) return dir_ + written.substr(stage_.size());
  for (const Staged& f : files_)
    if (f.temp == written) return f.path;
  return written;
}

void RunOutputs::check_write(const std::string& written) {
  const std::string final = final_path(written);
  if (const std::string in = input_named_by(final); !in.empty())
    throw InputError(final, "is an input of this run; its output of that name would replace it");
  if (!written_.insert(written).second)
    throw InputError(final, "is written twice by this run: two of its outputs have the same name");
}

void RunOutputs::commit_folder() {
  const fs::path d(dir_), stage(stage_);
  const FolderLock lock(d.parent_path().string());
  std::error_code ec;
  std::set<std::string> fresh, keep;
  for (const fs::directory_entry& e : fs::directory_iterator(stage))
    fresh.insert(e.path().filename().string());
  const bool exists = fs::is_directory(d, ec);
  if (exists) {
    const std::set<std::string> previous = read_manifest(d);
    for (const fs::directory_entry& e : fs::directory_iterator(d)) {
      const std::string name = e.path().filename().string();
      if (name == kManifest) continue;
      if (fresh.count(name)) {
        const bool was_dir = fs::is_directory(fs::symlink_status(e.path(), ec));
        const bool is_dir = fs::is_directory(fs::symlink_status(stage / name, ec));
        if (was_dir != is_dir)
          throw InputError(e.path().string(), std::string(was_dir ? "is a folder; the run writes a file"
                                                                  : "is a file; the run writes a folder") +
                                                  " of that name (nothing was moved into place)");
        continue;
      }
      if (previous.count(name) && !additive_ && input_named_by(e.path().string()).empty()) continue;
      carry(e.path(), stage / name);
      if (previous.count(name)) keep.insert(name);
    }
  }
  std::ostringstream manifest;
  for (const std::string& n : fresh) manifest << n << "\n";
  for (const std::string& n : keep) manifest << n << "\n";
  write_text_file(stage_ + "/" + kManifest, manifest.str());
  if (!exists) {
    if (::rename(stage_.c_str(), dir_.c_str()) != 0)
      throw InputError(flag_, "cannot move the outputs into '" + dir_ + "': " + os_reason(errno));
    return;
  }
  struct stat ds {};
  if (::stat(dir_.c_str(), &ds) == 0) ::chmod(stage_.c_str(), ds.st_mode & 07777);
  const std::string backup = dir_ + ".old-" + pid_text();
  if (::rename(dir_.c_str(), backup.c_str()) != 0)
    throw InputError(flag_, "cannot move the previous '" + dir_ + "' aside: " + os_reason(errno));
  if (::rename(stage_.c_str(), dir_.c_str()) != 0) {
    const int err = errno;
    ::rename(backup.c_str(), dir_.c_str());
    throw InputError(flag_, "cannot move the outputs into '" + dir_ + "': " + os_reason(err));
  }
  fs::remove_all(backup, ec);
}

void RunOutputs::commit() {
  const std::unique_lock<std::mutex> hold = hold_interrupts();
  set_commit_check(nullptr);
  if (!dir_.empty()) {
    try {
      commit_folder();
    } catch (const fs::filesystem_error& e) {
      throw InputError(flag_, std::string("cannot put the outputs in place: ") + e.what());
    }
  }
  committed_ = true;
  unregister_temporary(stage_);
  for (const Staged& f : files_) {
    unregister_temporary(f.temp);
    if (::rename(f.temp.c_str(), f.path.c_str()) != 0) {
      const int err = errno;
      std::error_code ec;
      fs::remove(f.temp, ec);
      throw InputError(f.flag, "cannot move '" + f.path + "' into place: " + os_reason(err));
    }
  }
}

}  // namespace shadowlab
