#include "engine/io/hdf5_file.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace fibrenet::io {

namespace {

// Closes an HDF5 handle when it goes out of scope.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

}  // namespace

bool IsHdf5(const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  return H5Fis_hdf5(path.c_str()) > 0;
}

H5FD_file_image_callbacks_t Hdf5File::ImageCallbacks(Image* image) {
  H5FD_file_image_callbacks_t c{};
  c.image_malloc = [](std::size_t size, H5FD_file_image_op_t, void* udata) -> void* {
    auto* im = static_cast<Image*>(udata);
    void* data = std::malloc(size);
    if (data) {
      im->data = data;
      im->size = size;
    }
    return data;
  };
  c.image_memcpy = [](void* dest, const void* src, std::size_t size, H5FD_file_image_op_t,
                      void*) -> void* { return std::memcpy(dest, src, size); };
  c.image_realloc = [](void* ptr, std::size_t size, H5FD_file_image_op_t, void* udata) -> void* {
    auto* im = static_cast<Image*>(udata);
    void* data = std::realloc(ptr, size);
    if (data) {
      im->data = data;
      im->size = size;
    }
    return data;
  };
  c.image_free = [](void* ptr, H5FD_file_image_op_t, void* udata) -> herr_t {
    auto* im = static_cast<Image*>(udata);
    if (ptr == im->data) {
      if (im->keep_on_close) return 0;  // Save() writes it out and frees it
      *im = {};
    }
    std::free(ptr);
    return 0;
  };
  // The property lists that HDF5 copies share the one Image this file owns.
  c.udata_copy = [](void* udata) { return udata; };
  c.udata_free = [](void*) -> herr_t { return 0; };
  c.udata = image;
  return c;
}

Hdf5File::Hdf5File(const std::string& path, Mode mode) : path_(path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by our exceptions
  if (mode == Mode::kCreate) {
    // In memory, grown 1 MiB at a time, no backing store (Save() writes it out).
    image_ = std::make_unique<Image>();
    H5FD_file_image_callbacks_t callbacks = ImageCallbacks(image_.get());
    Handle access{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
    if (access.id >= 0 && H5Pset_fapl_core(access.id, 1 << 20, 0) >= 0 &&
        H5Pset_file_image_callbacks(access.id, &callbacks) >= 0)
      file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.id);
  } else {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  if (file_ < 0)
    throw Error(fmt::format("{}: cannot {} HDF5 file", path,
                            mode == Mode::kCreate ? "create" : "open"));
}

Hdf5File::~Hdf5File() {
  if (file_ >= 0) H5Fclose(file_);
}

void Hdf5File::Save() {
  if (!image_ || file_ < 0) throw Error(fmt::format("{}: not a file being created", path_));
  if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) throw Error(fmt::format("{}: cannot flush", path_));
  // The file's extent; the driver's buffer runs past it to its 1 MiB increment.
  const ssize_t size = H5Fget_file_image(file_, nullptr, 0);
  if (size <= 0) throw Error(fmt::format("{}: cannot take the file image", path_));
  // Closing leaves the bytes as the library hands out a finished file (its superblock no
  // longer marked open for writing); the callbacks keep the buffer for the write below.
  image_->keep_on_close = true;
  const herr_t closed = H5Fclose(file_);
  file_ = -1;
  const std::unique_ptr<void, decltype(&std::free)> bytes(image_->data, &std::free);
  if (closed < 0 || !bytes || image_->size < static_cast<std::size_t>(size))
    throw Error(fmt::format("{}: cannot take the file image", path_));
  std::FILE* out = std::fopen(path_.c_str(), "wb");
  if (!out) throw Error(fmt::format("{}: cannot create the file: {}", path_, std::strerror(errno)));
  const auto length = static_cast<std::size_t>(size);
  const bool written = std::fwrite(bytes.get(), 1, length, out) == length;
  const int write_errno = errno;
  const bool file_closed = std::fclose(out) == 0;
  if (!written || !file_closed) {
    const int err = written ? errno : write_errno;
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
    throw Error(fmt::format("{}: cannot write the file: {}", path_, std::strerror(err)));
  }
}

