#include "engine/io/hdf5_file.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace fibrenet::io {
namespace {

std::vector<char> FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

// Save() writes the driver's own buffer, not a copy taken through H5Fget_file_image. The file
// must be what the library hands out for it: opened again, the library's image of the file
// is the file byte for byte (a superblock left marked open for writing would differ), and the
// data read back are the data written.
TEST(Hdf5File, ASavedFileIsTheLibrarysFinishedImageOfIt) {
  const std::string path = TempPath("fibrenet_hdf5_file_test.h5");
  std::vector<double> values(300000);  // 2.4 MB: the in-memory file grows past 1 MiB twice
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = 0.5 * static_cast<double>(k);
  {
    Hdf5File f(path, Hdf5File::Mode::kCreate);
    f.CreateGroup("g");
    f.WriteDoubles("g/values", values, 3);
    f.WriteInts("g/ids", {1, 2, 3, 4}, 2);
    f.WriteAttribute("time", 1.25);
    f.WriteText("scene", "tiny.toml");
    f.Save();
  }
  const std::vector<char> on_disk = FileBytes(path);
  ASSERT_GT(on_disk.size(), values.size() * sizeof(double));

  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const ssize_t size = H5Fget_file_image(file, nullptr, 0);
  std::vector<char> image(size > 0 ? static_cast<std::size_t>(size) : 0);
  ASSERT_EQ(H5Fget_file_image(file, image.data(), image.size()), size);
  H5Fclose(file);
  EXPECT_EQ(image, on_disk);

  const Hdf5File read(path, Hdf5File::Mode::kRead);
  EXPECT_EQ(read.ReadDoubles("g/values", 3), values);
  EXPECT_EQ(read.ReadInts("g/ids", 2), (std::vector<std::int64_t>{1, 2, 3, 4}));
  EXPECT_EQ(read.ReadAttribute("time"), 1.25);
  EXPECT_EQ(read.ReadText("scene"), "tiny.toml");
  std::filesystem::remove(path);
}

TEST(Hdf5File, AFileThatIsNotSavedLeavesNothingOnDisk) {
  const std::string path = TempPath("fibrenet_hdf5_unsaved_test.h5");
  std::filesystem::remove(path);
  {
    Hdf5File f(path, Hdf5File::Mode::kCreate);
    f.WriteDoubles("values", std::vector<double>(1000, 1.0), 1);
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(Hdf5File, SavingIntoAMissingFolderNamesTheFileAndTheCause) {
  const std::string path = TempPath("fibrenet_no_such_folder/out.h5");
  Hdf5File f(path, Hdf5File::Mode::kCreate);
  f.WriteDoubles("values", std::vector<double>(10, 1.0), 1);
  try {
    f.Save();
    FAIL() << "saved into a missing folder";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": cannot create the file: No such file"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace fibrenet::io
