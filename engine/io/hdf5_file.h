// A thin RAII layer over the HDF5 C API: a file, and reading/writing whole 1-D and 2-D
// datasets of doubles and integers, plus scalar attributes. Errors throw fibrenet::Error
// naming the file and the dataset.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fibrenet::io {

// True when `path` is a readable HDF5 file.
bool IsHdf5(const std::string& path);

// A created file is built in memory (HDF5's core driver) and reaches the disk only in Save(),
// through plain checked writes: a full disk or an unwritable folder is then an exception
// naming the file and the system's cause, never a half-written file or a failure inside the
// HDF5 library at exit (HDF5 1.10 crashes at exit after a failed close of a file it wrote
// to disk itself). The driver grows its buffer through our callbacks, so Save() writes that
// buffer as it is, without a second copy of the file in memory.
class Hdf5File {
 public:
  enum class Mode { kCreate, kRead };
  Hdf5File(const std::string& path, Mode mode);
  ~Hdf5File();
  // Writes a created file to its path. Throws fibrenet::Error; nothing is left at the path
  // when the write fails.
  void Save();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  const std::string& path() const { return path_; }
  void CreateGroup(const std::string& name);
  bool Exists(const std::string& name) const;

  // Row-major arrays of rows x cols (cols = 1 for a vector).
  void WriteDoubles(const std::string& name, const std::vector<double>& data, std::size_t cols);
  void WriteInts(const std::string& name, const std::vector<std::int64_t>& data, std::size_t cols);
  std::vector<double> ReadDoubles(const std::string& name, std::size_t cols) const;
  std::vector<std::int64_t> ReadInts(const std::string& name, std::size_t cols) const;

  // Scalar attributes on the root group.
  void WriteAttribute(const std::string& name, double value);
  double ReadAttribute(const std::string& name) const;
  void WriteText(const std::string& name, const std::string& value);
  std::string ReadText(const std::string& name) const;
  bool HasAttribute(const std::string& name) const;
  std::vector<std::string> AttributeNames() const;  // of the root group

 private:
  // The in-memory file's bytes, as the core driver last sized them.
  struct Image {
    void* data = nullptr;
    std::size_t size = 0;
    bool keep_on_close = false;  // set by Save(), which takes the buffer over
  };
  static H5FD_file_image_callbacks_t ImageCallbacks(Image* image);

  std::unique_ptr<Image> image_;  // outlives file_: the driver frees the buffer on close
  hid_t file_ = -1;
  std::string path_;
};

}  // namespace fibrenet::io