void Hdf5File::CreateGroup(const std::string& name) {
  Handle g{H5Gcreate2(file_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose};
  if (g.id < 0) throw Error(fmt::format("{}: cannot create group {}", path_, name));
}

bool Hdf5File::Exists(const std::string& name) const {
  return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
}

namespace {

template <typename T>
void Write(hid_t file, const std::string& path, const std::string& name, hid_t type,
           const std::vector<T>& data, std::size_t cols) {
  const hsize_t dims[2] = {cols ? data.size() / cols : 0, cols};
  Handle space{H5Screate_simple(cols == 1 ? 1 : 2, dims, nullptr), H5Sclose};
  Handle set{H5Dcreate2(file, name.c_str(), type, space.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose};
  if (set.id < 0 || (!data.empty() && H5Dwrite(set.id, type, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                               data.data()) < 0))
    throw Error(fmt::format("{}: cannot write dataset {}", path, name));
}

template <typename T>
std::vector<T> Read(hid_t file, const std::string& path, const std::string& name, hid_t type,
                    std::size_t cols) {
  Handle set{H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose};
  if (set.id < 0) throw Error(fmt::format("{}: missing dataset {}", path, name));
  Handle space{H5Dget_space(set.id), H5Sclose};
  hsize_t dims[2] = {0, 1};
  const int rank = H5Sget_simple_extent_dims(space.id, dims, nullptr);
  if (rank < 1 || (rank == 2 && dims[1] != cols) || (rank == 1 && cols != 1))
    throw Error(fmt::format("{}: dataset {} has the wrong shape", path, name));
  std::vector<T> data(dims[0] * cols);
  if (!data.empty() && H5Dread(set.id, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    throw Error(fmt::format("{}: cannot read dataset {}", path, name));
  return data;
}

}  // namespace

void Hdf5File::WriteDoubles(const std::string& name, const std::vector<double>& data,
                            std::size_t cols) {
  Write(file_, path_, name, H5T_NATIVE_DOUBLE, data, cols);
}

void Hdf5File::WriteInts(const std::string& name, const std::vector<std::int64_t>& data,
                         std::size_t cols) {
  Write(file_, path_, name, H5T_NATIVE_INT64, data, cols);
}

std::vector<double> Hdf5File::ReadDoubles(const std::string& name, std::size_t cols) const {
  return Read<double>(file_, path_, name, H5T_NATIVE_DOUBLE, cols);
}

std::vector<std::int64_t> Hdf5File::ReadInts(const std::string& name, std::size_t cols) const {
  return Read<std::int64_t>(file_, path_, name, H5T_NATIVE_INT64, cols);
}

void Hdf5File::WriteAttribute(const std::string& name, double value) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{H5Acreate2(file_, name.c_str(), H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT,
                         H5P_DEFAULT),
              H5Aclose};
  if (attr.id < 0 || H5Awrite(attr.id, H5T_NATIVE_DOUBLE, &value) < 0)
    throw Error(fmt::format("{}: cannot write attribute {}", path_, name));
}

double Hdf5File::ReadAttribute(const std::string& name) const {
  Handle attr{H5Aopen(file_, name.c_str(), H5P_DEFAULT), H5Aclose};
  double value = 0.0;
  if (attr.id < 0 || H5Aread(attr.id, H5T_NATIVE_DOUBLE, &value) < 0)
    throw Error(fmt::format("{}: missing attribute {}", path_, name));
  return value;
}

void Hdf5File::WriteText(const std::string& name, const std::string& value) {
  // A variable-length UTF-8 string, which h5dump and h5py show as text.
  Handle type{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(type.id, H5T_VARIABLE);
  H5Tset_cset(type.id, H5T_CSET_UTF8);
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{H5Acreate2(file_, name.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose};
  const char* text = value.c_str();
  if (attr.id < 0 || H5Awrite(attr.id, type.id, &text) < 0)
    throw Error(fmt::format("{}: cannot write attribute {}", path_, name));
}

std::string Hdf5File::ReadText(const std::string& name) const {
  Handle attr{H5Aopen(file_, name.c_str(), H5P_DEFAULT), H5Aclose};
  if (attr.id < 0) throw Error(fmt::format("{}: missing attribute {}", path_, name));
  Handle type{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(type.id, H5T_VARIABLE);
  H5Tset_cset(type.id, H5T_CSET_UTF8);
  char* text = nullptr;
  if (H5Aread(attr.id, type.id, &text) < 0 || text == nullptr)
    throw Error(fmt::format("{}: attribute {} is not text", path_, name));
  std::string value(text);
  H5free_memory(text);
  return value;
}

bool Hdf5File::HasAttribute(const std::string& name) const {
  return H5Aexists(file_, name.c_str()) > 0;
}

std::vector<std::string> Hdf5File::AttributeNames() const {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  if (H5Aiterate2(file_, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names) < 0)
    throw Error(fmt::format("{}: cannot list attributes", path_));
  return names;
}

}  // namespace fibrenet::io
