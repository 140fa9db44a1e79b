#pragma once
// Every file a program reads from outside (scenes, models and their buffers, images, slides,
// EXRs, JSON results, caches) is opened here: it must be a regular file of at most a limit
// that depends on its kind. The check runs on the open descriptor (fstat), so what is checked
// is what is read; opening uses O_NONBLOCK, so a FIFO or a device is refused without waiting
// for a writer. A directory, FIFO, socket or device never reaches a parser: read as a file, a
// FIFO blocks until a writer comes, /dev/zero never ends, and a directory's size is no length
// of contents.
#include <cstdint>
#include <string>
#include <vector>

namespace shadowlab {

// The size limit of one kind of input file, and the words that name the kind in errors.
struct InputLimit {
  uint64_t bytes;
  const char* kind;  // "a scene file", ...
};

// Scene files name their models rather than holding them: 1 MiB is thousands of models.
constexpr InputLimit kSceneFileLimit{uint64_t(1) << 20, "a scene file (it names its models rather than holding them)"};
// OBJ, glTF (.gltf, .glb) and glTF buffers: 2 GiB is about 30 M triangles as OBJ text, more
// than a scene loaded into memory beside its BVH and maps leaves room for; tinygltf takes a
// buffer's length as a 32-bit count, which 2 GiB stays within.
constexpr InputLimit kModelFileLimit{uint64_t(2) << 30, "a model file"};
// MTL material libraries: text naming textures and colours; 64 MiB is over a million materials.
constexpr InputLimit kMaterialFileLimit{uint64_t(64) << 20, "a material library"};
// EXR images (masks, references, slides): the largest image allowed
// (kMaxImageSide² = 16384², three float channels, uncompressed) is 3 GiB of pixels.
constexpr InputLimit kImageFileLimit{uint64_t(4) << 30, "an image"};
// PNG/JPEG images (textures, slides) go to stb_image, which takes a length as an int: 1.5 GiB
// holds the largest image allowed stored without compression (16384² RGBA is 1 GiB).
constexpr InputLimit kTextureFileLimit{uint64_t(1536) << 20, "a PNG/JPEG image"};
// JSON results read back (--from, merge shards): a tune shard of thousands of configurations
// is a few MB; 256 MiB leaves a factor of 50.
constexpr InputLimit kResultFileLimit{uint64_t(256) << 20, "a result JSON file"};
// Cache files (reference, LOD): written by shadowlab itself; a reference at kMaxImageSide² with
// its per-pixel data stays well below 16 GiB. A cache file over it, or not a regular file, is a
// cache miss, not an error.
constexpr InputLimit kCacheFileLimit{uint64_t(16) << 30, "a cache file"};

// An open, checked input file (closed on destruction).
class InputFile {
 public:
  // Opens `path` read-only and checks it is a regular file within `limit`. Throws
  // InputError(path, reason) otherwise: "cannot open: <OS reason>", "is a directory, not a
  // regular file", "is <N> bytes, over the limit of <L> for <kind>".
  InputFile(const std::string& path, const InputLimit& limit);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  int fd() const { return fd_; }
  uint64_t size() const { return size_; }
  // The descriptor's ownership passes to the caller (fdopen, a library); -1 afterwards.
  int release();

 private:
  int fd_ = -1;
  uint64_t size_ = 0;
};

// The whole of `path` (checked as InputFile does). Throws InputError naming the file; a file
// that changes size while read is an error too.
std::string read_input_file(const std::string& path, const InputLimit& limit);
std::vector<unsigned char> read_input_bytes(const std::string& path, const InputLimit& limit);
void read_input_file(const std::string& path, const InputLimit& limit, std::vector<char>& out);
// Only the checks of InputFile, for libraries that open a path themselves (OpenEXR).
void check_input_file(const std::string& path, const InputLimit& limit);
// read_input_file without throwing: false with the reason (no path) in *why.
bool try_read_input_file(const std::string& path, const InputLimit& limit, std::string& out,
                         std::string* why);

// "1 MiB", "2 GiB", or bytes: for limits in messages and documentation.
std::string format_byte_limit(uint64_t bytes);

}  // namespace shadowlab
